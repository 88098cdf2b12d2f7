/* The library's one copy of the optics of dielectric boundaries and scattering media (internal),
 * in the manner of pbrt-v4's util/scattering.h: the unpolarised Fresnel term, refraction and
 * reflection, the GGX microfacet distribution with Smith masking and its visible-normal sampling,
 * the pieces of Walter et al.'s rough dielectric, the Henyey-Greenstein phase function, and the
 * orthonormal basis these are built on. The path tracer (src/trace), the CDRF sphere simulation
 * (src/cdrf/sphere_mc.c) and the photon Monte Carlo (src/profile/mc_transport.c) all call these.
 *
 * Conventions.
 *   - eta = n_t / n_i: the index on the far side over the index on the incident side.
 *   - Travel directions (d) point along the light's path; directions named o, i, v point away
 *     from the surface (o toward the viewer, i toward the light), as in Walter et al. 2007.
 *   - Cosines are of angles to the normal on the incident side, in [0, 1].
 *   - Double precision throughout; where the callers run in float (the photon Monte Carlo's
 *     Henyey-Greenstein sampling, the curvature's first pass) a float variant (suffix _f) has the
 *     same formula.
 *
 * References.
 *   [BW]  Born & Wolf, Principles of Optics (7th ed. 1999), section 1.5.2, eqs. 20-21 (Fresnel).
 *   [W07] Walter, Marschner, Li & Torrance 2007, "Microfacet models for refraction through rough
 *         surfaces", EGSR.
 *   [H14] Heitz 2014, "Understanding the masking-shadowing function in microfacet-based BRDFs",
 *         JCGT 3(2).
 *   [H18] Heitz 2018, "Sampling the GGX distribution of visible normals", JCGT 7(4).
 *   [HG]  Henyey & Greenstein 1941, "Diffuse radiation in the galaxy", ApJ 93; Freude (2.4).
 *   [D17] Duff, Burgess, Christensen, Hery, Kensler, Liani & Villemin 2017, "Building an
 *         orthonormal basis, revisited", JCGT 6(1).
 *   [MCML] Wang & Jacques, the MCML manual, chapter 3. */
#ifndef LUCENT_BASE_OPTICS_H
#define LUCENT_BASE_OPTICS_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "base/vec3.h"

/* ---- frames ---- */

/* An orthonormal, right-handed basis (t, b, n) around unit n: t x b = n ([D17] Listing 3,
 * branch-free but for the sign of n.z; n.z = -0 counts as positive). */
static inline void lucent_basis(v3 n, v3 *t, v3 *b)
{
    double s = n.z >= 0 ? 1.0 : -1.0, a = -1.0 / (s + n.z), c = n.x * n.y * a;
    *t = (v3){1.0 + s * n.x * n.x * a, s * c, -s * n.x};
    *b = (v3){c, s + n.y * n.y * a, -n.y};
}

/* The same basis in float, on arrays, for the curvature's float pass (src/mesh). */
static inline void lucent_basis_f(const float n[3], float t[3], float b[3])
{
    float s = n[2] >= 0 ? 1.0f : -1.0f, a = -1.0f / (s + n[2]), c = n[0] * n[1] * a;
    t[0] = 1.0f + s * n[0] * n[0] * a, t[1] = s * c, t[2] = -s * n[0];
    b[0] = c, b[1] = s + n[1] * n[1] * a, b[2] = -n[1];
}

/* Local coordinates (x, y, z) of w in the frame (t, b, n), and back. */
static inline v3 lucent_to_local(v3 w, v3 t, v3 b, v3 n) { return (v3){v3_dot(w, t), v3_dot(w, b), v3_dot(w, n)}; }
static inline v3 lucent_from_local(v3 l, v3 t, v3 b, v3 n)
{
    return v3_add(v3_add(v3_scale(t, l.x), v3_scale(b, l.y)), v3_scale(n, l.z));
}

/* The unit direction at cosine mu from unit axis n, at azimuth phi in n's basis. */
static inline v3 lucent_around(v3 n, double mu, double phi)
{
    v3 t, b;
    lucent_basis(n, &t, &b);
    double s = sqrt(lucent_at_least(0.0, 1.0 - mu * mu));
    return v3_normalize(lucent_from_local((v3){s * cos(phi), s * sin(phi), mu}, t, b, n));
}

/* ---- smooth dielectric boundaries ---- */

/* Unpolarised Fresnel reflectance for incidence cosine cos_i in [0, 1] and eta = n_t / n_i: the
 * mean of the s and p reflectances ([BW] eqs. 21a, 21b divided through by n_i)
 *   r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t),  r_p = (cos_t - eta cos_i) / (cos_t + eta cos_i),
 * with cos_t from Snell's law, sin_t = sin_i / eta. Returns 1 under total internal reflection and
 * exactly 0 for eta == 1 (index matched: no rounding residue). When cos_t is not NULL it receives
 * the cosine of the refracted angle (0 under total internal reflection). */
