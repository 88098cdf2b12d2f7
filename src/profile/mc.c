/* Monte Carlo transport in multi-layered slabs: validation, the plan, the parallel run over
 * fixed chunks, and the reduction into MCML's normalised scores (Wang, Jacques & Zheng 1995).
 *
 * Determinism: photons are cut into chunks of MC_CHUNK; chunk c draws from RNG stream
 * (seed, c). Photon i belongs to batch floor(i B / N). Scores go to per-thread fixed-point
 * counters (integer sums do not depend on their order), so the result is bit-identical for
 * any number of threads. The same chunks are shared out between processes (lucent/dist.h:
 * MPI ranks, --part), whose counters are summed exactly, so the result does not depend on
 * the number of processes either. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "profile/mc_internal.h"

#define MC_CHUNK 1024

static double def(double v, double d) { return v != 0.0 ? v : d; }

void lucent_mc_defaults(const lucent_mc_desc *desc, lucent_mc_desc *dest)
{
    lucent_mc_desc d = *desc;
    d.n_above = def(d.n_above, 1.0);
    d.n_below = def(d.n_below, 1.0);
    if (!d.photons) d.photons = 100000;
    if (!d.batches) d.batches = 32;
    if ((uint64_t)d.batches > d.photons) d.batches = (int)d.photons;
    if (d.grid.dr == 0.0) {
        double mfp = 1.0; /* 1 mm when the first layer does not scatter */
        if (d.layers && d.layer_count > 0) {
            const lucent_mc_layer *l = &d.layers[0];
            double st = l->sigma_a + l->sigma_s * (1.0 - l->g);
            if (st > 0.0 && isfinite(st)) mfp = 1.0 / st;
        }
        d.grid.dr = mfp / 20.0;
    }
    d.grid.dz = def(d.grid.dz, d.grid.dr);
    if (!d.grid.nr) d.grid.nr = 640;
    if (!d.grid.nz) d.grid.nz = 200;
    if (!d.grid.na) d.grid.na = 30;
    if (!d.label) d.label = "Monte Carlo";
    *dest = d;
}

static bool semi_infinite(const lucent_mc_layer *l) { return !(l->thickness > 0.0) || isinf(l->thickness); }

