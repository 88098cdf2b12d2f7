/* Analytic half-space profiles: the classical dipole (Jensen et al. 2001), the better dipole
 * (d'Eon 2012) and Burley's normalized diffusion (Christensen & Burley 2015). Bins hold exact
 * bin averages: every model's r-weighted integral has a closed-form primitive. */
#include <math.h>
#include <string.h>

#include "lucent/profile.h"
#include "profile/pole.h"

/* A dipole: a real source at depth zr (charge +1) and a virtual one at signed depth zv
 * (charge -1), seen through alpha' (cE E + cphi phi), phi = (1/(4 pi dg)) (e^{-s dr}/dr -
 * e^{-s dv}/dv). The classical dipole has cE = 1, cphi = 0. */
typedef struct dipole {
    double alpha, s, zr, zv, ce, cphi, dg;
} dipole;

/* Jensen et al. 2001, eq. 4: z_r = 1/sigma_t', z_v = z_r (1 + 4A/3) above the surface. */
static void dipole_classical(const lucent_medium *md, dipole *d)
{
    double stp = md->sigma_a + md->sigma_s_prime;
    double fdr = lucent_fdr(md->eta);
    double a = (1.0 + fdr) / (1.0 - fdr); /* A = (1 + Fdr) / (1 - Fdr) */
    *d = (dipole){.alpha = md->sigma_s_prime / stp,
                  .s = sqrt(3.0 * md->sigma_a * stp), /* sigma_tr */
                  .zr = 1.0 / stp,
                  .ce = 1.0,
                  .dg = 1.0 / (3.0 * stp)};
    d->zv = -d->zr * (1.0 + 4.0 * a / 3.0);
}

/* d'Eon 2012's polynomial fits of the Fresnel moments 2 C1 and 3 C2, eta >= 1, divided back
 * to C1 = int_0^1 F(eta, mu) mu dmu and C2 = int_0^1 F(eta, mu) mu^2 dmu. */
static double fresnel_c1(double eta)
{
    double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    return -4.61686 + 11.1136 * eta - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}

static double fresnel_c2(double eta)
{
    double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    double r = 1.0 / eta, r2 = r * r, r3 = r2 * r;
    return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * eta - 189.519 * e2 + 54.9327 * e3 -
           9.00603 * e4 + 0.63942 * e5;
}

/* d'Eon 2012: D = (2 sigma_a + sigma_s') / (3 sigma_t'^2) (Grosjean), A = (1 + 3 C2) / (1 - 2 C1),
 * z_b = 2 A D, z_r = 1/sigma_t', z_v = -z_r - 2 z_b, C_phi = (1 - 2 C1)/4, C_E = (1 - 3 C2)/2. */
static void dipole_better(const lucent_medium *md, dipole *d)
{
    double stp = md->sigma_a + md->sigma_s_prime;
    double c1 = fresnel_c1(md->eta), c2 = fresnel_c2(md->eta);
    double dg = (2.0 * md->sigma_a + md->sigma_s_prime) / (3.0 * stp * stp);
    double a = (1.0 + 3.0 * c2) / (1.0 - 2.0 * c1);
    *d = (dipole){.alpha = md->sigma_s_prime / stp,
                  .s = sqrt(md->sigma_a / dg), /* sigma_tr = sqrt(sigma_a / D) */
                  .zr = 1.0 / stp,
                  .ce = 0.5 * (1.0 - 3.0 * c2),
                  .cphi = 0.25 * (1.0 - 2.0 * c1),
                  .dg = dg};
    d->zv = -d->zr - 4.0 * a * dg;
}

static double dipole_value(const dipole *d, double r)
{
    double e = pole_flux(d->zr, d->s, r) - pole_flux(d->zv, d->s, r);
    double phi = 0.0;
    if (d->cphi != 0.0) {
        double dr = hypot(r, d->zr), dv = hypot(r, d->zv);
        phi = (exp(-d->s * dr) / dr - exp(-d->s * dv) / dv) / (4.0 * M_PI * d->dg);
    }
    return d->alpha * (d->ce * e + d->cphi * phi);
}

/* 2 pi integral over [r0, r1] of R r dr; the fluence term integrates to
 * (1/(2 dg)) [g(dr0, dv0) - g(dr1, dv1)], g(a, b) = (e^{-s a} - e^{-s b}) / s. */
