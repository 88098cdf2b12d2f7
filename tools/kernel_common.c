/* Shared by `lucent kernel` and `lucent kernel-eval`: the radial profile a kernel is built from. */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "kernel_common.h"

bool kernel_profile_known(const char *name)
{
    return !strcmp(name, "dipole") || !strcmp(name, "better-dipole") || !strcmp(name, "burley") ||
           !strcmp(name, "mc");
}

/* Monte Carlo R_d(r) of a half-space of m, per channel, on the default grid (Freude Table 6.1). */
static lucent_status profile_mc(int photons, int seed, const lucent_material *m, lucent_profile **dest)
{
    lucent_profile_grid g;
    lucent_profile_grid_default(m, &g);
    lucent_status s = lucent_profile_create(&g, "mc", dest);
    static const char *const labels[] = {"Monte Carlo R", "Monte Carlo G", "Monte Carlo B"};
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        lucent_mc_layer layer = {.n = m->eta,
                                 .sigma_a = m->sigma_a[c],
                                 .sigma_s = m->sigma_s[c],
                                 .g = m->g[c],
                                 .thickness = INFINITY};
        lucent_mc_desc d = {.layers = &layer,
                            .layer_count = 1,
                            .photons = (uint64_t)photons,
                            .seed = 4 * (uint64_t)seed + (uint64_t)c,
                            .grid = {.dr = g.dr, .nr = g.count},
                            .pool = cli_pool(),
                            .label = labels[c]};
        lucent_mc_result r = {0};
        if ((s = lucent_mc_run(&d, &r)) != LUCENT_OK) break;
        for (int j = 0; j < g.count; j++)
            (*dest)->value[c][j] = r.rd_r[j], (*dest)->error[c][j] = r.rd_r_se[j];
        lucent_mc_result_free(&r);
    }
    if (s != LUCENT_OK) lucent_profile_destroy(*dest), *dest = NULL;
    return s;
}

lucent_status kernel_make_profile(const char *profile, int photons, int seed, const lucent_material *m,
                                  lucent_profile **dest)
{
    if (!strcmp(profile, "mc")) return profile_mc(photons, seed, m, dest);
    if (!strcmp(profile, "better-dipole")) return lucent_profile_better_dipole(m, NULL, dest);
    if (!strcmp(profile, "burley")) {
        lucent_burley_params bp;
        lucent_status s = lucent_burley_params_from_material(m, LUCENT_BURLEY_SEARCHLIGHT_MFP, &bp);
        return s == LUCENT_OK ? lucent_profile_burley(&bp, NULL, dest) : s;
    }
    return lucent_profile_dipole(m, NULL, dest);
}
