/* CPU reference of the Lambert and CDRF shading with the boundary's reflection (see reference.h). */
#include <math.h>

#include "base/optics.h"
#include "base/vec3.h"
#include "gl/reference/reference.h"

static double dot3(const double *a, const double *b) { return v3_dot(v3_load(a), v3_load(b)); }

static void normalise3(double *a) { v3_store(v3_normalize(v3_load(a)), a); }

double gl_ref_lut(const lucent_image *lut, double sigma_max, double cos_theta, double sigma)
{
    double x = (fmin(fmax(cos_theta, -1), 1) + 1) / 2 * (lut->width - 1);
    double y = fmin(fmax(sigma / sigma_max, 0), 1) * (lut->height - 1);
    int x0 = (int)fmin(floor(x), lut->width - 2), y0 = (int)fmin(floor(y), lut->height - 2);
    double fx = x - x0, fy = y - y0;
    const float *row0 = lut->data + (size_t)y0 * (size_t)lut->width, *row1 = row0 + lut->width;
    double top = (1 - fx) * row0[x0] + fx * row0[x0 + 1], bottom = (1 - fx) * row1[x0] + fx * row1[x0 + 1];
    return (1 - fy) * top + fy * bottom;
}

double gl_ref_boundary(const float *table, int c, double mu_i, double mu_o, bool exit)
{
    enum { N = LUCENT_BOUNDARY_BINS };
    double x = fmin(fmax(mu_o * N - 0.5, 0), N - 1), y = exit ? N : fmin(fmax(mu_i * N, 0.5), N - 0.5) - 0.5;
    int x0 = (int)fmin(floor(x), N - 2), y0 = exit ? N : (int)fmin(floor(y), N - 2);
    double fx = x - x0, fy = exit ? 0 : y - y0;
    const float *r0 = table + (size_t)y0 * N * 3, *r1 = exit ? r0 : r0 + N * 3;
    double top = (1 - fx) * r0[x0 * 3 + c] + fx * r0[(x0 + 1) * 3 + c];
    double bottom = (1 - fx) * r1[x0 * 3 + c] + fx * r1[(x0 + 1) * 3 + c];
    return (1 - fy) * top + fy * bottom;
}

/* The row of curvature kappa (surface.glsl's curved_row) and a bilinear read of the table's half
 * `half` (0: the exitance factor, 1: beta) at theta = acos(ndl). */
static double curved_read(const float *table, double r0, int c, double ndl, double kappa, int half)
{
    enum { NB = LUCENT_BAKE_SPHERE_BINS, NR = LUCENT_BAKE_SPHERE_RADII };
    double last = NR - 1, rmax = r0 * pow(2.0, 0.5 * last), k = fmax(kappa, 0);
    double y = k * rmax >= 1 ? fmin(fmax(2 * log2(1 / (k * r0)), 0), last) : last + (1 - k * rmax);
    double x = fmin(fmax(acos(fmin(fmax(ndl, -1), 1)) / M_PI * NB - 0.5, 0), NB - 1);
    int x0 = (int)fmin(floor(x), NB - 2), y0 = (int)fmin(floor(y), NR - 1);
    double fx = x - x0, fy = y - y0;
    const float *r0w = table + ((size_t)half * (NR + 1) + (size_t)y0) * NB * 3, *r1w = r0w + NB * 3;
    double top = (1 - fx) * r0w[x0 * 3 + c] + fx * r0w[(x0 + 1) * 3 + c];
    double bottom = (1 - fx) * r1w[x0 * 3 + c] + fx * r1w[(x0 + 1) * 3 + c];
    return (1 - fy) * top + fy * bottom;
}

double gl_ref_curved(const float *table, double r0, int c, double ndl, double kappa)
{
    return curved_read(table, r0, c, ndl, kappa, 0);
}

double gl_ref_curved_lean(const float *table, double r0, int c, const double n[3], const double l[3], const double v[3],
                          double kappa)
{
    double ndl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2], f[3], fl = 0, vf = 0;
    for (int i = 0; i < 3; i++) f[i] = n[i] * ndl - l[i], fl += f[i] * f[i];
    fl = sqrt(fl);
    if (fl > 1e-6) vf = (v[0] * f[0] + v[1] * f[1] + v[2] * f[2]) / fl;
    return fmax(1 + curved_read(table, r0, c, ndl, kappa, 1) * vf, 0);
}