static lucent_status check_index(const char *field, double n)
{
    if (!(n >= 1.0 && n <= 10.0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: must be in [1, 10], got %g", field, n);
    return LUCENT_OK;
}

static lucent_status check_layer(const lucent_mc_layer *l, int i, int count)
{
    char f[64];
    snprintf(f, sizeof f, "layers[%d].n", i);
    lucent_status s = check_index(f, def(l->n, 1.0));
    if (s != LUCENT_OK) return s;
    if (!(l->sigma_a >= 0.0 && isfinite(l->sigma_a)))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers[%d].sigma_a: must be finite and >= 0, got %g", i,
                            l->sigma_a);
    if (!(l->sigma_s >= 0.0 && isfinite(l->sigma_s)))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers[%d].sigma_s: must be finite and >= 0, got %g", i,
                            l->sigma_s);
    if (!(l->g >= -1.0 && l->g <= 1.0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers[%d].g: must be in [-1, 1], got %g", i, l->g);
    if (isnan(l->thickness)) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers[%d].thickness: not a number", i);
    if (semi_infinite(l) && i != count - 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "layers[%d].thickness: only the last layer may be semi-infinite", i);
    if (semi_infinite(l) && l->sigma_a + l->sigma_s == 0.0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers[%d]: a semi-infinite layer must absorb or scatter", i);
    double st = l->sigma_a + l->sigma_s;
    if (st > 0.0 && (st < LUCENT_MC_MIN_SIGMA_T || st > LUCENT_MC_MAX_SIGMA_T))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "layers[%d].%s: sigma_t = sigma_a + sigma_s = %g mm^-1 is outside what the Monte Carlo can "
                            "step (%g to %g mm^-1, or 0 for a clear layer)",
                            i, l->sigma_s >= l->sigma_a ? "sigma_s" : "sigma_a", st, LUCENT_MC_MIN_SIGMA_T,
                            LUCENT_MC_MAX_SIGMA_T);
    if (!semi_infinite(l) && l->thickness > LUCENT_MC_MAX_THICKNESS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "layers[%d].thickness: %g mm is more than %g mm (leave it 0 or inf for semi-infinite)", i,
                            l->thickness, LUCENT_MC_MAX_THICKNESS);
    return LUCENT_OK;
}

static lucent_status check_grid(const lucent_mc_grid *g, bool a_rz)
{
    if (!(g->dr > 0.0 && isfinite(g->dr)) || !(g->dz > 0.0 && isfinite(g->dz)))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "grid: dr and dz must be finite and > 0");
    /* Bins are found as float(r / dr): a bin too small or a grid too large has no float representation. */
    if (g->dr < LUCENT_MC_MIN_BIN || g->dz < LUCENT_MC_MIN_BIN)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "grid.%s: %g mm is below %g mm, which cannot be represented",
                            g->dr < LUCENT_MC_MIN_BIN ? "dr" : "dz", g->dr < LUCENT_MC_MIN_BIN ? g->dr : g->dz,
                            LUCENT_MC_MIN_BIN);
    if (g->dr * g->nr > LUCENT_MC_MAX_EXTENT || g->dz * g->nz > LUCENT_MC_MAX_EXTENT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "grid.%s: the grid spans more than %g mm",
                            g->dr * g->nr > LUCENT_MC_MAX_EXTENT ? "dr" : "dz", LUCENT_MC_MAX_EXTENT);
    if (g->nr < 1 || g->nr > LUCENT_MC_MAX_RADIAL_BINS || g->nz < 1 || g->nz > LUCENT_MC_MAX_RADIAL_BINS || g->na < 1 ||
        g->na > LUCENT_MC_MAX_ANGLE_BINS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "grid: too many bins (nr %d, nz %d, na %d; at most %d, %d, %d)", g->nr, g->nz, g->na,
                            LUCENT_MC_MAX_RADIAL_BINS, LUCENT_MC_MAX_RADIAL_BINS, LUCENT_MC_MAX_ANGLE_BINS);
    double cells = (double)g->nr * (double)(a_rz ? (g->nz > g->na ? g->nz : g->na) : g->na);
    if (cells > LUCENT_MC_MAX_GRID_CELLS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "grid: too many bins (%.0f cells, at most %d)", cells,
                            LUCENT_MC_MAX_GRID_CELLS);
    return LUCENT_OK;
}

lucent_status lucent_mc_validate(const lucent_mc_desc *desc)
{
    lucent_mc_desc d;
    lucent_mc_defaults(desc, &d);
    if (!d.layers || d.layer_count < 1 || d.layer_count > LUCENT_MC_MAX_LAYERS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "layers: need 1 to %d layers, got %d", LUCENT_MC_MAX_LAYERS,
                            d.layer_count);
    for (int i = 0; i < d.layer_count; i++) {
        lucent_status s = check_layer(&d.layers[i], i, d.layer_count);
        if (s != LUCENT_OK) return s;
    }
    lucent_status s = check_index("n_above", d.n_above);
    if (s == LUCENT_OK) s = check_index("n_below", d.n_below);
    if (s != LUCENT_OK) return s;
    if ((double)d.photons > LUCENT_MC_MAX_PHOTONS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "photons: at most 1e12, got %llu",
                            (unsigned long long)d.photons);
    if (d.batches < 1 || d.batches > LUCENT_MC_MAX_BATCHES)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "batches: must be in [1, %d], got %d", LUCENT_MC_MAX_BATCHES,
                            d.batches);
    return check_grid(&d.grid, d.score_a_rz);
}

/* Normal-incidence Fresnel reflectance ((n0 - n1) / (n0 + n1))^2 (MCML manual eq. 3.1; base/optics.h);
 * with a clear first layer, the multiple reflections inside it (eq. 3.2). */
