/* The camera: view and projection matrices (OpenGL conventions) and the matching primary rays,
 * so that the GL renderer and the path tracer see exactly the same image. */
#include <math.h>
#include <string.h>

#include "lucent/scene.h"
#include "scene/internal.h"

/* The camera's orthonormal frame: right, up and back (eye space looks down -back). */
static void camera_frame(const lucent_camera *cam, double right[3], double up[3], double back[3])
{
    scene_v3_sub(cam->position, cam->target, back);
    scene_v3_normalize(back);
    scene_v3_cross(cam->up, back, right);
    if (scene_v3_normalize(right) == 0) { /* up parallel to the view: pick any perpendicular */
        double alt[3] = {fabs(back[0]) < 0.9 ? 1 : 0, fabs(back[0]) < 0.9 ? 0 : 1, 0};
        scene_v3_cross(alt, back, right);
        scene_v3_normalize(right);
    }
    scene_v3_cross(back, right, up);
}

void lucent_camera_view(const lucent_camera *cam, double dest[16])
{
    double r[3], u[3], b[3];
    camera_frame(cam, r, u, b);
    memset(dest, 0, 16 * sizeof *dest);
    for (int i = 0; i < 3; i++) {
        dest[4 * i + 0] = r[i]; /* column i, rows 0..2: the frame's rows */
        dest[4 * i + 1] = u[i];
        dest[4 * i + 2] = b[i];
    }
    dest[12] = -scene_v3_dot(r, cam->position);
    dest[13] = -scene_v3_dot(u, cam->position);
    dest[14] = -scene_v3_dot(b, cam->position);
    dest[15] = 1;
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

void lucent_camera_ray(const lucent_camera *cam, int width, int height, double px, double py,
                       double origin[3], double dir[3])
{
    double r[3], u[3], b[3];
    camera_frame(cam, r, u, b);
    double t = tan(0.5 * cam->fov_y * M_PI / 180), aspect = (double)width / height;
    double sx = (2 * px / width - 1) * t * aspect; /* normalised device x times the frustum slope */
    double sy = (1 - 2 * py / height) * t;         /* y from the top row: +1 at the top edge */
    for (int i = 0; i < 3; i++) {
        origin[i] = cam->position[i];
        dir[i] = sx * r[i] + sy * u[i] - b[i];
    }
    scene_v3_normalize(dir);
}