/* Direction toward light l from p and the irradiance on a surface facing it. */
static double incident(const lucent_light *l, const double *p, double *dir)
{
    if (l->type == LUCENT_LIGHT_DIRECTIONAL) {
        for (int i = 0; i < 3; i++) dir[i] = -l->direction[i];
        return l->intensity;
    }
    for (int i = 0; i < 3; i++) dir[i] = l->position[i] - p[i];
    double d2 = fmax(dot3(dir, dir), 1e-12);
    normalise3(dir);
    return l->intensity / d2;
}

/* The rough boundary's reflection times cos_i, the tracer's (src/trace/bsdf.c, rough_reflect):
 * F(o.m) D(m) G1(i) G1(o) / (4 cos_i cos_o) (Walter et al. 2007 eqs. 20, 23, 33, 34) from
 * base/optics.h, alpha at least 1e-3 as the shader has it. */
static double boundary_reflection(const double *n, const double *v, const double *l, double alpha, double eta)
{
    double ci = dot3(n, l), co = dot3(n, v), h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]}, hh = dot3(h, h);
    if (ci <= 0 || co <= 0 || hh < 1e-12) return 0;
    double m[3] = {h[0] / sqrt(hh), h[1] / sqrt(hh), h[2] / sqrt(hh)}, om = dot3(v, m), a = fmax(alpha, 1e-3);
    if (om <= 0) return 0;
    double f = lucent_fresnel_dielectric(om, eta, NULL) * lucent_ggx_d(dot3(n, m), a) * lucent_ggx_g1(ci, a) *
               lucent_ggx_g1(co, a) / (4 * ci * co);
    return f * ci;
}

static double cdrf_value(lucent_cdrf_variant variant, const lucent_image *lut, double sigma_max, double ndl,
                         double sigma)
{
    sigma = fmin(fmax(sigma, 0), sigma_max);
    if (lut) return gl_ref_lut(lut, sigma_max, ndl, sigma);
    return lucent_cdrf_eval(variant, acos(fmin(fmax(ndl, -1), 1)), sigma);
}

void gl_ref_shade(const lucent_scene *scene, lucent_render_method method, lucent_cdrf_variant variant,
                  const lucent_image *lut, double sigma_max, const gl_ref_material *m, const gl_ref_point *p,
                  double diffuse[3], double specular[3])
{
    double v[3], e_sum[3] = {0}, ambient[3] = {0}, spec[3] = {0};
    for (int i = 0; i < 3; i++) v[i] = scene->camera.position[i] - p->position[i];
    normalise3(v);
    /* A normal seen from behind is bent toward the viewer until n.v = 0.01, as the shaders' face_viewer
     * (lights.glsl) */
    double n[3], c0 = dot3(p->normal, v);
    for (int i = 0; i < 3; i++) n[i] = c0 >= 0.01 ? p->normal[i] : p->normal[i] + (0.01 - c0) * v[i];
    normalise3(n);
    double mu_o = fmin(fmax(dot3(n, v), 0), 1);
    int k = 0; /* index among the non-environment lights (the visibility array's order) */
    for (int i = 0; i < scene->light_count; i++) {
        const lucent_light *l = &scene->lights[i];
        if (l->type == LUCENT_LIGHT_ENVIRONMENT) {
            for (int c = 0; c < 3; c++) ambient[c] += l->intensity * l->color[c];
            continue;
        }
        double dir[3], e = incident(l, p->position, dir), ndl = dot3(n, dir);
        double vis = p->visibility ? p->visibility[k] : 1, s = boundary_reflection(n, v, dir, m->roughness, m->eta);
        for (int c = 0; c < 3; c++) {
            double f = method == LUCENT_METHOD_LAMBERT ? fmax(ndl, 0)
                       : m->spheres
                           ? gl_ref_curved(m->spheres, m->sphere_r0, c, ndl, p->curvature)          /* curved parts */
                           : cdrf_value(variant, lut, sigma_max, ndl, m->sigma0[c] * p->curvature); /* Kubo 4-5 */
            double lean = m->spheres ? gl_ref_curved_lean(m->spheres, m->sphere_r0, c, n, dir, v, p->curvature) : 1;
            e_sum[c] += e * l->color[c] * f * vis * gl_ref_boundary(m->boundary, c, fmax(ndl, 0), mu_o, false) * lean;
            spec[c] += e * l->color[c] * vis * s;
        }
        k++;
    }
    /* the diffuse light leaves toward the viewer by the boundary's exit curve (docs/render.md) */
    for (int c = 0; c < 3; c++) {
        diffuse[c] = gl_ref_boundary(m->boundary, c, 0, mu_o, true) * m->albedo[c] * (e_sum[c] / M_PI + ambient[c]);
        specular[c] = spec[c];
    }
}