double lucent_mc_specular(const lucent_mc_desc *desc)
{
    double n0 = def(desc->n_above, 1.0), n1 = def(desc->layers[0].n, 1.0);
    double r1 = lucent_fresnel_dielectric(1.0, n1 / n0, NULL);
    const lucent_mc_layer *l0 = &desc->layers[0];
    if (l0->sigma_a + l0->sigma_s == 0.0 && desc->layer_count > 1) {
        double n2 = def(desc->layers[1].n, 1.0), r2 = lucent_fresnel_dielectric(1.0, n2 / n1, NULL);
        r1 += (1.0 - r1) * (1.0 - r1) * r2 / (1.0 - r1 * r2);
    }
    return r1;
}

static float cos_crit(double n_from, double n_to)
{
    return n_from > n_to ? (float)sqrt(1.0 - n_to * n_to / (n_from * n_from)) : 0.0f;
}

static void plan_layer(const lucent_mc_desc *d, int i, double z0, mc_layer_k *k)
{
    const lucent_mc_layer *l = &d->layers[i];
    double mut = l->sigma_a + l->sigma_s, g = l->g, n = def(l->n, 1.0);
    k->z0 = (float)z0;
    k->z1 = semi_infinite(l) ? INFINITY : (float)(z0 + l->thickness);
    k->clear = mut == 0.0;
    k->mut = (float)mut;
    k->inv_mut = mut > 0.0 ? (float)(1.0 / mut) : INFINITY;
    k->absorb = mut > 0.0 ? (float)(l->sigma_a / mut) : 0.0f;
    k->g = (float)g;
    k->g_exact = g;
    k->hg_kind = g == 0.0 ? 0 : fabs(g) == 1.0 ? 3 : fabs(g) < 0.01 ? 2 : 1;
    k->hg = lucent_hg_prepare_f(g);
    k->n = (float)n;
    double up = i == 0 ? d->n_above : def(d->layers[i - 1].n, 1.0);
    double down = i == d->layer_count - 1 ? d->n_below : def(d->layers[i + 1].n, 1.0);
    k->n_up = (float)up;
    k->n_down = (float)down;
    k->cos_crit_up = cos_crit(n, up);
    k->cos_crit_down = cos_crit(n, down);
}

static void plan_layout(mc_plan *p)
{
    mc_layout *l = &p->lay;
    size_t nr1 = (size_t)p->nr + 1, nz1 = (size_t)p->nz + 1, na = (size_t)p->na;
    l->rd_r = 0;
    l->tt_r = nr1;
    l->rd_a = 2 * nr1;
    l->tt_a = l->rd_a + na;
    l->a_z = l->tt_a + na;
    l->a_l = l->a_z + nz1;
    l->capped = l->a_l + (size_t)p->layer_count;
    l->a_zl = l->capped + 1;
    l->batch_size = l->a_zl + (size_t)p->nz + (size_t)p->layer_count;
    l->rd_ra = 0;
    l->tt_ra = nr1 * na;
    l->a_rz = 2 * nr1 * na;
    l->grid_size = l->a_rz + (p->score_a_rz ? nr1 * nz1 : 0);
}

static void make_plan(const lucent_mc_desc *d, mc_plan *p)
{
    memset(p, 0, sizeof *p);
    p->layer_count = d->layer_count;
    double z = 0.0;
    for (int i = 0; i < d->layer_count; i++) {
        plan_layer(d, i, z, &p->layers[i]);
        if (!semi_infinite(&d->layers[i])) z += d->layers[i].thickness;
    }
    p->nr = d->grid.nr;
    p->nz = d->grid.nz;
    p->na = d->grid.na;
    p->r_lim = d->last_bin_collects ? p->nr - 1 : p->nr;
    p->z_lim = d->last_bin_collects ? p->nz - 1 : p->nz;
    p->dr = d->grid.dr;
    p->dz = d->grid.dz;
    p->inv_dr = (float)(1.0 / d->grid.dr);
    p->inv_dz = (float)(1.0 / d->grid.dz);
    p->inv_da = 2.0 * p->na / M_PI; /* da = pi / (2 na) */
    /* Every counter sums at most N units of weight: keep N * scale below 2^62. */
    int bits = 0;
    while (bits < 62 && ((uint64_t)1 << bits) < d->photons) bits++;
    p->scale = ldexp(1.0, bits > 22 ? 62 - bits : 40);
    p->photons = d->photons;
    p->batches = d->batches;
    p->w_launch = (float)(1.0 - lucent_mc_specular(d));
    /* MCML launches into the first turbid layer when the first layer is clear. */
    p->launch_layer = p->layers[0].clear && d->layer_count > 1 ? 1 : 0;
    p->launch_z = p->layers[p->launch_layer].z0;
    p->score_a_rz = d->score_a_rz;
    p->seed = d->seed;
    plan_layout(p);
}

