/* Tabulated radial profiles: creation, the default grid (Freude 2014, Table 6.1), totals, and
 * the one-channel medium the diffusion models read. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mc.h"
#include "lucent/profile.h"

#define LUCENT_PROFILE_MAX_COUNT 100000000

void lucent_profile_grid_default(const lucent_material *m, lucent_profile_grid *dest)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    double lo = INFINITY, hi = 0.0;
    for (int c = 0; c < 3; c++) { /* MFP = 1 / sigma_t' (Freude 2014, Section 6.1) */
        lo = fmin(lo, d.mfp_prime[c]);
        hi = fmax(hi, d.mfp_prime[c]);
    }
    dest->dr = lo / 20.0;                                 /* Table 6.1: d_r = min(MFP_rgb) / 20 */
    dest->count = (int)ceil(32.0 * hi / dest->dr - 1e-9); /* n_r = ceil(32 max(MFP) / d_r) */
}

lucent_status lucent_profile_grid_resolve(const lucent_profile_grid *grid, const lucent_material *m,
                                          lucent_profile_grid *dest)
{
    lucent_profile_grid g = grid ? *grid : (lucent_profile_grid){0};
    if (g.dr == 0.0 || g.count == 0) {
        if (!m)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile grid: dr and count are required (no material)");
        lucent_status st = lucent_material_validate(m);
        if (st != LUCENT_OK) return st;
        for (int c = 0; c < 3; c++) { /* the Monte Carlo's bound, said of the material's own field */
            double t = m->sigma_a[c] + m->sigma_s[c];
            if (t > LUCENT_MC_MAX_SIGMA_T)
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                    "%s[%d]: sigma_t = sigma_a + sigma_s = %g mm^-1 is above %g mm^-1: too dense for a "
                                    "profile (its default grid, the smallest mean free path / 20, would not hold)",
                                    m->sigma_s[c] >= m->sigma_a[c] ? "sigma_s" : "sigma_a", c, t,
                                    LUCENT_MC_MAX_SIGMA_T);
        }
        lucent_profile_grid def;
        lucent_profile_grid_default(m, &def);
        if (g.dr == 0.0) g.dr = def.dr;
        if (g.count == 0) g.count = def.count;
    }
    if (!(g.dr > 0.0) || !isfinite(g.dr))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile grid: dr must be finite and > 0, got %g", g.dr);
    if (g.count <= 0 || g.count > LUCENT_PROFILE_MAX_COUNT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile grid: count must be in [1, %d], got %d",
                            LUCENT_PROFILE_MAX_COUNT, g.count);
    /* The Monte Carlo's bounds for every model (issue 32): a bin below 1e-15 mm gave NaN or inf in the analytic
     * models (annulus areas of r^2 underflowing; dr = 1e-300, or the default grid of sigma_s = 1e300), a grid past
     * 1e12 mm zeros, written with exit 0. */
    const char *why = grid && grid->dr != 0.0 ? "" : " (the default: the smallest mean free path / 20)";
    if (g.dr < LUCENT_MC_MIN_BIN)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile grid: dr = %g mm%s is below %g mm", g.dr, why,
                            LUCENT_MC_MIN_BIN);
    if (g.dr * g.count > LUCENT_MC_MAX_EXTENT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile grid: dr = %g mm%s x %d bins spans more than %g mm",
                            g.dr, why, g.count, LUCENT_MC_MAX_EXTENT);
    *dest = g;
    return LUCENT_OK;
}

lucent_status lucent_profile_create(const lucent_profile_grid *grid, const char *model, lucent_profile **dest)
{
    *dest = NULL;
    if (!grid) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "profile: grid is NULL");
    lucent_profile_grid g = {0}; /* set by resolve; initialised for GCC -O3 */
    lucent_status st = lucent_profile_grid_resolve(grid, NULL, &g);
    if (st != LUCENT_OK) return st;
    lucent_profile *p = calloc(1, sizeof *p);
    double *block = calloc((size_t)g.count * 7u, sizeof *block);
    if (!p || !block) {
        free(p);
        free(block);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "profile: %d bins", g.count);
    }
    p->count = g.count;
    p->dr = g.dr;
    p->r = block;
    for (int c = 0; c < 3; c++) {
        p->value[c] = block + (size_t)(1 + c) * (size_t)g.count;
        p->error[c] = block + (size_t)(4 + c) * (size_t)g.count;
    }
    for (int j = 0; j < g.count; j++) p->r[j] = (j + 0.5) * g.dr;
    if (model) snprintf(p->model, sizeof p->model, "%s", model);
    *dest = p;
    return LUCENT_OK;
}

lucent_status lucent_profile_clone(const lucent_profile *src, lucent_profile **dest)
{
    lucent_status st =
        lucent_profile_create(&(lucent_profile_grid){.dr = src->dr, .count = src->count}, src->model, dest);
    if (st != LUCENT_OK) return st;
    memcpy((*dest)->r, src->r, (size_t)src->count * sizeof *src->r);
    for (int c = 0; c < 3; c++) {
        memcpy((*dest)->value[c], src->value[c], (size_t)src->count * sizeof *src->value[c]);
        memcpy((*dest)->error[c], src->error[c], (size_t)src->count * sizeof *src->error[c]);
    }
    return LUCENT_OK;
}

void lucent_profile_destroy(lucent_profile *p)
{
    if (!p) return;
    free(p->r); /* one block holds r, value and error */
    free(p);
}

double lucent_profile_total(const lucent_profile *p, int c)
{
    double sum = 0.0;
    for (int j = 0; j < p->count; j++) {
        double area = M_PI * (2.0 * j + 1.0) * p->dr * p->dr; /* pi ((j+1)^2 - j^2) dr^2 */
        sum += p->value[c][j] * area;
    }
    return sum;
}

void lucent_medium_from_material(const lucent_material *m, int c, lucent_medium *dest)
{
    dest->sigma_a = m->sigma_a[c];
    dest->sigma_s_prime = m->sigma_s[c] * (1.0 - m->g[c]); /* Jensen 2001: sigma_s' */
    dest->eta = m->eta;
}

lucent_status lucent_medium_validate(const lucent_medium *md)
{
    if (!isfinite(md->sigma_a) || md->sigma_a < 0.0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sigma_a must be finite and >= 0, got %g", md->sigma_a);
    if (!isfinite(md->sigma_s_prime) || md->sigma_s_prime < 0.0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sigma_s_prime must be finite and >= 0, got %g",
                            md->sigma_s_prime);
    if (!(md->sigma_a + md->sigma_s_prime > 0.0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "sigma_a + sigma_s_prime must be > 0, got %g",
                            md->sigma_a + md->sigma_s_prime);
    if (!(md->eta >= LUCENT_MATERIAL_ETA_MIN && md->eta <= LUCENT_MATERIAL_ETA_MAX))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "eta must be in [%g, %g], got %g", LUCENT_MATERIAL_ETA_MIN,
                            LUCENT_MATERIAL_ETA_MAX, md->eta);
    return LUCENT_OK;
}
