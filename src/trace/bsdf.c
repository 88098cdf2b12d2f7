/* Dielectric boundaries: Fresnel (smooth, with total internal reflection) and GGX microfacet
 * reflection and transmission after Walter, Marschner, Li & Torrance 2007, "Microfacet models for
 * refraction through rough surfaces" (EGSR), with the separable Smith masking-shadowing
 * G = G1(i) G1(o) (Walter eq. 23), the form the CDRF sphere simulation uses too, and sampling of
 * the visible normals (Heitz 2018, "Sampling the GGX distribution of visible normals", JCGT 7(4)).
 * The optics themselves (Fresnel, refraction, D, G1, the visible-normal sampler, half vectors and
 * Jacobians) are the library's one copy in base/optics.h; this file assembles the BSDF.
 *
 * Directions o (toward the viewer) and i (toward the light) point away from the surface; n is the
 * outward normal; the outside has index 1, the medium index eta. */
#include <math.h>

#include "trace/internal.h"

/* Reflection (Walter eq. 20) and its sampling density (eq. 14 with visible-normal sampling). */
static double rough_reflect(const tr_boundary *b, v3 no, v3 o, v3 i, double eta_o, double eta_t, double *pdf)
{
    v3 m = lucent_ggx_half_reflect(o, i);
    double om = v3_dot(o, m), co = v3_dot(o, no), ci = v3_dot(i, no);
    if (om <= 0 || v3_dot(m, no) <= 0) return 0;
    double F = lucent_fresnel_dielectric(om, eta_t / eta_o, NULL), D = lucent_ggx_d(v3_dot(m, no), b->alpha);
    double G = lucent_ggx_g1(co, b->alpha) * lucent_ggx_g1(ci, b->alpha);
    *pdf = lucent_ggx_visible_pdf(o, no, m, b->alpha) * F * lucent_ggx_jacobian_reflect(om);
    return F * D * G / (4.0 * co * ci);
}

/* Transmission (Walter eq. 21, radiance convention) and its density (eq. 17 with visible normals). */
static double rough_transmit(const tr_boundary *b, v3 no, v3 o, v3 i, double eta_o, double eta_i, double *pdf)
{
    v3 m = lucent_ggx_half_transmit(o, i, eta_o, eta_i, no);
    double om = v3_dot(o, m), im = v3_dot(i, m), co = v3_dot(o, no), ci = -v3_dot(i, no);
    if (om <= 0 || im >= 0 || !(v3_dot(m, no) > 0)) return 0;
    double F = lucent_fresnel_dielectric(om, eta_i / eta_o, NULL);
    if (F >= 1.0) return 0;
    double D = lucent_ggx_d(v3_dot(m, no), b->alpha), G = lucent_ggx_g1(co, b->alpha) * lucent_ggx_g1(ci, b->alpha);
    double den = eta_i * im + eta_o * om, den2 = den * den;
    if (!(den2 > 0)) return 0;
    *pdf = lucent_ggx_visible_pdf(o, no, m, b->alpha) * (1.0 - F) * lucent_ggx_jacobian_transmit(om, im, eta_o, eta_i);
    return fabs(im) * om / (co * ci) * eta_o * eta_o * (1.0 - F) * D * G / den2;
}

/* ---- Blender 3.x Cycles' Glass BSDF (render.boundary_model = cycles3): a peer's convention ----
 * As Blender 3.4 builds it (intern/cycles/kernel/svm/closure.h, the GGX glass case, and
 * closure/bsdf_microfacet.h, read from the sources Debian's blender 3.4.1 ships): two closures, a
 * GGX reflection with no Fresnel factor of its own, weighted by F = Fresnel(macro normal . view
 * direction), and a GGX refraction weighted by R = max(1e-4, 1 - F), picked in proportion to F and
 * R. The refraction's value uses the half vector of the pair, h = -(eta_i i + eta_o o), with |cos|
 * everywhere: no check that the implied microfacet faces the viewer and the medium as a refraction
 * needs (Walter's eq. 21 and Lucent's walter model are zero there). Masking is separable Smith G1 of
 * the macro angles, as in walter. A sampled refraction that meets total internal reflection at its
 * microfacet is lost (the refraction closure gives nothing). Cycles' BTDF carries no radiance
 * scaling ((eta_i / eta_o)^2 times Walter's); this one keeps Lucent's radiance convention, which
 * changes nothing seen from outside (the factors of entering and leaving cancel). Densities are those
 * of the sampler here (zero for the invalid pairs it never produces), for Lucent's MIS. */
