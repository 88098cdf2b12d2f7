/* Profiles by name: the radial profile a kernel or a renderer builds from a material. */
#include <math.h>
#include <string.h>

#include "lucent/mc.h"
#include "lucent/profile.h"
#include "lucent/skin.h"

static const char *const k_sources[] = {"dipole", "better-dipole", "burley", "mc", NULL};

const char *lucent_profile_source_name(int index)
{
    return index >= 0 && index < (int)(sizeof k_sources / sizeof k_sources[0]) ? k_sources[index] : NULL;
}

bool lucent_profile_source_known(const char *name)
{
    for (int i = 0; name && k_sources[i]; i++)
        if (!strcmp(name, k_sources[i])) return true;
    return false;
}

/* Channel c of m as a half-space, run on grid g (Freude Table 6.1's default grid). */
static lucent_status mc_half_space(const lucent_material *m, int c, uint64_t photons, uint64_t seed, lucent_pool *pool,
                                   const lucent_profile_grid *g, lucent_mc_result *r)
{
    static const char *const labels[] = {"Monte Carlo R", "Monte Carlo G", "Monte Carlo B"};
    lucent_mc_layer layer = {
        .n = m->eta, .sigma_a = m->sigma_a[c], .sigma_s = m->sigma_s[c], .g = m->g[c], .thickness = INFINITY};
    lucent_mc_desc md = {.layers = &layer,
                         .layer_count = 1,
                         .photons = photons ? photons : 200000,
                         .seed = 4 * seed + (uint64_t)c,
                         .grid = {.dr = g->dr, .nr = g->count},
                         .pool = pool,
                         .label = labels[c]};
    return lucent_mc_run(&md, r);
}

/* Monte Carlo R_d(r) of a half-space of m, per channel, on desc's grid (zero fields: the default grid,
 * Freude Table 6.1). */
static lucent_status profile_mc(const lucent_profile_source_desc *d, const lucent_material *m, lucent_profile **dest)
{
    lucent_profile_grid g;
    lucent_status s = lucent_profile_grid_resolve(&d->grid, m, &g);
    if (s == LUCENT_OK) s = lucent_profile_create(&g, "mc", dest);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        lucent_mc_result r = {0};
        if ((s = mc_half_space(m, c, d->photons, d->seed, d->pool, &g, &r)) != LUCENT_OK) break;
        for (int j = 0; j < g.count; j++) (*dest)->value[c][j] = r.rd_r[j], (*dest)->error[c][j] = r.rd_r_se[j];
        lucent_mc_result_free(&r);
    }
    if (s != LUCENT_OK) lucent_profile_destroy(*dest), *dest = NULL;
    return s;
}

lucent_status lucent_profile_mc_total(const lucent_material *m, uint64_t photons, uint64_t seed, lucent_pool *pool,
                                      double rd[3], double rd_se[3])
{
    lucent_profile_grid g;
    lucent_profile_grid_default(m, &g);
    lucent_status s = LUCENT_OK;
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        lucent_mc_result r = {0};
        if ((s = mc_half_space(m, c, photons, seed, pool, &g, &r)) == LUCENT_OK) rd[c] = r.rd, rd_se[c] = r.rd_se;
        lucent_mc_result_free(&r);
    }
    return s;
}

lucent_status lucent_profile_from_source(const lucent_profile_source_desc *desc, const lucent_material *m,
                                         lucent_profile **dest)
{
    static const lucent_profile_source_desc zero = {0};
    const lucent_profile_source_desc *d = desc ? desc : &zero;
    const char *source = d->source ? d->source : "dipole";
    if (!lucent_profile_source_known(source))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown profile \"%s\" (dipole, better-dipole, burley, mc)",
                            source);
    if (m->skin.layer_count > 0) { /* a spectral skin: every band carried, then weighted (lucent/skin.h) */
        lucent_skin_desc sd = {.transport = strcmp(source, "mc") ? "multipole" : "mc",
                               .photons = d->photons ? 3 * d->photons / LUCENT_BANDS_DEFAULT : 0,
                               .seed = d->seed,
                               .pool = d->pool};
        return lucent_profile_skin(m, &sd, dest);
    }
    if (!strcmp(source, "mc")) return profile_mc(d, m, dest);
    if (!strcmp(source, "better-dipole")) return lucent_profile_better_dipole(m, NULL, dest);
    if (!strcmp(source, "burley")) {
        lucent_burley_params bp;
        lucent_status s = lucent_burley_params_from_material(m, LUCENT_BURLEY_SEARCHLIGHT_MFP, &bp);
        return s == LUCENT_OK ? lucent_profile_burley(&bp, NULL, dest) : s;
    }
    return lucent_profile_dipole(m, NULL, dest);
}
