/* Benchmark of the path tracer (issue 7, item 5): the time to reach 5% per-pixel relative RMS error on
 * a Skin1 sphere of radius 10 mm (rough boundary, alpha 0.3, eta 1.3; a delta sun from the side; the
 * camera at 6 R with a 25 degree vertical field of view; 128 x 128; bench/skin1-sphere.json).
 * Anchor: Blender 3.4's Cycles with the same volume and rough glass on this kind of machine reaches
 * 51% after 22 s and 27% after 91 s, about 45 minutes to 5%. Target: 10x sooner (5% within ~270 s).
 *
 * The error is measured, not taken from the tracer's own variance estimate: two independent
 * progressive renders A and B (seeds 1 and 2) stop at the same sample counts; for one estimate,
 * E[(a - b)^2] = 2 var, so at each checkpoint the squared relative error of a pixel is
 * (a - b)^2 / (2 m^2), with m the mean of A and B at the last checkpoint (the best estimate of the
 * true value there). Pixels: those fully covered by the sphere in both runs. Two errors:
 *   luminance: RMS over pixels of the relative error of Y = 0.2126 R + 0.7152 G + 0.0722 B;
 *   RGB:       RMS over pixels and channels of each channel's relative error (every channel counts
 *              as much in the dark limb, where blue is 1e-9 of the lit side, as in the light).
 * Time: the wall clock of one run (the mean of A and B), 2 threads, and its CPU time over the threads
 * (what the wall clock would be on an unloaded machine: the machine is shared). The result uses adaptive sampling
 * (lucent_tracer_desc.adaptive: samples where the relative variance is, still unbiased); for
 * comparison also run: one sample per pixel and pass (UNIFORM_SECONDS), and next-event estimation only
 * at boundary vertices, Cycles' strategy (CYCLES_SECONDS).
 * Then the default scenes' references (issue 12 section 3, references() below).
 * Then the efficiency on the dragon (efficiency() below).
 * Usage: bench_trace [references] [max_seconds_per_run (default 300)] [threads (default 2)]
 *   references: only the default scenes' references (BENCH_REFERENCE_SECONDS each, default 60)
 *   bench_trace efficiency: only noise^2 x CPU on the dragon at 128 x 128 (BENCH_EFFICIENCY_PASSES) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/lucent.h"

#ifndef LUCENT_SOURCE_DIR
#define LUCENT_SOURCE_DIR "."
#endif

enum { MAX_CHECKPOINTS = 40 };
#define CYCLES_SECONDS 30.0
#define UNIFORM_SECONDS 60.0

typedef struct run {
    lucent_tracer *tracer;
    lucent_trace_result last;
    lucent_image *snap[MAX_CHECKPOINTS];
    double seconds[MAX_CHECKPOINTS], cpu[MAX_CHECKPOINTS];
} run;

typedef struct errors {
    double lum, rgb;
    int pixels;
} errors;

static const double k_lum[3] = {0.2126, 0.7152, 0.0722};

static void die(const char *what)
{
    fprintf(stderr, "bench_trace: %s: %s\n", what, lucent_last_error());
    exit(1);
}

/* Adds samples to r up to spp and keeps a copy of the image. */
static void advance(run *r, uint64_t seed, int spp, lucent_pool *pool, int cp)
{
    int more = spp - (int)r->last.spp;
    lucent_trace_result_free(&r->last);
    double c0 = lucent_cpu_seconds();
    if (lucent_tracer_render(r->tracer, &(lucent_trace_desc){.spp = more, .seed = seed, .pool = pool}, &r->last))
        die("render");
    r->cpu[cp] = (cp ? r->cpu[cp - 1] : 0) + lucent_cpu_seconds() - c0;
    if (lucent_image_clone(r->last.image, &r->snap[cp])) die("clone");
    r->seconds[cp] = r->last.seconds;
}