static double cycles3_eval(const tr_boundary *b, v3 no, v3 o, v3 i, double eta_o, double eta_other, double *pdf)
{
    double co = v3_dot(o, no), ci = v3_dot(i, no);
    double F = lucent_fresnel_dielectric(co, eta_other / eta_o, NULL), R = lucent_at_least(1e-4, 1.0 - F), W = F + R;
    double g = lucent_ggx_g1(co, b->alpha) * lucent_ggx_g1(fabs(ci), b->alpha);
    if (ci > 0) { /* reflection closure (bsdf_microfacet_ggx_eval_reflect): F D G / (4 co ci) */
        v3 m = lucent_ggx_half_reflect(o, i);
        double om = v3_dot(o, m);
        *pdf = om > 0 ? F / W * lucent_ggx_visible_pdf(o, no, m, b->alpha) * lucent_ggx_jacobian_reflect(om) : 0.0;
        return F * lucent_ggx_d(fabs(v3_dot(m, no)), b->alpha) * g / (4.0 * co * ci);
    }
    /* refraction closure (bsdf_microfacet_ggx_eval_transmit), eta_i the light's side */
    double eta_i = eta_other;
    v3 h = v3_neg(v3_add(v3_scale(i, eta_i), v3_scale(o, eta_o)));
    double h2 = v3_dot(h, h);
    if (!(h2 > 0)) return 0;
    v3 m = v3_scale(h, 1.0 / sqrt(h2));
    if (v3_dot(m, no) < 0) m = v3_neg(m);
    double om = v3_dot(o, m), im = v3_dot(i, m), D = lucent_ggx_d(v3_dot(m, no), b->alpha);
    *pdf = om > 0 && im < 0
               ? R / W * lucent_ggx_visible_pdf(o, no, m, b->alpha) * lucent_ggx_jacobian_transmit(om, im, eta_o, eta_i)
               : 0.0;
    return R * fabs(im) * fabs(om) * eta_o * eta_o * D * g / (co * fabs(ci) * h2);
}

/* Cycles 3.x's sampling (bsdf_microfacet_ggx_sample with the closure picked by weight): a visible
 * normal m; reflect with probability F / (F + R), else refract through m (lost under total internal
 * reflection at m, or on the wrong side of the surface). The weight is (F + R) G1(i) (eta_o / eta_t)^2
 * for refraction: Cycles' eval / pdf over its two closures, in the radiance convention. */
static bool sample_cycles3(const tr_boundary *b, v3 n, v3 no, v3 o, double eta_o, double eta_t, double u0, double u1,
                           double u2, tr_bsdf_sample *dest)
{
    double F = lucent_fresnel_dielectric(v3_dot(o, no), eta_t / eta_o, NULL), R = lucent_at_least(1e-4, 1.0 - F),
           W = F + R;
    v3 m = lucent_ggx_sample_visible(o, no, b->alpha, u1, u2);
    *dest = (tr_bsdf_sample){.weight = W, .scale = 1.0};
    if (u0 * W < F) {
        dest->i = lucent_reflect(v3_neg(o), m);
        if (v3_dot(dest->i, no) <= 0) return false;
    } else {
        if (!lucent_refract(v3_neg(o), m, eta_t / eta_o, &dest->i) || v3_dot(dest->i, no) >= 0) return false;
        dest->transmit = true;
        dest->scale = (eta_o / eta_t) * (eta_o / eta_t);
        dest->weight *= dest->scale;
    }
    dest->weight *= lucent_ggx_g1(fabs(v3_dot(dest->i, no)), b->alpha);
    tr_bsdf_eval(b, n, o, dest->i, &dest->pdf);
    return dest->pdf > 0 && dest->weight > 0;
}