void mc_fold_zl(const mc_plan *p, int64_t *batch)
{
    for (int b = 0; b < p->batches; b++) {
        int64_t *c = batch + (size_t)b * p->lay.batch_size;
        for (int l = 0; l < p->layer_count; l++) { /* layer l's bins: those of its top to its bottom */
            int lo = mc_depth_bin(p, p->layers[l].z0), hi = mc_depth_bin(p, p->layers[l].z1);
            for (int iz = lo; iz <= hi; iz++) {
                int64_t *v = c + p->lay.a_zl + (size_t)(iz + l);
                c[p->lay.a_z + (size_t)iz] += *v;
                c[p->lay.a_l + (size_t)l] += *v;
                *v = 0;
            }
        }
    }
}

/* ---- the kernels ---- */

static void trace_scalar(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch,
                         int64_t *grid, int64_t *scratch)
{
    (void)scratch;
    mc_trace(plan, rng, begin, end, batch, grid);
}

static const mc_kernel k_kernels[] = {
    {LUCENT_ISA_SCALAR, 1, trace_scalar, NULL, NULL, NULL},
#if defined(LUCENT_SIMD_X86)
    {LUCENT_ISA_AVX2, 8, mc_trace_avx2, mc_simd_neglog_avx2, mc_simd_sincos_avx2, mc_simd_hg_avx2},
    {LUCENT_ISA_AVX512, 16, mc_trace_avx512, mc_simd_neglog_avx512, mc_simd_sincos_avx512, mc_simd_hg_avx512},
#endif
};

const mc_kernel *mc_kernel_get(lucent_isa isa)
{
    if (isa == LUCENT_ISA_AUTO) isa = lucent_isa_active();
    if (!lucent_isa_supported(isa)) return NULL;
    for (size_t i = 0; i < sizeof k_kernels / sizeof k_kernels[0]; i++)
        if (k_kernels[i].isa == isa) return &k_kernels[i];
    return NULL;
}

/* ---- the parallel run ---- */

typedef struct run_ctx {
    const mc_plan *plan;
    const mc_kernel *kernel;
    int64_t **batch, **grid, **scratch; /* per thread */
    lucent_progress *progress;
} run_ctx;

static lucent_status run_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    run_ctx *c = ctx;
    lucent_rng rng;
    lucent_rng_init(c->plan->seed, chunk, &rng);
    c->kernel->trace(c->plan, &rng, begin, end, c->batch[thread], c->grid[thread], c->scratch[thread]);
    lucent_progress_add(c->progress, end - begin);
    return LUCENT_OK;
}

static void free_counters(int64_t **v, int n)
{
    if (!v) return;
    for (int i = 0; i < n; i++) free(v[i]);
    free(v);
}

static int64_t **alloc_counters(int n, size_t size)
{
    int64_t **v = calloc((size_t)n, sizeof *v);
    if (!v) return NULL;
    for (int i = 0; i < n; i++) {
        v[i] = calloc(size ? size : 1, sizeof **v);
        if (!v[i]) {
            free_counters(v, n);
            return NULL;
        }
    }
    return v;
}

/* Sums thread t's counters into thread 0's (integers: the order does not matter). */
static void sum_counters(int64_t **v, int n, size_t size)
{
    for (int t = 1; t < n; t++)
        for (size_t i = 0; i < size; i++) v[0][i] += v[t][i];
}

/* ---- the reduction into normalised scores ---- */

typedef struct reducer {
    const mc_plan *plan;
    const int64_t *batch; /* batches * batch_size, summed over threads */
    double *nb;           /* photons in each batch */
} reducer;

