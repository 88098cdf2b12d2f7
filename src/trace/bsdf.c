/* Dielectric boundaries: Fresnel (smooth, with total internal reflection) and GGX microfacet
 * reflection and transmission after Walter, Marschner, Li & Torrance 2007, "Microfacet models for
 * refraction through rough surfaces" (EGSR), with the separable Smith masking-shadowing
 * G = G1(i) G1(o) (Walter eq. 23), the form the CDRF sphere simulation uses too, and sampling of
 * the visible normals (Heitz 2018, "Sampling the GGX distribution of visible normals", JCGT 7(4)).
 *
 * Directions o (toward the viewer) and i (toward the light) point away from the surface; n is the
 * outward normal; the outside has index 1, the medium index eta. */
#include <math.h>

#include "trace/internal.h"

double tr_fresnel(double ci, double ni, double nt)
{
    if (ni == nt) return 0;
    double r = ni / nt, st2 = r * r * (1.0 - ci * ci);
    if (st2 >= 1.0) return 1.0;
    double ct = sqrt(1.0 - st2);
    double rs = (ni * ci - nt * ct) / (ni * ci + nt * ct);
    double rp = (ni * ct - nt * ci) / (ni * ct + nt * ci);
    return 0.5 * (rs * rs + rp * rp);
}

bool tr_refract(v3 d, v3 m, double ratio, v3 *dest)
{
    double ci = -v3_dot(m, d), st2 = ratio * ratio * (1.0 - ci * ci);
    if (st2 >= 1.0) return false;
    *dest = v3_norm(v3_madd(v3_scale(d, ratio), m, ratio * ci - sqrt(1.0 - st2)));
    return true;
}

double tr_ggx_d(double cm, double alpha)
{
    if (cm <= 0) return 0;
    double a2 = alpha * alpha, k = cm * cm * (a2 - 1.0) + 1.0;
    return a2 / (TR_PI * k * k);
}

double tr_ggx_g1(double c, double alpha)
{
    c = fabs(c);
    if (c >= 1.0) return 1.0;
    if (c <= 0.0) return 0.0;
    double tan2 = (1.0 - c * c) / (c * c);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

/* Heitz 2018, section 4: stretch v to the hemisphere configuration, sample the projected disc
 * (half of it warped by the visible fraction), lift to the hemisphere and unstretch. */
v3 tr_ggx_sample_visible(v3 v, v3 n, double alpha, double u1, double u2)
{
    v3 t, b;
    v3_basis(n, &t, &b);
    v3 lv = v3_to_local(v, t, b, n);
    v3 vh = v3_norm(v3_make(alpha * lv.x, alpha * lv.y, lv.z));
    double len2 = vh.x * vh.x + vh.y * vh.y;
    v3 t1 = len2 > 0 ? v3_scale(v3_make(-vh.y, vh.x, 0), 1.0 / sqrt(len2)) : v3_make(1, 0, 0);
    v3 t2 = v3_cross(vh, t1);
    double r = sqrt(u1), phi = 2.0 * TR_PI * u2, s = 0.5 * (1.0 + vh.z);
    double p1 = r * cos(phi), p2 = r * sin(phi);
    p2 = (1.0 - s) * sqrt(fmax(0.0, 1.0 - p1 * p1)) + s * p2;
    double p3 = sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2));
    v3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, p3));
    v3 m = v3_norm(v3_make(alpha * nh.x, alpha * nh.y, fmax(1e-12, nh.z)));
    return v3_from_local(m, t, b, n);
}

double tr_ggx_visible_pdf(v3 v, v3 n, v3 m, double alpha)
{
    double vn = v3_dot(v, n), vm = v3_dot(v, m);
    if (vn <= 0 || vm <= 0) return 0;
    return tr_ggx_g1(vn, alpha) * vm * tr_ggx_d(v3_dot(m, n), alpha) / vn;
}

/* Reflection (Walter eq. 20) and its sampling density (eq. 14 with visible-normal sampling). */
static double rough_reflect(const tr_boundary *b, v3 no, v3 o, v3 i, double eta_o, double eta_t, double *pdf)
{
    v3 m = v3_norm(v3_add(o, i));
    double om = v3_dot(o, m), co = v3_dot(o, no), ci = v3_dot(i, no);
    if (om <= 0 || v3_dot(m, no) <= 0) return 0;
    double F = tr_fresnel(om, eta_o, eta_t), D = tr_ggx_d(v3_dot(m, no), b->alpha);
    double G = tr_ggx_g1(co, b->alpha) * tr_ggx_g1(ci, b->alpha);
    *pdf = tr_ggx_visible_pdf(o, no, m, b->alpha) * F / (4.0 * om);
    return F * D * G / (4.0 * co * ci);
}

