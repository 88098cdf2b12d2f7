/* The camera: view and projection matrices (OpenGL conventions) and the matching primary rays,
 * so that the GL renderer and the path tracer see exactly the same image. */
#include <math.h>
#include <string.h>

#include "lucent/scene.h"
#include "scene/internal.h"

/* The camera's orthonormal frame: right, up and back (eye space looks down -back). */
static void camera_frame(const lucent_camera *cam, v3 *right, v3 *up, v3 *back)
{
    *back = v3_normalize(v3_sub(v3_load(cam->position), v3_load(cam->target)));
    *right = v3_normalize(v3_cross(v3_load(cam->up), *back));
    if (v3_dot(*right, *right) == 0) { /* up parallel to the view: pick any perpendicular */
        v3 alt = fabs(back->x) < 0.9 ? v3_make(1, 0, 0) : v3_make(0, 1, 0);
        *right = v3_normalize(v3_cross(alt, *back));
    }
    *up = v3_cross(*back, *right);
}

void lucent_camera_view(const lucent_camera *cam, double dest[16])
{
    v3 r, u, b, p = v3_load(cam->position);
    camera_frame(cam, &r, &u, &b);
    /* columns 0..2, rows 0..2: the frame's rows; column 3: the eye moved to the origin */
    const double m[16] = {r.x, u.x, b.x, 0, r.y,           u.y,           b.y,           0,
                          r.z, u.z, b.z, 0, -v3_dot(r, p), -v3_dot(u, p), -v3_dot(b, p), 1};
    memcpy(dest, m, sizeof m);
}

void lucent_camera_projection(const lucent_camera *cam, double aspect, double dest[16])
{
    double f = 1 / tan(0.5 * cam->fov_y * M_PI / 180), n = cam->near_plane, fa = cam->far_plane;
    memset(dest, 0, 16 * sizeof *dest);
    dest[0] = f / aspect;
    dest[5] = f;
    dest[10] = (fa + n) / (n - fa);
    dest[11] = -1;
    dest[14] = 2 * fa * n / (n - fa);
}

void lucent_camera_ray(const lucent_camera *cam, int width, int height, double px, double py, double origin[3],
                       double dir[3])
{
    v3 r, u, b;
    camera_frame(cam, &r, &u, &b);
    double t = tan(0.5 * cam->fov_y * M_PI / 180), aspect = (double)width / height;
    double sx = (2 * px / width - 1) * t * aspect; /* normalised device x times the frustum slope */
    double sy = (1 - 2 * py / height) * t;         /* y from the top row: +1 at the top edge */
    memcpy(origin, cam->position, 3 * sizeof *origin);
    v3_store(v3_normalize(v3_sub(v3_add(v3_scale(r, sx), v3_scale(u, sy)), b)), dir);
}

bool lucent_camera_project(const lucent_camera *cam, int width, int height, const double point[3], double *px,
                           double *py, double *cos_axis)
{
    v3 r, u, b, v = v3_sub(v3_load(point), v3_load(cam->position));
    camera_frame(cam, &r, &u, &b);
    double z = -v3_dot(v, b), len = v3_length(v);
    if (!(z > 0) || !(len > 0)) return false;
    double t = tan(0.5 * cam->fov_y * M_PI / 180), aspect = (double)width / height;
    double sx = v3_dot(v, r) / z, sy = v3_dot(v, u) / z; /* lucent_camera_ray's sx, sy, inverted */
    *px = (sx / (t * aspect) + 1) * 0.5 * width;
    *py = (1 - sy / t) * 0.5 * height;
    *cos_axis = z / len;
    return *px >= 0 && *px < width && *py >= 0 && *py < height;
}
