/* The CPU references of the renderer's passes, written separately in double precision and free of
 * GL: the scene pass's shading (shading.c: what one surface point gives for Lambert and the CDRF,
 * LUT or function, with the boundary's GGX reflection (the tracer's) and its entry factor and exit
 * curve; the tests feed it the GPU's own normal,
 * curvature and position and compare pixel by pixel) and the separable blur (blur_cpu.c:
 * lucent_ssss_blur_cpu of lucent/render.h). */
#ifndef LUCENT_SRC_GL_REFERENCE_REFERENCE_H
#define LUCENT_SRC_GL_REFERENCE_REFERENCE_H

#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "lucent/profile.h"
#include "lucent/render.h"
#include "lucent/scene.h"

/* A shaded point: where it is, its shading normal (unit, facing the viewer's side), its mean
 * curvature (mm^-1), and the shadow visibility of each light (NULL: all 1). */
typedef struct gl_ref_point {
    double position[3];
    double normal[3];
    double curvature;
    const double *visibility;
} gl_ref_point;

/* What the renderer uses for an object. */
typedef struct gl_ref_material {
    double albedo[3];
    double sigma0[3];
    double roughness, eta; /* the boundary: GGX alpha and the material's index */
    const float *boundary; /* the boundary's entry factors and exit curve (lucent_baked.boundary) */
    const float *spheres;  /* curved parts (lucent_baked.spheres; NULL: the CDRF or Lambert alone) */
    double sphere_r0;      /* mm: the spheres' first radius (lucent_baked.sphere_r0) */
} gl_ref_material;

/* The curved parts' factor of channel c for n.l = ndl and mean curvature kappa from table
 * (lucent_baked.spheres), read as surface.glsl's curved_factor reads its texture. */
double gl_ref_curved(const float *table, double r0, int c, double ndl, double kappa);

/* How light from unit l leaves toward unit v at normal n: 1 + beta v . f (surface.glsl's curved_lean). */
double gl_ref_curved_lean(const float *table, double r0, int c, const double n[3], const double l[3], const double v[3],
                          double kappa);

/* The boundary's entry factor A(mu_i, mu_o) (exit < 0) or exit curve E(mu_o) (exit >= 0) of channel c
 * from table (lucent_baked.boundary), read bilinearly between the bins' centres as the GPU's
 * boundary.glsl reads its texture. */
double gl_ref_boundary(const float *table, int c, double mu_i, double mu_o, bool exit);

/* Bilinear read of the CDRF LUT (lucent_cdrf_lut_build's layout: samples on the end points). */
double gl_ref_lut(const lucent_image *lut, double sigma_max, double cos_theta, double sigma);

/* The diffuse and specular radiance of point p under the scene's lights for method (lambert or
 * cdrf; lut NULL: the exact function of `variant`), sigma clamped to [0, sigma_max]. */
void gl_ref_shade(const lucent_scene *scene, lucent_render_method method, lucent_cdrf_variant variant,
                  const lucent_image *lut, double sigma_max, const gl_ref_material *m, const gl_ref_point *p,
                  double diffuse[3], double specular[3]);

/* Checks the arguments of lucent_ssss_blur_cpu / _gl; messages name what is wrong. */
lucent_status gl_blur_check_args(const lucent_image *irradiance, const lucent_image *depth, const uint8_t *material,
                                 const lucent_ssss_blur_desc *desc, const lucent_image *dest);

#endif