/* Weight fraction in counter `off` of batch b. */
static double frac(const reducer *r, int b, size_t off)
{
    return (double)r->batch[(size_t)b * r->plan->lay.batch_size + off] / r->plan->scale;
}

/* Standard error of a mean from batch means x[b] of nb[b] photons each (n in all): the
 * variance of the ratio estimator, sum (n_b / n)^2 (x_b - mean)^2 * B / (B - 1). */
static double batch_se(const double *x, const double *nb, int count, double mean, double n)
{
    double v = 0.0;
    for (int b = 0; b < count; b++) {
        double f = nb[b] / n * (x[b] - mean);
        v += f * f;
    }
    return count > 1 ? sqrt(v * count / (count - 1)) : 0.0;
}

/* Mean per photon and its standard error (batch means, weighted by batch size) of the sum of
 * counters [off, off + count) (MCML's totals are sums of their bins). */
static void batch_stat(const reducer *r, size_t off, size_t count, double *mean, double *se)
{
    int nb = r->plan->batches;
    double n = (double)r->plan->photons, total = 0.0;
    double x[LUCENT_MC_MAX_BATCHES];
    for (int b = 0; b < nb; b++) {
        double s = 0.0;
        for (size_t i = 0; i < count; i++) s += frac(r, b, off + i);
        total += s;
        x[b] = s / r->nb[b];
    }
    *mean = total / n;
    *se = batch_se(x, r->nb, nb, *mean, n);
}

/* One 1-D score: bins [0, count) at off, each divided by norm(i). */
static void reduce_1d(const reducer *r, size_t off, int count, double (*norm)(const mc_plan *, int), double *dest,
                      double *dest_se)
{
    for (int i = 0; i < count; i++) {
        double m, se, k = norm(r->plan, i);
        batch_stat(r, off + (size_t)i, 1, &m, &se);
        dest[i] = m / k;
        dest_se[i] = se / k;
    }
}

static double norm_ring(const mc_plan *p, int i)
{
    return 2.0 * M_PI * (i + 0.5) * p->dr * p->dr; /* MCML manual eq. 4.5 */
}

static double norm_solid_angle(const mc_plan *p, int j)
{
    double da = M_PI / (2.0 * p->na);
    return 4.0 * M_PI * sin((j + 0.5) * da) * sin(da / 2.0); /* MCML manual eq. 4.7 */
}

static double norm_dz(const mc_plan *p, int k)
{
    (void)k;
    return p->dz;
}

static double norm_one(const mc_plan *p, int k)
{
    (void)p, (void)k;
    return 1.0;
}

static lucent_status alloc_result(lucent_mc_result *r, int nl, const lucent_mc_grid *g, bool rz)
{
    size_t nr = (size_t)g->nr, nz = (size_t)g->nz, na = (size_t)g->na;
    struct {
        double **p;
        size_t n;
    } a[] = {
        {&r->a_layer, nl},    {&r->a_layer_se, nl}, {&r->rd_r, nr},
        {&r->rd_r_se, nr},    {&r->tt_r, nr},       {&r->tt_r_se, nr},
        {&r->rd_a, na},       {&r->rd_a_se, na},    {&r->tt_a, na},
        {&r->tt_a_se, na},    {&r->a_z, nz},        {&r->a_z_se, nz},
        {&r->rd_ra, nr * na}, {&r->tt_ra, nr * na}, {&r->a_rz, rz ? nr * nz : 0},
    };
    for (size_t i = 0; i < sizeof a / sizeof a[0]; i++) {
        if (!a[i].n) continue;
        *a[i].p = calloc(a[i].n, sizeof(double));
        if (!*a[i].p) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "Monte Carlo: out of memory");
    }
    return LUCENT_OK;
}