double tr_bsdf_eval(const tr_boundary *b, v3 n, v3 o, v3 i, double *pdf)
{
    *pdf = 0;
    if (b->kind != TR_BOUNDARY_ROUGH) return 0;
    double co = v3_dot(o, n), ci = v3_dot(i, n);
    if (co == 0 || ci == 0) return 0;
    v3 no = co > 0 ? n : v3_neg(n); /* the normal on o's side */
    double eta_o = co > 0 ? 1.0 : b->eta, eta_other = co > 0 ? b->eta : 1.0;
    double f = b->cycles3    ? cycles3_eval(b, no, o, i, eta_o, eta_other, pdf)
               : co * ci > 0 ? rough_reflect(b, no, o, i, eta_o, eta_other, pdf)
                             : rough_transmit(b, no, o, i, eta_o, eta_other, pdf);
    /* cycles3 has values where its sampler has no density (the invalid transmitted pairs) */
    if (!(f > 0) || !isfinite(f) || (!(*pdf > 0) && !b->cycles3)) {
        *pdf = 0;
        return 0;
    }
    if (!(*pdf > 0)) *pdf = 0;
    return f;
}

/* Smooth boundary: reflect with probability F, else refract (weight (eta_o / eta_i)^2). */
static bool sample_smooth(v3 no, v3 o, double eta_o, double eta_t, double u0, tr_bsdf_sample *dest)
{
    double co = v3_dot(o, no), F = lucent_fresnel_dielectric(co, eta_t / eta_o, NULL);
    *dest = (tr_bsdf_sample){.weight = 1.0, .delta = true, .scale = 1.0};
    if (u0 < F || !lucent_refract(v3_neg(o), no, eta_t / eta_o, &dest->i)) {
        dest->i = lucent_reflect(v3_neg(o), no);
        return true;
    }
    dest->transmit = true;
    dest->weight = dest->scale = (eta_o / eta_t) * (eta_o / eta_t);
    return true;
}

/* Rough boundary: a visible normal, then reflect with probability F(o . m) or refract; the weight
 * f |cos i| / pdf reduces to G1(i) (eta_o / eta_i)^2. */
static bool sample_rough(const tr_boundary *b, v3 n, v3 no, v3 o, double eta_o, double eta_t, double u0, double u1,
                         double u2, tr_bsdf_sample *dest)
{
    v3 m = lucent_ggx_sample_visible(o, no, b->alpha, u1, u2);
    double om = v3_dot(o, m), F = lucent_fresnel_dielectric(om, eta_t / eta_o, NULL);
    *dest = (tr_bsdf_sample){.weight = 1.0, .scale = 1.0};
    if (u0 < F || !lucent_refract(v3_neg(o), m, eta_t / eta_o, &dest->i)) {
        dest->i = lucent_reflect(v3_neg(o), m);
        if (v3_dot(dest->i, no) <= 0) return false;
    } else {
        if (v3_dot(dest->i, no) >= 0) return false;
        dest->transmit = true;
        dest->weight = dest->scale = (eta_o / eta_t) * (eta_o / eta_t);
    }
    dest->weight *= lucent_ggx_g1(v3_dot(dest->i, no), b->alpha);
    tr_bsdf_eval(b, n, o, dest->i, &dest->pdf);
    return dest->pdf > 0 && dest->weight > 0;
}

bool tr_bsdf_sample_dir(const tr_boundary *b, v3 n, v3 o, double u0, double u1, double u2, tr_bsdf_sample *dest)
{
    double co = v3_dot(o, n);
    if (b->kind == TR_BOUNDARY_MATCHED) {
        *dest = (tr_bsdf_sample){.i = v3_neg(o), .weight = 1.0, .delta = true, .transmit = true, .scale = 1.0};
        return true;
    }
    if (co == 0) return false;
    v3 no = co > 0 ? n : v3_neg(n);
    double eta_o = co > 0 ? 1.0 : b->eta, eta_t = co > 0 ? b->eta : 1.0;
    if (b->kind == TR_BOUNDARY_SMOOTH) return sample_smooth(no, o, eta_o, eta_t, u0, dest);
    if (b->cycles3) return sample_cycles3(b, n, no, o, eta_o, eta_t, u0, u1, u2, dest);
    return sample_rough(b, n, no, o, eta_o, eta_t, u0, u1, u2, dest);
}