/* The errors of one estimate at checkpoint images a, b, normalised by the means ma, mb. */
static errors measure(const lucent_image *a, const lucent_image *b, const lucent_image *ma, const lucent_image *mb,
                      const lucent_image *cov)
{
    errors e = {0};
    double sl = 0, srgb = 0;
    int nrgb = 0;
    for (int p = 0; p < a->width * a->height; p++) {
        if (cov->data[p] < 0.999f) continue;
        double ya = 0, yb = 0, ym = 0;
        for (int c = 0; c < 3; c++) {
            double va = a->data[3 * p + c], vb = b->data[3 * p + c];
            double m = 0.5 * (ma->data[3 * p + c] + mb->data[3 * p + c]);
            ya += k_lum[c] * va, yb += k_lum[c] * vb, ym += k_lum[c] * m;
            if (m > 0) srgb += (va - vb) * (va - vb) / (2 * m * m), nrgb++;
        }
        if (ym > 0) sl += (ya - yb) * (ya - yb) / (2 * ym * ym), e.pixels++;
    }
    e.lum = sqrt(sl / e.pixels), e.rgb = sqrt(srgb / nrgb);
    return e;
}

/* Seconds at which error curve (t, e) reaches target: log-log interpolation, or extrapolation with
 * the Monte Carlo slope -1/2 from the last point (*extrapolated set). */
static double time_to(const double *t, const double *e, int n, double target, bool *extrapolated)
{
    *extrapolated = false;
    for (int i = 1; i < n; i++)
        if (e[i] <= target && e[i - 1] > target) {
            double f = log(e[i - 1] / target) / log(e[i - 1] / e[i]);
            return exp(log(t[i - 1]) + f * log(t[i] / t[i - 1]));
        }
    if (n && e[0] <= target) return t[0];
    *extrapolated = true;
    return n ? t[n - 1] * (e[n - 1] / target) * (e[n - 1] / target) : INFINITY;
}

static void load(const char *path, lucent_scene **sc)
{
    if (lucent_scene_load(path, NULL, sc)) die(path);
}

typedef struct curve {
    int n, spp[MAX_CHECKPOINTS];
    double t[MAX_CHECKPOINTS], u[MAX_CHECKPOINTS], lum[MAX_CHECKPOINTS], rgb[MAX_CHECKPOINTS];
    int pixels;
} curve;

static int g_threads = 2;

/* Two runs of the scene (with desc), checkpoints at doubling passes from first until the luminance
 * error (against the current mean) is below stop or a run has taken max_seconds. */
static void measure_curve(const lucent_scene *sc, const lucent_tracer_desc *desc, int first, double max_seconds,
                          double stop, lucent_pool *pool, curve *cv)
{
    run r[2] = {{0}};
    for (int k = 0; k < 2; k++)
        if (lucent_tracer_create(sc, desc, &r[k].tracer)) die("tracer");
    int n = 0;
    for (int spp = first; n < MAX_CHECKPOINTS; spp *= 2, n++) {
        for (int k = 0; k < 2; k++) advance(&r[k], 1 + k, spp, pool, n);
        cv->spp[n] = spp;
        cv->t[n] = 0.5 * (r[0].seconds[n] + r[1].seconds[n]);
        cv->u[n] = 0.5 * (r[0].cpu[n] + r[1].cpu[n]) / g_threads;
        errors now = measure(r[0].snap[n], r[1].snap[n], r[0].snap[n], r[1].snap[n], r[0].last.coverage);
        printf("    %6d passes  %7.1f s  (cpu / %d: %7.1f s; luminance error against the current mean %.3f)\n", spp,
               cv->t[n], g_threads, cv->u[n], now.lum);
        fflush(stdout);
        if (now.lum < stop || 2.2 * cv->t[n] > max_seconds) {
            n++;
            break;
        }
    }
    cv->n = n;
    for (int i = 0; i < n; i++) {
        errors e = measure(r[0].snap[i], r[1].snap[i], r[0].snap[n - 1], r[1].snap[n - 1], r[0].last.coverage);
        cv->lum[i] = e.lum, cv->rgb[i] = e.rgb, cv->pixels = e.pixels;
    }
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < n; i++) lucent_image_destroy(r[k].snap[i]);
        lucent_trace_result_free(&r[k].last);
        lucent_tracer_destroy(r[k].tracer);
    }
}