static void reduce_grids(const mc_plan *p, const int64_t *grid, const lucent_mc_grid *g, lucent_mc_result *r)
{
    double n = (double)p->photons * p->scale;
    for (int i = 0; i < p->nr; i++)
        for (int j = 0; j < p->na; j++) {
            double k = n * norm_ring(p, i) * norm_solid_angle(p, j);
            size_t at = (size_t)i * (size_t)p->na + (size_t)j;
            r->rd_ra[at] = (double)grid[p->lay.rd_ra + at] / k;
            r->tt_ra[at] = (double)grid[p->lay.tt_ra + at] / k;
        }
    if (!p->score_a_rz) return;
    for (int i = 0; i < p->nr; i++)
        for (int k = 0; k < p->nz; k++) {
            double v = (double)grid[p->lay.a_rz + (size_t)i * (size_t)(p->nz + 1) + (size_t)k];
            r->a_rz[(size_t)i * (size_t)p->nz + (size_t)k] = v / (n * norm_ring(p, i) * g->dz);
        }
}

static lucent_status reduce(const lucent_mc_desc *d, const mc_plan *p, const int64_t *batch, const int64_t *grid,
                            lucent_mc_result *r)
{
    memset(r, 0, sizeof *r);
    r->photons = p->photons;
    r->batches = p->batches;
    r->layer_count = p->layer_count;
    r->grid = d->grid;
    r->rsp = lucent_mc_specular(d);
    lucent_status s = alloc_result(r, p->layer_count, &d->grid, p->score_a_rz);
    double *nb = malloc((size_t)p->batches * sizeof *nb);
    if (s == LUCENT_OK && !nb) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s != LUCENT_OK) {
        free(nb);
        lucent_mc_result_free(r);
        return s;
    }
    for (int b = 0; b < p->batches; b++) { /* batch b holds photons i with floor(i B / N) = b */
        uint64_t lo = ((uint64_t)b * p->photons + (uint64_t)p->batches - 1) / (uint64_t)p->batches;
        uint64_t hi = ((uint64_t)(b + 1) * p->photons + (uint64_t)p->batches - 1) / (uint64_t)p->batches;
        nb[b] = (double)(hi - lo);
    }
    reducer rd = {p, batch, nb};
    const mc_layout *l = &p->lay;
    size_t nr1 = (size_t)p->nr + 1;
    batch_stat(&rd, l->rd_r, nr1, &r->rd, &r->rd_se);
    batch_stat(&rd, l->tt_r, nr1, &r->tt, &r->tt_se);
    batch_stat(&rd, l->a_l, (size_t)p->layer_count, &r->a, &r->a_se);
    double unused;
    batch_stat(&rd, l->rd_r + (size_t)p->nr, 1, &r->rd_beyond, &unused);
    batch_stat(&rd, l->tt_r + (size_t)p->nr, 1, &r->tt_beyond, &unused);
    batch_stat(&rd, l->a_z + (size_t)p->nz, 1, &r->a_z_beyond, &unused);
    reduce_1d(&rd, l->a_l, p->layer_count, norm_one, r->a_layer, r->a_layer_se);
    reduce_1d(&rd, l->rd_r, p->nr, norm_ring, r->rd_r, r->rd_r_se);
    reduce_1d(&rd, l->tt_r, p->nr, norm_ring, r->tt_r, r->tt_r_se);
    reduce_1d(&rd, l->rd_a, p->na, norm_solid_angle, r->rd_a, r->rd_a_se);
    reduce_1d(&rd, l->tt_a, p->na, norm_solid_angle, r->tt_a, r->tt_a_se);
    reduce_1d(&rd, l->a_z, p->nz, norm_dz, r->a_z, r->a_z_se);
    /* balance: the rows rd_r .. a_l are contiguous except for rd_a, tt_a (which repeat Rd, Tt)
     * and a_z (which repeats A): sum the per-batch totals directly. */
    double n = (double)p->photons, mean = 0.0, x[LUCENT_MC_MAX_BATCHES];
    for (int b = 0; b < p->batches; b++) {
        double t = 0.0;
        for (size_t i = 0; i < 2 * nr1; i++) t += frac(&rd, b, l->rd_r + i);
        for (int i = 0; i < p->layer_count; i++) t += frac(&rd, b, l->a_l + (size_t)i);
        mean += t;
        x[b] = t / nb[b];
    }
    mean /= n;
    r->balance = r->rsp + mean;
    r->balance_se = batch_se(x, nb, p->batches, mean, n);
    free(nb);
    reduce_grids(p, grid, &d->grid, r);
    return LUCENT_OK;
}