static inline double lucent_fresnel_dielectric(double cos_i, double eta, double *cos_t)
{
    if (eta == 1.0) {
        if (cos_t) *cos_t = cos_i;
        return 0.0;
    }
    double st2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if (st2 >= 1.0) {
        if (cos_t) *cos_t = 0.0;
        return 1.0;
    }
    double ct = sqrt(1.0 - st2);
    if (cos_t) *cos_t = ct;
    double rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (ct - eta * cos_i) / (ct + eta * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

/* The cosine-weighted hemispherical mean of the transmittance 1 - F of light arriving from the outside,
 * 2 int_0^1 (1 - F(mu)) mu dmu (midpoint rule, 512 steps; 1 for eta == 1): the factor that
 * normalises F_t(w) in Jensen et al. 2001's S_d = F_t(w_i) R_d F_t(w_o) / pi, so that the diffuse
 * reflectance of uniform light stays the material's R_d. */
static inline double lucent_fresnel_mean_transmittance(double eta)
{
    double sum = 0;
    for (int k = 0; k < 512; k++) {
        double mu = (k + 0.5) / 512;
        sum += (1.0 - lucent_fresnel_dielectric(mu, eta, NULL)) * mu;
    }
    return 2.0 * sum / 512;
}

/* Refracts the travel direction d (unit) through a surface with unit normal m on the incident
 * side (m . d < 0), eta = n_t / n_i: t = d / eta + (cos_i / eta - cos_t) m ([W07] section 5.3, with
 * i = -d). Returns false under total internal reflection. */
static inline bool lucent_refract(v3 d, v3 m, double eta, v3 *dest)
{
    double r = 1.0 / eta, ci = -v3_dot(m, d), st2 = r * r * (1.0 - ci * ci);
    if (st2 >= 1.0) return false;
    *dest = v3_normalize(v3_madd(v3_scale(d, r), m, r * ci - sqrt(1.0 - st2)));
    return true;
}

/* Mirrors the travel direction d at unit normal m: d - 2 (d . m) m ([W07] section 5.3, with i = -d). */
static inline v3 lucent_reflect(v3 d, v3 m) { return v3_madd(d, m, -2.0 * v3_dot(d, m)); }

/* ---- GGX microfacets ([W07] section 5.2) ---- */

/* The GGX distribution of normals D(m) for cos_m = m . n ([W07] eq. 33); 0 for cos_m <= 0. */
static inline double lucent_ggx_d(double cos_m, double alpha)
{
    if (cos_m <= 0) return 0;
    double a2 = alpha * alpha, k = cos_m * cos_m * (a2 - 1.0) + 1.0;
    return a2 / (M_PI * k * k);
}

/* Smith masking G1 of GGX for a direction at cosine c to the macro normal ([W07] eq. 34, the
 * microfacet's own side test left to the caller):
 *   G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)). */
static inline double lucent_ggx_g1(double c, double alpha)
{
    c = fabs(c);
    if (c >= 1.0) return 1.0;
    if (c <= 0.0) return 0.0;
    double tan2 = (1.0 - c * c) / (c * c);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

/* Samples a microfacet normal from the distribution of normals visible from v (unit, v . n > 0)
 * about unit normal n, D_v(m) = G1(v) max(0, v . m) D(m) / (v . n) ([H18] eq. 2, Listing 1): stretch
 * v to the hemisphere configuration, sample the projected disc (half of it warped by the visible
 * fraction), lift to the hemisphere and unstretch. u1, u2 uniform in [0, 1). */
static inline v3 lucent_ggx_sample_visible(v3 v, v3 n, double alpha, double u1, double u2)
{
    v3 t, b;
    lucent_basis(n, &t, &b);
    v3 lv = lucent_to_local(v, t, b, n);
    v3 vh = v3_normalize(v3_make(alpha * lv.x, alpha * lv.y, lv.z));
    double len2 = vh.x * vh.x + vh.y * vh.y;
    v3 t1 = len2 > 0 ? v3_scale(v3_make(-vh.y, vh.x, 0), 1.0 / sqrt(len2)) : v3_make(1, 0, 0);
    v3 t2 = v3_cross(vh, t1);
    double r = sqrt(u1), phi = 2.0 * M_PI * u2, s = 0.5 * (1.0 + vh.z);
    double p1 = r * cos(phi), p2 = r * sin(phi);
    p2 = (1.0 - s) * sqrt(lucent_at_least(0.0, 1.0 - p1 * p1)) + s * p2;
    double p3 = sqrt(lucent_at_least(0.0, 1.0 - p1 * p1 - p2 * p2));
    v3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, p3));
    v3 m = v3_normalize(v3_make(alpha * nh.x, alpha * nh.y, lucent_at_least(1e-12, nh.z)));
    return lucent_from_local(m, t, b, n);
}

/* The density of lucent_ggx_sample_visible producing m: D_v(m) = G1(v) max(0, v . m) D(m) / (v . n). */
static inline double lucent_ggx_visible_pdf(v3 v, v3 n, v3 m, double alpha)
{
    double vn = v3_dot(v, n), vm = v3_dot(v, m);
    if (vn <= 0 || vm <= 0) return 0;
    return lucent_ggx_g1(vn, alpha) * vm * lucent_ggx_d(v3_dot(m, n), alpha) / vn;
}

/* The half vector of a reflection from o to i ([W07] eq. 13): normalize(o + i). */
static inline v3 lucent_ggx_half_reflect(v3 o, v3 i) { return v3_normalize(v3_add(o, i)); }

/* The half vector of a refraction between o (index eta_o) and i (index eta_i) ([W07] eq. 16),
 * -normalize(eta_o o + eta_i i), turned to the side of the macro normal n. */
static inline v3 lucent_ggx_half_transmit(v3 o, v3 i, double eta_o, double eta_i, v3 n)
{
    v3 m = v3_normalize(v3_neg(v3_add(v3_scale(i, eta_i), v3_scale(o, eta_o))));
    return v3_dot(m, n) < 0 ? v3_neg(m) : m;
}

/* |d omega_m / d omega_i| of a reflection at m, o . m = om > 0 ([W07] eq. 14): 1 / (4 om). */
static inline double lucent_ggx_jacobian_reflect(double om) { return 1.0 / (4.0 * om); }

/* |d omega_m / d omega_i| of a refraction at m with om = o . m, im = i . m ([W07] eq. 17, with i
 * the direction the sample produces): eta_i^2 |im| / (eta_i im + eta_o om)^2; 0 when degenerate. */
static inline double lucent_ggx_jacobian_transmit(double om, double im, double eta_o, double eta_i)
{
    double den = eta_i * im + eta_o * om, den2 = den * den;
    return den2 > 0 ? eta_i * eta_i * fabs(im) / den2 : 0.0;
}

/* ---- Henyey-Greenstein ([HG]) ----
 * mu is the cosine between the travel directions before and after scattering; g the mean cosine. */

/* The phase function p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)) ([HG] eq. 3, Freude (2.4)). */
static inline double lucent_hg_phase(double mu, double g)
{
    double k = 1.0 + g * g - 2.0 * g * mu;
    return (0.25 * M_1_PI) * (1.0 - g * g) / (k * sqrt(k));
}

/* mu drawn from p by inverting its cumulative distribution ([MCML] eq. 3.28):
 *   mu = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g),   mu = 2u - 1 for |g| < 1e-6,
 * clamped to [-1, 1]; |g| >= 1 gives sign(g) (the delta limit). u uniform in [0, 1). */
static inline double lucent_hg_sample_cos(double g, double u)
{
    if (fabs(g) < 1e-6) return 2.0 * u - 1.0;
    if (fabs(g) >= 1.0) return g > 0 ? 1.0 : -1.0;
    double q = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return lucent_at_least(-1.0, lucent_at_most(1.0, (1.0 + g * g - q * q) / (2.0 * g)));
}

/* A new travel direction after scattering from travel direction d (unit): mu from
 * lucent_hg_sample_cos(g, u1), azimuth 2 pi u2. */
static inline v3 lucent_hg_sample(v3 d, double g, double u1, double u2)
{
    return lucent_around(d, lucent_hg_sample_cos(g, u1), 2.0 * M_PI * u2);
}

/* The same inversion in float for the photon Monte Carlo, its constants prepared once per
 * medium (0 < |g| < 1; the caller keeps g = 0 and |g| near 0 or 1 on the double path):
 * mu = (a - t^2) e, t = b / (c + d u). */
typedef struct lucent_hg_f {
    float a, b, c, d, e; /* 1 + g^2, 1 - g^2, 1 - g, 2 g, 1 / (2 g) */
} lucent_hg_f;

static inline lucent_hg_f lucent_hg_prepare_f(double g)
{
    return (lucent_hg_f){(float)(1.0 + g * g), (float)(1.0 - g * g), (float)(1.0 - g), (float)(2.0 * g),
                         g != 0.0 ? (float)(1.0 / (2.0 * g)) : 0.0f};
}

static inline float lucent_hg_sample_cos_f(const lucent_hg_f *h, float u)
{
    float t = h->b / (h->c + h->d * u), c = (h->a - t * t) * h->e;
    return c < -1.0f ? -1.0f : c > 1.0f ? 1.0f : c;
}

#endif