static void print_curve(const char *name, const curve *cv)
{
    printf("  %s (%d sphere pixels):\n   passes   wall s  cpu/%d s   luminance   RGB\n", name, cv->pixels, g_threads);
    for (int i = 0; i < cv->n; i++)
        printf("  %7d  %7.1f  %8.1f   %7.1f%%  %7.1f%%\n", cv->spp[i], cv->t[i], cv->u[i], 100 * cv->lum[i],
               100 * cv->rgb[i]);
}

/* The error at time t on curve (x, e), interpolated in log-log (0 when t is outside). */
static double error_at(const double *x, const double *e, int n, double t)
{
    for (int i = 1; i < n; i++)
        if (x[i] >= t && x[i - 1] < t) {
            double f = log(t / x[i - 1]) / log(x[i] / x[i - 1]);
            return exp(log(e[i - 1]) + f * log(e[i] / e[i - 1]));
        }
    return 0;
}

static void report_clock(const char *clock, const curve *cv, const double *x)
{
    bool xl, xr;
    double tl = time_to(x, cv->lum, cv->n, 0.05, &xl), tr = time_to(x, cv->rgb, cv->n, 0.05, &xr);
    double l22 = error_at(x, cv->lum, cv->n, 22), r22 = error_at(x, cv->rgb, cv->n, 22);
    double l91 = error_at(x, cv->lum, cv->n, 91), r91 = error_at(x, cv->rgb, cv->n, 91);
    printf("  %s: to 5%%: luminance %.0f s%s, RGB %.0f s%s; at 22 s %.1f%% / %.1f%%; at 91 s %.1f%% / %.1f%%; "
           "Cycles / this: %.1fx (luminance), %.1fx (RGB)\n",
           clock, tl, xl ? " (extrapolated)" : "", tr, xr ? " (extrapolated)" : "", 100 * l22, 100 * r22, 100 * l91,
           100 * r91, 2700 / tl, 2700 / tr);
}

static void report(const curve *cv)
{
    printf("\n  Cycles 3.4 (anchor): 51%% at 22 s, 27%% at 91 s, ~2700 s to 5%%; target 10x: 5%% within 270 s\n");
    report_clock("wall clock      ", cv, cv->t);
    report_clock("cpu / threads   ", cv, cv->u);
}

/* ---- the default scenes' references (issue 12 section 3) ----
 * Today's estimator (plain_flights + nee_every_vertex: a ray query per flight, next-event estimation
 * from every vertex; bit for bit the tracer before the change) against the default one, pass by pass
 * interleaved (so both see the same load on the shared machine), at the size lucent compare renders
 * (256 x 256; the spheres 384 x 128). Time is CPU time over the threads: the wall clock on an
 * unloaded machine. Noise is what lucent compare reports as the reference's noise:
 * sqrt(sum var / sum mean^2) over the pixels the object covers (coverage >= 0.5), from the tracer's
 * own variance. Time to 5%: the fixed cost (scene set-up, the guiding field's pre-pass and the first
 * pass, measured) plus the passes' cost scaled by (noise / 5%)^2. */
typedef struct reference_run {
    lucent_tracer *tracer;
    lucent_trace_result last;
    double cpu, first_cpu;
    int passes;
} reference_run;

static double reference_noise(const lucent_trace_result *r)
{
    size_t n = (size_t)r->image->width * (size_t)r->image->height;
    float *mask = malloc(n * sizeof *mask);
    if (!mask) die("out of memory");
    for (size_t p = 0; p < n; p++) mask[p] = r->coverage->data[p] >= 0.5f ? 1.0f : 0.0f;
    double noise = lucent_compare_reference_noise(r->image, r->variance, mask);
    free(mask);
    return noise;
}