lucent_status lucent_mc_run(const lucent_mc_desc *desc, lucent_mc_result *dest)
{
    memset(dest, 0, sizeof *dest);
    lucent_status s = lucent_mc_validate(desc);
    if (s != LUCENT_OK) return s;
    lucent_mc_desc d;
    lucent_mc_defaults(desc, &d);
    mc_plan *plan = malloc(sizeof *plan);
    if (!plan) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "Monte Carlo: out of memory");
    make_plan(&d, plan);
    int threads = d.pool ? lucent_pool_threads(d.pool) : 1;
    size_t bsize = plan->lay.batch_size * (size_t)plan->batches;
    const mc_kernel *kernel = mc_kernel_get(LUCENT_ISA_AUTO);
    if (!kernel) kernel = mc_kernel_get(LUCENT_ISA_SCALAR);
    size_t scratch = kernel->lanes > 1 ? mc_scratch_size(plan) : 0;
    double per_thread = (double)(bsize + plan->lay.grid_size + scratch) * sizeof(int64_t);
    if (per_thread * threads > (double)LUCENT_MC_MAX_TALLY_BYTES) {
        free(plan);
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: the scores take %.0f MB per thread, %.0f MB for %d threads: above the %.0f MB limit; "
                            "use fewer threads, fewer batches or a smaller grid",
                            d.label, per_thread / 1e6, per_thread * threads / 1e6, threads,
                            (double)LUCENT_MC_MAX_TALLY_BYTES / 1e6);
    }
    run_ctx ctx = {plan,
                   kernel,
                   alloc_counters(threads, bsize),
                   alloc_counters(threads, plan->lay.grid_size),
                   alloc_counters(threads, scratch),
                   NULL};
    if (!ctx.batch || !ctx.grid || !ctx.scratch) {
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "Monte Carlo: out of memory for the scores");
    } else {
        ctx.progress = lucent_progress_begin(d.label, d.photons);
        s = lucent_parallel_for_share(d.pool, d.photons, MC_CHUNK, run_chunk, &ctx, lucent_dist_share());
        lucent_progress_end(ctx.progress);
    }
    if (s == LUCENT_OK) {
        sum_counters(ctx.batch, threads, bsize);
        sum_counters(ctx.grid, threads, plan->lay.grid_size);
    }
    /* the other processes' counters (integers: exact in any order) */
    s = lucent_dist_sum(s, LUCENT_DIST_I64, s == LUCENT_OK ? ctx.batch[0] : NULL, bsize);
    s = lucent_dist_sum(s, LUCENT_DIST_I64, s == LUCENT_OK ? ctx.grid[0] : NULL, plan->lay.grid_size);
    if (s == LUCENT_OK) mc_fold_zl(plan, ctx.batch[0]);
    if (s == LUCENT_OK) s = reduce(&d, plan, ctx.batch[0], ctx.grid[0], dest);
    if (s == LUCENT_OK) {
        for (int b = 0; b < plan->batches; b++)
            dest->capped += (uint64_t)ctx.batch[0][(size_t)b * plan->lay.batch_size + plan->lay.capped];
        if (dest->capped)
            lucent_log(LUCENT_LOG_WARN,
                       "%s: %llu photons reached the step limit (%d steps): the medium barely absorbs; results are "
                       "lower bounds",
                       d.label, (unsigned long long)dest->capped, LUCENT_MC_MAX_STEPS);
    }
    free_counters(ctx.batch, threads);
    free_counters(ctx.grid, threads);
    free_counters(ctx.scratch, threads);
    free(plan);
    return s;
}

void lucent_mc_result_free(lucent_mc_result *r)
{
    double **a[] = {&r->a_layer, &r->a_layer_se, &r->rd_r, &r->rd_r_se, &r->tt_r,  &r->tt_r_se, &r->rd_a, &r->rd_a_se,
                    &r->tt_a,    &r->tt_a_se,    &r->a_z,  &r->a_z_se,  &r->rd_ra, &r->tt_ra,   &r->a_rz};
    for (size_t i = 0; i < sizeof a / sizeof a[0]; i++) free(*a[i]);
    memset(r, 0, sizeof *r);
}
