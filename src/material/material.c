/* Material physics: derived quantities, the classical dipole's total diffuse reflectance and
 * its inverse, validation, and the albedo / diffuse-colour parameterisations.
 * Reference: H. W. Jensen, S. R. Marschner, M. Levoy, P. Hanrahan, "A Practical Model for
 * Subsurface Light Transport", SIGGRAPH 2001 (cited below as Jensen 2001). */
#include <math.h>
#include <string.h>

#include "lucent/material.h"
#include "lucent/spectral.h"

/* Jensen 2001: Fdr = -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta (fit of the diffuse
 * Fresnel reflectance, for eta > 1). */
double lucent_fdr(double eta) { return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta; }

/* Jensen 2001, total diffuse reflectance of the dipole:
 *   Rd = (alpha'/2) (1 + exp(-(4/3) A sqrt(3 (1 - alpha')))) exp(-sqrt(3 (1 - alpha'))),
 *   A = (1 + Fdr) / (1 - Fdr). */
double lucent_dipole_rd(double albedo_prime, double eta)
{
    double fdr = lucent_fdr(eta);
    double a = (1.0 + fdr) / (1.0 - fdr);
    double s = sqrt(3.0 * (1.0 - albedo_prime));
    return 0.5 * albedo_prime * (1.0 + exp(-(4.0 / 3.0) * a * s)) * exp(-s);
}

double lucent_dipole_albedo_from_rd(double rd, double eta)
{
    if (!(rd > 0.0)) return 0.0;
    if (rd >= 1.0) return 1.0; /* Rd(1) = 1: nothing absorbed, everything comes back */
    double lo = 0.0, hi = 1.0; /* Rd(lo) < rd <= Rd(hi): Rd increases with alpha' */
    while (hi - lo > 1e-12) {
        double mid = 0.5 * (lo + hi);
        if (lucent_dipole_rd(mid, eta) < rd)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

static void derive_channel(const lucent_material *m, int c, lucent_material_derived *d)
{
    double sa = m->sigma_a[c], ss = m->sigma_s[c];
    double ssp = ss * (1.0 - m->g[c]); /* Jensen 2001: sigma_s' = sigma_s (1 - g) */
    double stp = sa + ssp;             /* sigma_t' = sigma_a + sigma_s' */
    d->sigma_s_prime[c] = ssp;
    d->sigma_t[c] = sa + ss;
    d->sigma_t_prime[c] = stp;
    d->albedo[c] = ss / (sa + ss);
    d->albedo_prime[c] = ssp / stp;        /* alpha' = sigma_s' / sigma_t' */
    d->sigma_tr[c] = sqrt(3.0 * sa * stp); /* sigma_tr = sqrt(3 sigma_a sigma_t') */
    d->diffusion[c] = 1.0 / (3.0 * stp);   /* D = 1 / (3 sigma_t') */
    d->mfp[c] = 1.0 / (sa + ss);
    d->mfp_prime[c] = 1.0 / stp;
    d->mfp_diffuse[c] = sa > 0.0 ? 1.0 / d->sigma_tr[c] : INFINITY;
    d->rd[c] = lucent_dipole_rd(d->albedo_prime[c], m->eta);
}

void lucent_material_derive(const lucent_material *m, lucent_material_derived *dest)
{
    memset(dest, 0, sizeof *dest);
    dest->fdr = lucent_fdr(m->eta);
    dest->a = (1.0 + dest->fdr) / (1.0 - dest->fdr);
    for (int c = 0; c < 3; c++) derive_channel(m, c, dest);
}

static const char *name_or(const lucent_material *m) { return m->name[0] ? m->name : "material"; }

static lucent_status bad(const lucent_material *m, const char *field, int c, double v, const char *rule)
{
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: %s[%d]: must be %s, got %g", name_or(m), field, c, rule, v);
}

static lucent_status validate_channel(const lucent_material *m, int c)
{
    double sa = m->sigma_a[c], ss = m->sigma_s[c], g = m->g[c];
    if (!isfinite(sa) || sa < 0.0) return bad(m, "sigma_a", c, sa, "finite and >= 0");
    if (!isfinite(ss) || ss < 0.0) return bad(m, "sigma_s", c, ss, "finite and >= 0");
    if (!(sa + ss > 0.0)) return bad(m, "sigma_a + sigma_s", c, sa + ss, "> 0");
    if (!(g > -1.0 && g < 1.0)) return bad(m, "g", c, g, "in (-1, 1)");
    return LUCENT_OK;
}

lucent_status lucent_material_validate(const lucent_material *m)
{
    if (!memchr(m->name, '\0', sizeof m->name))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "material name is not terminated");
    if (m->skin.layer_count != 0) {
        lucent_status s = lucent_skin_validate(&m->skin, name_or(m));
        if (s != LUCENT_OK) return s;
        if (!m->skin.resolved)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s: a spectral skin whose equivalent medium is not resolved yet "
                                "(lucent_skin_resolve, lucent/skin.h)",
                                name_or(m));
    }
    for (int c = 0; c < 3; c++) {
        lucent_status s = validate_channel(m, c);
        if (s != LUCENT_OK) return s;
    }
    if (!(m->eta >= LUCENT_MATERIAL_ETA_MIN && m->eta <= LUCENT_MATERIAL_ETA_MAX))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: eta: must be in [%g, %g], got %g", name_or(m),
                            LUCENT_MATERIAL_ETA_MIN, LUCENT_MATERIAL_ETA_MAX, m->eta);
    return LUCENT_OK;
}