static void reference_pass(reference_run *r, lucent_pool *pool)
{
    lucent_trace_result_free(&r->last);
    double c0 = lucent_cpu_seconds();
    if (lucent_tracer_render(r->tracer, &(lucent_trace_desc){.spp = 1, .seed = 1, .pool = pool}, &r->last))
        die("render");
    double c = (lucent_cpu_seconds() - c0) / g_threads;
    r->cpu += c, r->passes++;
    if (r->passes == 1) r->first_cpu = r->cpu; /* set-up, the guiding field's pre-pass and one pass */
}

/* Seconds (CPU over the threads) to noise 5%, and the noise at `at` seconds, of a run. */
static void reference_figures(const reference_run *r, double at, double *t5, double *noise_at)
{
    double noise = reference_noise(&r->last),
           per_pass = r->passes > 1 ? (r->cpu - r->first_cpu) / (r->passes - 1) : r->cpu;
    double fixed = r->first_cpu - per_pass, passes = r->cpu - fixed;
    *t5 = fixed + passes * (noise / 0.05) * (noise / 0.05);
    *noise_at = at > fixed ? noise * sqrt(passes / (at - fixed)) : INFINITY;
}

/* Three estimators on the same scene: today's (before section 3), the camera paths alone (light
 * paths off: the third pass's), and the default (light paths for dense media, docs/trace.md). */
enum { REF_RUNS = 3 };
static const char *const ref_names[REF_RUNS] = {"today", "camera paths", "now"};

static void reference_scene(const char *file, const char *const *sets, int nsets, double budget, lucent_pool *pool)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/data/scenes/%s", LUCENT_SOURCE_DIR, file);
    lucent_scene *sc;
    if (lucent_scene_load(path, &(lucent_scene_load_desc){.overrides = sets, .override_count = nsets}, &sc)) die(path);
    reference_run runs[REF_RUNS] = {{0}};
    const lucent_tracer_desc today = {.plain_flights = true, .nee_every_vertex = true};
    int mode = sc->render.trace.light_paths;
    for (int k = 0; k < REF_RUNS; k++) {
        double c0 = lucent_cpu_seconds();
        sc->render.trace.light_paths = k == 1 ? LUCENT_LIGHT_PATHS_OFF : mode; /* the tracer copies it */
        if (lucent_tracer_create(sc, k == 0 ? &today : NULL, &runs[k].tracer)) die("tracer");
        runs[k].cpu = (lucent_cpu_seconds() - c0) / g_threads; /* set-up (the BVH) */
    }
    bool more = true;
    while (more) {
        more = false;
        for (int k = 0; k < REF_RUNS; k++)
            if (runs[k].cpu < budget) reference_pass(&runs[k], pool), more = true;
    }
    printf("  %-18s %dx%d", file, runs[0].last.image->width, runs[0].last.image->height);
    double t5[REF_RUNS], n60[REF_RUNS];
    for (int k = 0; k < REF_RUNS; k++) {
        reference_figures(&runs[k], 60.0, &t5[k], &n60[k]);
        const lucent_trace_cost *c = &runs[k].last.cost;
        printf(
            "%s%s: %4d passes in %5.1f s, noise %5.1f%% (at 60 s %5.1f%%), to 5%% %7.0f s; per camera path %.1f rays + "
            "%.1f distance queries, %.2f light paths",
            k ? " | " : "  ", ref_names[k], runs[k].passes, runs[k].cpu, 100 * reference_noise(&runs[k].last),
            100 * n60[k], t5[k], (double)c->rays / c->paths, (double)c->points / c->paths,
            (double)c->photons / c->paths);
    }
    printf(" | time to 5%%: now %.2fx faster than today, %.2fx than the camera paths\n", t5[0] / t5[2], t5[1] / t5[2]);
    fflush(stdout);
    for (int k = 0; k < REF_RUNS; k++) lucent_trace_result_free(&runs[k].last), lucent_tracer_destroy(runs[k].tracer);
    lucent_scene_destroy(sc);
}