static double dipole_bin(const dipole *d, double r0, double r1)
{
    double e = pole_flux_bin(d->zr, d->s, r0, r1) - pole_flux_bin(d->zv, d->s, r0, r1);
    double phi = 0.0;
    if (d->cphi != 0.0) {
        double g0 = exp_diff_over_s(d->s, hypot(r0, d->zr), hypot(r0, d->zv));
        double g1 = exp_diff_over_s(d->s, hypot(r1, d->zr), hypot(r1, d->zv));
        phi = (g0 - g1) / (2.0 * d->dg);
    }
    return d->alpha * (d->ce * e + d->cphi * phi);
}

double lucent_dipole_eval(const lucent_medium *md, double r)
{
    if (lucent_medium_validate(md) != LUCENT_OK || !(r >= 0.0)) return NAN;
    dipole d;
    dipole_classical(md, &d);
    return dipole_value(&d, r);
}

double lucent_better_dipole_eval(const lucent_medium *md, double r)
{
    if (lucent_medium_validate(md) != LUCENT_OK || !(r >= 0.0)) return NAN;
    dipole d;
    dipole_better(md, &d);
    return dipole_value(&d, r);
}

/* Plane integrals: E of a pole gives sign(h) e^{-s|h|}/2; phi gives g(z_r, |z_v|) / (2 D). */
double lucent_better_dipole_total(const lucent_medium *md)
{
    if (lucent_medium_validate(md) != LUCENT_OK) return NAN;
    dipole d;
    dipole_better(md, &d);
    double e = pole_flux_total(d.zr, d.s) - pole_flux_total(d.zv, d.s);
    double phi = exp_diff_over_s(d.s, d.zr, fabs(d.zv)) / (2.0 * d.dg);
    return d.alpha * (d.ce * e + d.cphi * phi);
}

typedef void (*dipole_setup_fn)(const lucent_medium *md, dipole *d);

static lucent_status build_dipole(const lucent_material *m, const lucent_profile_grid *grid, const char *model,
                                  dipole_setup_fn setup, lucent_profile **dest)
{
    *dest = NULL;
    lucent_profile_grid g;
    lucent_status st = lucent_profile_grid_resolve(grid, m, &g);
    if (st == LUCENT_OK) st = lucent_material_validate(m);
    if (st == LUCENT_OK) st = lucent_profile_create(&g, model, dest);
    if (st != LUCENT_OK) return st;
    for (int c = 0; c < 3; c++) {
        lucent_medium md;
        dipole d;
        lucent_medium_from_material(m, c, &md);
        setup(&md, &d);
        for (int j = 0; j < g.count; j++) {
            double r0 = j * g.dr, r1 = (j + 1) * g.dr;
            (*dest)->value[c][j] = bin_average(dipole_bin(&d, r0, r1), r0, r1);
        }
    }
    return LUCENT_OK;
}

lucent_status lucent_profile_dipole(const lucent_material *m, const lucent_profile_grid *grid, lucent_profile **dest)
{
    return build_dipole(m, grid, "dipole", dipole_classical, dest);
}

lucent_status lucent_profile_better_dipole(const lucent_material *m, const lucent_profile_grid *grid,
                                           lucent_profile **dest)
{
    return build_dipole(m, grid, "better-dipole", dipole_better, dest);
}

/* ---- Burley normalized diffusion ---- */

/* Christensen & Burley 2015, Section 3 (empirical fits of the scaling factor s, d = l / s). */
double lucent_burley_scale(lucent_burley_fit fit, double albedo)
{
    double a = fmin(fmax(albedo, 0.0), 1.0);
    switch (fit) {
    case LUCENT_BURLEY_SEARCHLIGHT_MFP: /* eq. 5: searchlight configuration, mfp */
        return 1.85 - a + 7.0 * pow(fabs(a - 0.8), 3.0);
    case LUCENT_BURLEY_DIFFUSE_MFP: /* eq. 6: diffuse surface transmission, mfp */
        return 1.9 - a + 3.5 * (a - 0.8) * (a - 0.8);
    case LUCENT_BURLEY_SEARCHLIGHT_DMFP: /* eq. 8: searchlight configuration, dmfp */
        return 3.5 + 100.0 * pow(a - 0.33, 4.0);
    }
    return NAN;
}