static lucent_status check_g(const lucent_material *m)
{
    for (int c = 0; c < 3; c++)
        if (!(m->g[c] > -1.0 && m->g[c] < 1.0)) return bad(m, "g", c, m->g[c], "in (-1, 1)");
    return LUCENT_OK;
}

/* Single:  sigma_t = 1/l,   sigma_s = alpha sigma_t,   sigma_a = (1 - alpha) sigma_t.
 * Reduced: sigma_t' = 1/l', sigma_s' = alpha' sigma_t', sigma_a = (1 - alpha') sigma_t',
 *          sigma_s = sigma_s' / (1 - g). */
lucent_status lucent_material_set_albedo(lucent_albedo_kind kind, const double albedo[3], const double mfp[3],
                                         lucent_material *dest)
{
    lucent_status s = check_g(dest);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        if (!(albedo[c] >= 0.0 && albedo[c] <= 1.0))
            s = bad(dest, "albedo", c, albedo[c], "in [0, 1]");
        else if (!(mfp[c] > 0.0 && isfinite(mfp[c])))
            s = bad(dest, "mean free path", c, mfp[c], "finite and > 0");
    }
    if (s != LUCENT_OK) return s;
    for (int c = 0; c < 3; c++) {
        double st = 1.0 / mfp[c];
        double scale = kind == LUCENT_ALBEDO_REDUCED ? 1.0 / (1.0 - dest->g[c]) : 1.0;
        dest->sigma_a[c] = (1.0 - albedo[c]) * st;
        dest->sigma_s[c] = albedo[c] * st * scale;
    }
    return LUCENT_OK;
}

/* Rd -> alpha' by inverting the dipole; then sigma_tr = sigma_t' sqrt(3 (1 - alpha')) gives
 * sigma_t' = sigma_tr / sqrt(3 (1 - alpha')), with sigma_tr = 1 / ld. */
lucent_status lucent_material_set_diffuse(const double rd[3], const double mfp_diffuse[3], lucent_material *dest)
{
    lucent_status s = check_g(dest);
    if (s == LUCENT_OK && !(dest->eta >= LUCENT_MATERIAL_ETA_MIN && dest->eta <= LUCENT_MATERIAL_ETA_MAX))
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: eta: must be in [%g, %g], got %g", name_or(dest),
                         LUCENT_MATERIAL_ETA_MIN, LUCENT_MATERIAL_ETA_MAX, dest->eta);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        if (!(rd[c] >= 0.0 && rd[c] < 1.0))
            s = bad(dest, "diffuse reflectance", c, rd[c], "in [0, 1)");
        else if (!(mfp_diffuse[c] > 0.0 && isfinite(mfp_diffuse[c])))
            s = bad(dest, "diffuse mean free path", c, mfp_diffuse[c], "finite and > 0");
    }
    if (s != LUCENT_OK) return s;
    for (int c = 0; c < 3; c++) {
        double ap = lucent_dipole_albedo_from_rd(rd[c], dest->eta);
        double stp = (1.0 / mfp_diffuse[c]) / sqrt(3.0 * (1.0 - ap));
        dest->sigma_a[c] = (1.0 - ap) * stp;
        dest->sigma_s[c] = ap * stp / (1.0 - dest->g[c]);
    }
    return LUCENT_OK;
}