/* BENCH_REFERENCE_SECONDS (default 60): each estimator's CPU seconds over the threads per scene;
 * BENCH_REFERENCE_SCENES: the scenes (names separated by commas; default all four). */
static void references(lucent_pool *pool)
{
    const char *env = getenv("BENCH_REFERENCE_SECONDS");
    double budget = env && atof(env) > 0 ? atof(env) : 60.0;
    printf("\nbench_trace: the default scenes' references, today's estimator (a ray query per flight, next-event "
           "estimation from every vertex), the camera paths alone (light paths off) and the default one, interleaved, "
           "%.0f s each (CPU over %d threads); "
           "anchor (issue 12): dragon-marble 22 spp in 60 s, 28%% noise; goal 10%% in 60 s, 5%% in 300 s; measured "
           "(docs/trace.md, 2026-12-03, ninth pass): default 9.5%% at 60 s (9.7%% at the anchor's speed), 213 s to "
           "5%%, before section 3 1656 s\n",
           budget, g_threads);
    const char *square[] = {"render.width=256", "render.height=256"},
               *wide[] = {"render.width=384", "render.height=128"};
    const char *files[] = {"dragon-marble.json", "bunny-skin.json", "bunny-jade.json", "spheres-skin.json"};
    const char *only = getenv("BENCH_REFERENCE_SCENES"); /* e.g. "dragon-marble,bunny-jade" (default: all) */
    for (int i = 0; i < 4; i++) {
        char stem[64];
        snprintf(stem, sizeof stem, "%.*s", (int)(strlen(files[i]) - 5), files[i]);
        if (!only || strstr(only, stem)) reference_scene(files[i], i == 3 ? wide : square, 2, budget, pool);
    }
}

/* ---- efficiency on the dragon (issue 12 section 3, docs/trace.md "Measured in the third pass") ----
 * noise^2 x CPU seconds of the passes (lower is better; independent of the budget at a fixed
 * estimator): dragon-marble at 128 x 128, BENCH_EFFICIENCY_PASSES passes (default 50) of one sample
 * per pixel on one thread, seed BENCH_EFFICIENCY_SEED (default 1), the camera paths alone (light
 * paths off) and the default. The passes' CPU leaves out the fixed cost (set-up, the guiding field's
 * pre-pass): the first pass's cost beyond an ordinary one. */
static void efficiency_run(int passes, uint64_t seed, bool light_paths)
{
    const char *sets[] = {"render.width=128", "render.height=128",
                          light_paths ? "render.light_paths=auto" : "render.light_paths=off"};
    lucent_scene *sc;
    if (lucent_scene_load(LUCENT_SOURCE_DIR "/data/scenes/dragon-marble.json",
                          &(lucent_scene_load_desc){.overrides = sets, .override_count = 3}, &sc))
        die("dragon-marble.json");
    lucent_pool *one = lucent_pool_create(1);
    reference_run r = {0};
    double c0 = lucent_cpu_seconds();
    if (lucent_tracer_create(sc, NULL, &r.tracer)) die("tracer");
    r.cpu = lucent_cpu_seconds() - c0;
    for (int i = 0; i < passes; i++) {
        lucent_trace_result_free(&r.last);
        double c = lucent_cpu_seconds();
        if (lucent_tracer_render(r.tracer, &(lucent_trace_desc){.spp = 1, .seed = seed, .pool = one}, &r.last))
            die("render");
        r.cpu += lucent_cpu_seconds() - c, r.passes++;
        if (r.passes == 1) r.first_cpu = r.cpu;
    }
    double per_pass = (r.cpu - r.first_cpu) / (r.passes - 1), fixed = r.first_cpu - per_pass;
    double noise = reference_noise(&r.last), paths = (double)r.last.cost.paths;
    const lucent_trace_cost *c = &r.last.cost;
    printf("\nbench_trace: efficiency on dragon-marble 128 x 128, %s, %d passes on 1 thread, seed %llu: noise %.2f%%, "
           "passes %.1f CPU s (fixed %.1f s), noise^2 x CPU s = %.3f (lower is better); per camera path %.1f rays, "
           "%.2f distance queries, %.1f scatterings, %.2f next-event estimates, %.2f light paths (their queries "
           "and scatterings included)\n",
           light_paths ? "light paths (the default)" : "camera paths alone", passes, (unsigned long long)seed,
           100 * noise, r.cpu - fixed, fixed, noise * noise * (r.cpu - fixed), c->rays / paths, c->points / paths,
           c->scatters / paths, c->nee / paths, c->photons / paths);
    fflush(stdout);
    lucent_trace_result_free(&r.last);
    lucent_tracer_destroy(r.tracer);
    lucent_pool_destroy(one);
    lucent_scene_destroy(sc);
}

