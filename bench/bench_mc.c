/* Benchmark of the Monte Carlo transport (issue 3, item 6): photons per second per core and in
 * total for the red channels of Skin1 (n 1.3, sigma_a 0.032, sigma_s 0.74 mm^-1, g 0) and
 * Marble (n 1.5, sigma_a 0.0021, sigma_s 2.19 mm^-1, g 0), semi-infinite, on the grid of
 * Wang's thesis Table 6.1 (dr = MFP/20 with MFP = 1 / (sigma_a + sigma_s), 640 radial bins),
 * without and with the A(r, z) grid (nz = 640, dz = dr).
 * Anchor: MCML 1.2.2 (gcc -O2, one core) on this kind of machine runs Skin1 at 103k photons/s
 * with its absorption grid, 171-198k without; Marble at 13.3k (19.8k). Target: 5x per core.
 * Usage: bench_mc [seconds_per_case] */
#include <math.h>
#include <stdlib.h>

#include "lucent/mc.h"

typedef struct bench_case {
    const char *name;
    lucent_mc_layer layer;
    double mcml_arz, mcml_lo, mcml_hi; /* MCML photons/s: with A(r,z); without (a range) */
} bench_case;

static const bench_case k_cases[] = {
    {"Skin1 (red)", {1.3, 0.032, 0.74, 0.0, INFINITY}, 103e3, 171e3, 198e3},
    {"Marble (red)", {1.5, 0.0021, 2.19, 0.0, INFINITY}, 13.3e3, 19.8e3, 19.8e3},
};

/* Photons per second for n photons on `threads` threads; *rd receives Rd as a sanity figure. */
static double rate(const bench_case *c, bool a_rz, int threads, uint64_t n, double *rd)
{
    double mfp = 1.0 / (c->layer.sigma_a + c->layer.sigma_s);
    lucent_pool *pool = threads > 1 ? lucent_pool_create(threads) : NULL;
    lucent_mc_desc d = {.layers = &c->layer,
                        .layer_count = 1,
                        .photons = n,
                        .seed = 1,
                        .pool = pool,
                        .score_a_rz = a_rz,
                        .last_bin_collects = true,
                        .grid = {.dr = mfp / 20, .dz = mfp / 20, .nr = 640, .nz = 640, .na = 30}};
    lucent_mc_result r;
    double t0 = lucent_clock_seconds();
    lucent_status s = lucent_mc_run(&d, &r);
    double t = lucent_clock_seconds() - t0;
    lucent_pool_destroy(pool);
    if (s != LUCENT_OK) {
        fprintf(stderr, "bench_mc: %s\n", lucent_last_error());
        exit(1);
    }
    *rd = r.rd;
    lucent_mc_result_free(&r);
    return (double)n / t;
}

static void run_case(const bench_case *c, bool a_rz, int cores, double seconds)
{
    double rd, probe = rate(c, a_rz, 1, 20000, &rd);
    uint64_t n = (uint64_t)(probe * seconds) + 1000;
    double one = rate(c, a_rz, 1, n, &rd);
    double all = cores > 1 ? rate(c, a_rz, cores, n * (uint64_t)cores, &rd) : one;
    double lo = a_rz ? c->mcml_arz : c->mcml_lo, hi = a_rz ? c->mcml_arz : c->mcml_hi;
    char anchor[48];
    if (hi > lo)
        snprintf(anchor, sizeof anchor, "%.0f-%.0fk", lo / 1e3, hi / 1e3);
    else
        snprintf(anchor, sizeof anchor, "%.1fk", lo / 1e3);
    printf("  %-12s %-7s %7.0fk/s per core = %5.1fx MCML (%s)  %7.0fk/s on %d cores (%.2fx)  "
           "Rd %.4f\n",
           c->name, a_rz ? "A(r,z)" : "no Arz", one / 1e3, one / hi, anchor, all / 1e3, cores, all / one, rd);
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? atof(argv[1]) : 1.5;
    if (!(seconds > 0)) seconds = 1.5;
    int cores = lucent_cpu_count();
    printf("bench_mc: semi-infinite red channels, dr = MFP/20, nr = 640, nz = 640 (A(r,z) case), "
           "%d cores\n  ratio = per-core rate / MCML 1.2.2 (gcc -O2, one core; the faster end "
           "of its range); target >= 5x\n",
           cores);
    for (size_t i = 0; i < sizeof k_cases / sizeof k_cases[0]; i++) {
        run_case(&k_cases[i], false, cores, seconds);
        run_case(&k_cases[i], true, cores, seconds);
    }
    return 0;
}