/* Christensen & Burley 2015, eq. 2 with d = 1/s: R(r) = A s (e^{-sr} + e^{-sr/3}) / (8 pi r). */
double lucent_burley_eval(double albedo, double s, double r)
{
    if (!(r >= 0.0) || !(s > 0.0)) return NAN;
    if (r == 0.0) return albedo > 0.0 ? INFINITY : 0.0;
    return albedo * s * (exp(-s * r) + exp(-s * r / 3.0)) / (8.0 * M_PI * r);
}

/* 2 pi integral_{r0}^{r1} R r dr = (A/4) [(e^{-s r0} - e^{-s r1}) + 3 (e^{-s r0/3} - e^{-s r1/3})]:
 * the 1/r singularity cancels against r, so the first bin is exact too. */
static double burley_bin(double albedo, double s, double r0, double r1)
{
    double near = -exp(-s * r0) * expm1(-s * (r1 - r0));
    double far = -exp(-s * r0 / 3.0) * expm1(-s * (r1 - r0) / 3.0);
    return 0.25 * albedo * (near + 3.0 * far);
}

static lucent_status burley_validate(const lucent_burley_params *p)
{
    if (!(p->fit == LUCENT_BURLEY_SEARCHLIGHT_MFP || p->fit == LUCENT_BURLEY_DIFFUSE_MFP ||
          p->fit == LUCENT_BURLEY_SEARCHLIGHT_DMFP))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "burley: fit: unknown value %d", (int)p->fit);
    for (int c = 0; c < 3; c++) {
        if (!(p->albedo[c] >= 0.0 && p->albedo[c] <= 1.0))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "burley: albedo[%d] must be in [0, 1], got %g", c,
                                p->albedo[c]);
        if (!(p->length[c] > 0.0) || !isfinite(p->length[c]))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "burley: length[%d] must be finite and > 0, got %g", c,
                                p->length[c]);
    }
    return LUCENT_OK;
}

lucent_status lucent_burley_params_from_material(const lucent_material *m, lucent_burley_fit fit,
                                                 lucent_burley_params *dest)
{
    lucent_status st = lucent_material_validate(m);
    if (st != LUCENT_OK) return st;
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    lucent_burley_params p = {.fit = fit};
    for (int c = 0; c < 3; c++) {
        p.albedo[c] = d.rd[c];
        p.length[c] = fit == LUCENT_BURLEY_SEARCHLIGHT_DMFP ? d.mfp_diffuse[c] : d.mfp_prime[c];
    }
    st = burley_validate(&p);
    if (st != LUCENT_OK) return lucent_error_context(st, "%s", m->name[0] ? m->name : "material");
    *dest = p;
    return LUCENT_OK;
}

/* Table 6.1 of Freude 2014 with MFP replaced by the profile's length d = l / s. */
static void burley_grid(const lucent_burley_params *p, const lucent_profile_grid *grid, lucent_profile_grid *dest)
{
    double lo = INFINITY, hi = 0.0;
    for (int c = 0; c < 3; c++) {
        double d = p->length[c] / lucent_burley_scale(p->fit, p->albedo[c]);
        lo = fmin(lo, d);
        hi = fmax(hi, d);
    }
    *dest = grid ? *grid : (lucent_profile_grid){0};
    if (dest->dr == 0.0) dest->dr = lo / 20.0;
    if (dest->count == 0) dest->count = (int)ceil(32.0 * hi / dest->dr - 1e-9);
}

lucent_status lucent_profile_burley(const lucent_burley_params *params, const lucent_profile_grid *grid,
                                    lucent_profile **dest)
{
    *dest = NULL;
    lucent_status st = burley_validate(params);
    if (st != LUCENT_OK) return st;
    lucent_profile_grid g;
    burley_grid(params, grid, &g);
    st = lucent_profile_create(&g, "burley", dest);
    if (st != LUCENT_OK) return st;
    for (int c = 0; c < 3; c++) {
        double s = lucent_burley_scale(params->fit, params->albedo[c]) / params->length[c];
        for (int j = 0; j < g.count; j++) {
            double r0 = j * g.dr, r1 = (j + 1) * g.dr;
            (*dest)->value[c][j] = bin_average(burley_bin(params->albedo[c], s, r0, r1), r0, r1);
        }
    }
    return LUCENT_OK;
}