static void efficiency(void)
{
    const char *env = getenv("BENCH_EFFICIENCY_PASSES"), *seed_env = getenv("BENCH_EFFICIENCY_SEED");
    int passes = env && atoi(env) > 1 ? atoi(env) : 50;
    uint64_t seed = seed_env ? strtoull(seed_env, NULL, 10) : 1;
    printf("\nbench_trace: figures measured (docs/trace.md, 30 passes, load 1-2): camera paths 0.786 / 0.761, "
           "light paths 0.706 / 0.628 (seeds 1 / 2, 2026-12-03, with the depth lattice; before it 0.967 / 0.957 and "
           "0.754 / 1.080; before the light shares 0.941 / 1.395, 50 passes in the fourth pass on section 3, before "
           "the 8-mean-free-path reach: 1.29 / 1.26)\n");
    efficiency_run(passes, seed, false);
    efficiency_run(passes, seed, true);
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "efficiency") == 0) {
        efficiency();
        return 0;
    }
    bool only_references = argc > 1 && strcmp(argv[1], "references") == 0;
    if (only_references) argc--, argv++;
    double max_seconds = argc > 1 ? atof(argv[1]) : 300;
    int threads = argc > 2 ? atoi(argv[2]) : 2;
    if (!(max_seconds > 0)) max_seconds = 300;
    lucent_pool *pool = lucent_pool_create(threads > 0 ? threads : 2);
    g_threads = lucent_pool_threads(pool);
    if (only_references) {
        references(pool);
        lucent_pool_destroy(pool);
        return 0;
    }
    lucent_scene *sc;
    load(LUCENT_SOURCE_DIR "/bench/skin1-sphere.json", &sc);
    printf("bench_trace: Skin1 sphere R 10 mm, rough boundary (alpha 0.3, eta 1.3), delta sun from the side, "
           "128 x 128, %d threads; error of one run from two independent runs (seeds 1, 2)\n",
           lucent_pool_threads(pool));
    curve adaptive = {0}, uniform = {0}, cycles = {0};
    printf("  this tracer, adaptive sampling (5 samples per pixel and pass, one of them the pilot's):\n");
    measure_curve(sc, &(lucent_tracer_desc){.adaptive = true}, 1, max_seconds, 0.04, pool, &adaptive);
    printf("  this tracer, one sample per pixel and pass:\n");
    measure_curve(sc, NULL, 4, UNIFORM_SECONDS, 0.0, pool, &uniform);
    printf("  the same tracer with next-event estimation at boundary vertices only (Cycles' strategy):\n");
    measure_curve(sc, &(lucent_tracer_desc){.boundary_nee_only = true}, 4, CYCLES_SECONDS, 0.0, pool, &cycles);
    printf("\n");
    print_curve("adaptive (the result)", &adaptive);
    print_curve("uniform", &uniform);
    print_curve("boundary vertices only (Cycles' strategy, same code, uniform)", &cycles);
    report(&adaptive);
    lucent_scene_destroy(sc);
    references(pool);
    lucent_pool_destroy(pool);
    efficiency();
    return 0;
}