/* Transmission (Walter eq. 21, radiance convention) and its density (eq. 17 with visible normals). */
static double rough_transmit(const tr_boundary *b, v3 no, v3 o, v3 i, double eta_o, double eta_i, double *pdf)
{
    v3 m = v3_norm(v3_neg(v3_add(v3_scale(i, eta_i), v3_scale(o, eta_o))));
    if (v3_dot(m, no) < 0) m = v3_neg(m);
    double om = v3_dot(o, m), im = v3_dot(i, m), co = v3_dot(o, no), ci = -v3_dot(i, no);
    if (om <= 0 || im >= 0 || !(v3_dot(m, no) > 0)) return 0;
    double F = tr_fresnel(om, eta_o, eta_i);
    if (F >= 1.0) return 0;
    double D = tr_ggx_d(v3_dot(m, no), b->alpha), G = tr_ggx_g1(co, b->alpha) * tr_ggx_g1(ci, b->alpha);
    double den = eta_i * im + eta_o * om, den2 = den * den;
    if (!(den2 > 0)) return 0;
    *pdf = tr_ggx_visible_pdf(o, no, m, b->alpha) * (1.0 - F) * eta_i * eta_i * fabs(im) / den2;
    return fabs(im) * om / (co * ci) * eta_o * eta_o * (1.0 - F) * D * G / den2;
}

double tr_bsdf_eval(const tr_boundary *b, v3 n, v3 o, v3 i, double *pdf)
{
    *pdf = 0;
    if (b->kind != TR_BOUNDARY_ROUGH) return 0;
    double co = v3_dot(o, n), ci = v3_dot(i, n);
    if (co == 0 || ci == 0) return 0;
    v3 no = co > 0 ? n : v3_neg(n); /* the normal on o's side */
    double eta_o = co > 0 ? 1.0 : b->eta, eta_other = co > 0 ? b->eta : 1.0;
    double f = co * ci > 0 ? rough_reflect(b, no, o, i, eta_o, eta_other, pdf)
                           : rough_transmit(b, no, o, i, eta_o, eta_other, pdf);
    if (!(f > 0) || !(*pdf > 0) || !isfinite(f)) {
        *pdf = 0;
        return 0;
    }
    return f;
}

/* Smooth boundary: reflect with probability F, else refract (weight (eta_o / eta_i)^2). */
static bool sample_smooth(v3 no, v3 o, double eta_o, double eta_t, double u0, tr_bsdf_sample *dest)
{
    double co = v3_dot(o, no), F = tr_fresnel(co, eta_o, eta_t);
    *dest = (tr_bsdf_sample){.weight = 1.0, .delta = true, .scale = 1.0};
    if (u0 < F || !tr_refract(v3_neg(o), no, eta_o / eta_t, &dest->i)) {
        dest->i = v3_madd(v3_neg(o), no, 2.0 * co);
        return true;
    }
    dest->transmit = true;
    dest->weight = dest->scale = (eta_o / eta_t) * (eta_o / eta_t);
    return true;
}

/* Rough boundary: a visible normal, then reflect with probability F(o . m) or refract; the weight
 * f |cos i| / pdf reduces to G1(i) (eta_o / eta_i)^2. */
static bool sample_rough(const tr_boundary *b, v3 n, v3 no, v3 o, double eta_o, double eta_t, double u0,
                         double u1, double u2, tr_bsdf_sample *dest)
{
    v3 m = tr_ggx_sample_visible(o, no, b->alpha, u1, u2);
    double om = v3_dot(o, m), F = tr_fresnel(om, eta_o, eta_t);
    *dest = (tr_bsdf_sample){.weight = 1.0, .scale = 1.0};
    if (u0 < F || !tr_refract(v3_neg(o), m, eta_o / eta_t, &dest->i)) {
        dest->i = v3_madd(v3_neg(o), m, 2.0 * om);
        if (v3_dot(dest->i, no) <= 0) return false;
    } else {
        if (v3_dot(dest->i, no) >= 0) return false;
        dest->transmit = true;
        dest->weight = dest->scale = (eta_o / eta_t) * (eta_o / eta_t);
    }
    dest->weight *= tr_ggx_g1(v3_dot(dest->i, no), b->alpha);
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
    return sample_rough(b, n, no, o, eta_o, eta_t, u0, u1, u2, dest);
}
