/* lucent_mesh_paint: a picture of a mesh with per-vertex colours (the curvature maps of
 * `lucent curvature --out x.png`, like Kubo et al.'s Figure 10a), without a GPU: an orthographic
 * camera fitted to the bounding sphere, a z-buffer, colours interpolated across each triangle,
 * supersampled and box-filtered. Lit by a head light, 0.35 + 0.65 |n.v| with the interpolated
 * vertex normal, so the shape reads through the colours. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/image.h"
#include "lucent/mesh.h"

/* sRGB byte -> linear (IEC 61966-2-1). */
static float srgb_to_linear(uint8_t v)
{
    double c = v / 255.0;
    return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

/* The view: rows of the rotation taking world directions to camera (right, up, toward the eye). */
static void view_basis(double azimuth_deg, double elevation_deg, double dest[3][3])
{
    double a = azimuth_deg * M_PI / 180, e = elevation_deg * M_PI / 180;
    double z[3] = {sin(a) * cos(e), sin(e), cos(a) * cos(e)}; /* toward the eye */
    double x[3] = {cos(a), 0, -sin(a)};                       /* right, horizontal */
    double y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
    memcpy(dest[0], x, sizeof x), memcpy(dest[1], y, sizeof y), memcpy(dest[2], z, sizeof z);
}

typedef struct paint_job {
    int w, h;           /* supersampled size */
    float *depth, *rgb; /* w * h; w * h * 3 */
    double (*p)[3];     /* camera-space vertex positions, pixels for x and y */
    float (*c)[3];      /* linear vertex colours times shading */
} paint_job;

static double edge(const double *a, const double *b, double x, double y)
{
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

static void triangle(paint_job *j, const uint32_t *f)
{
    const double *a = j->p[f[0]], *b = j->p[f[1]], *c = j->p[f[2]];
    double area = edge(a, b, c[0], c[1]);
    if (!(fabs(area) > 1e-12)) return; /* degenerate or NaN */
    int x0 = (int)fmax(0, floor(fmin(a[0], fmin(b[0], c[0])))),
        x1 = (int)fmin(j->w - 1, ceil(fmax(a[0], fmax(b[0], c[0]))));
    int y0 = (int)fmax(0, floor(fmin(a[1], fmin(b[1], c[1])))),
        y1 = (int)fmin(j->h - 1, ceil(fmax(a[1], fmax(b[1], c[1]))));
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double px = x + 0.5, py = y + 0.5;
            double wa = edge(b, c, px, py) / area, wb = edge(c, a, px, py) / area, wc = 1 - wa - wb;
            if (wa < 0 || wb < 0 || wc < 0) continue;
            float z = (float)(wa * a[2] + wb * b[2] + wc * c[2]); /* larger: nearer the eye */
            size_t i = (size_t)y * (size_t)j->w + (size_t)x;
            if (z <= j->depth[i]) continue;
            j->depth[i] = z;
            for (int k = 0; k < 3; k++)
                j->rgb[3 * i + k] = (float)(wa * j->c[f[0]][k] + wb * j->c[f[1]][k] + wc * j->c[f[2]][k]);
        }
}

/* Camera-space positions (x, y in supersampled pixels, y down; z toward the eye) and shaded colours. */
static void project(const lucent_mesh *m, const lucent_mesh_paint_desc *d, paint_job *j)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, r = 0, v[3][3];
    for (size_t i = 0; i < m->vertex_count; i++)
        for (int k = 0; k < 3; k++)
            lo[k] = fmin(lo[k], m->positions[3 * i + k]), hi[k] = fmax(hi[k], m->positions[3 * i + k]);
    double centre[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    for (size_t i = 0; i < m->vertex_count; i++) {
        double dx = m->positions[3 * i] - centre[0], dy = m->positions[3 * i + 1] - centre[1];
        double dz = m->positions[3 * i + 2] - centre[2];
        r = fmax(r, sqrt(dx * dx + dy * dy + dz * dz));
    }
    view_basis(d->azimuth, d->elevation, v);
    double scale = 0.46 * fmin(j->w, j->h) / fmax(r, 1e-300); /* the bounding sphere fills 92% */
    for (size_t i = 0; i < m->vertex_count; i++) {
        double q[3], n[3];
        for (int k = 0; k < 3; k++) {
            q[k] = v[k][0] * (m->positions[3 * i] - centre[0]) + v[k][1] * (m->positions[3 * i + 1] - centre[1]) +
                   v[k][2] * (m->positions[3 * i + 2] - centre[2]);
            n[k] = v[k][0] * m->normals[3 * i] + v[k][1] * m->normals[3 * i + 1] + v[k][2] * m->normals[3 * i + 2];
        }
        double shade = 0.35 + 0.65 * fmin(fabs(n[2]), 1);
        j->p[i][0] = 0.5 * j->w + scale * q[0], j->p[i][1] = 0.5 * j->h - scale * q[1], j->p[i][2] = q[2];
        for (int k = 0; k < 3; k++) j->c[i][k] = (float)(shade * srgb_to_linear(d->colors[3 * i + k]));
    }
}

/* Averages s x s blocks of the supersampled picture into dest. */
static void resolve(const paint_job *j, int s, const float bg[3], lucent_image *dest)
{
    for (int y = 0; y < dest->height; y++)
        for (int x = 0; x < dest->width; x++)
            for (int k = 0; k < 3; k++) {
                double sum = 0;
                for (int sy = 0; sy < s; sy++)
                    for (int sx = 0; sx < s; sx++) {
                        size_t i = (size_t)(y * s + sy) * (size_t)j->w + (size_t)(x * s + sx);
                        sum += j->depth[i] > -INFINITY ? j->rgb[3 * i + k] : bg[k];
                    }
                lucent_image_set(dest, x, y, k, (float)(sum / (s * s)));
            }
}

lucent_status lucent_mesh_paint(const lucent_mesh *m, const lucent_mesh_paint_desc *desc, lucent_image **dest)
{
    *dest = NULL;
    lucent_mesh_paint_desc d = *desc;
    int w = d.width ? d.width : 800, h = d.height ? d.height : 800, s = d.supersample ? d.supersample : 3;
    if (!m || !d.colors || w < 1 || h < 1 || w > 16384 || h > 16384 || s < 1 || s > 8 || !isfinite(d.azimuth) ||
        !isfinite(d.elevation))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "mesh paint: a mesh, colours, 1..16384 pixels a side, "
                                                         "supersampling 1..8 and finite angles");
    /* Supersampling only as far as 64 Mpixels (about 1 GB of buffers): a 16384 x 16384 picture is drawn once
     * per pixel, not 3 x 3 (38.7 GB). */
    while (s > 1 && (double)w * h * s * s > (double)(1 << 26)) s--;
    lucent_status st = lucent_image_create(w, h, 3, dest);
    if (st != LUCENT_OK) return st;
    paint_job j = {.w = w * s, .h = h * s};
    size_t n = (size_t)j.w * (size_t)j.h;
    j.depth = malloc(n * sizeof *j.depth), j.rgb = malloc(3 * n * sizeof *j.rgb);
    j.p = malloc((m->vertex_count + 1) * sizeof *j.p), j.c = malloc((m->vertex_count + 1) * sizeof *j.c);
    if (!j.depth || !j.rgb || !j.p || !j.c) {
        st = lucent_error(LUCENT_ERR_OUT_OF_MEMORY,
                          "mesh paint: out of memory for a %d x %d picture (drawn %dx supersampled, %d x %d: %.1f GB)",
                          w, h, s, j.w, j.h, (double)n * (sizeof *j.depth + 3 * sizeof *j.rgb) / 1e9);
    } else {
        for (size_t i = 0; i < n; i++) j.depth[i] = -INFINITY;
        project(m, &d, &j);
        for (size_t f = 0; f < m->face_count; f++) triangle(&j, m->faces + 3 * f);
        resolve(&j, s, d.background, *dest);
    }
    free(j.depth), free(j.rgb), free(j.p), free(j.c);
    if (st != LUCENT_OK) lucent_image_destroy(*dest), *dest = NULL;
    return st;
}
