/* The estimate: per pixel the sums of the samples, of their squares and of the squared luminance,
 * and how many camera rays met an object. Work is cut into passes and tiles of TILE x TILE pixels; a
 * pass runs its tiles in parallel and each pixel adds its own samples in order, so the sums are
 * added in sample order whatever the thread count. Sample i of pixel p draws from RNG stream
 * (i << 32 | p); the pilot sample of pass k from stream (k << 32 | p) with the top bit set. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/dist.h"
#include "trace/film.h"

enum { TILE = 16 };
#define PILOT_STREAM (1ull << 63)

const double tr_film_luminance[3] = {0.2126, 0.7152, 0.0722};

lucent_status tr_film_create(int width, int height, bool adaptive, tr_film **dest)
{
    size_t n = (size_t)width * (size_t)height;
    tr_film *f = calloc(1, sizeof *f);
    bool ok = f && (f->acc = calloc(n * TR_FILM_ACC, sizeof *f->acc)) && (f->count = calloc(n, sizeof *f->count)) &&
              (f->hits = calloc(n, sizeof *f->hits)) && (f->quota = calloc(n, sizeof *f->quota)) &&
              (f->light = calloc(n * TR_FILM_ACC, sizeof *f->light));
    if (ok && adaptive)
        ok = (f->pilot = calloc(n * TR_FILM_ACC, sizeof *f->pilot)) && (f->carry = calloc(n, sizeof *f->carry));
    if (!ok) {
        tr_film_destroy(f);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory for a %d x %d image", width, height);
    }
    f->width = width, f->height = height, f->adaptive = adaptive;
    tr_film_reset(f);
    *dest = f;
    return LUCENT_OK;
}

void tr_film_destroy(tr_film *f)
{
    if (!f) return;
    free(f->acc), free(f->count), free(f->hits), free(f->quota), free(f->pilot), free(f->carry), free(f->light);
    free(f);
}

void tr_film_reset(tr_film *f)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    memset(f->acc, 0, n * TR_FILM_ACC * sizeof *f->acc);
    memset(f->count, 0, n * sizeof *f->count);
    memset(f->hits, 0, n * sizeof *f->hits);
    memset(f->light, 0, n * TR_FILM_ACC * sizeof *f->light);
    f->light_passes = 0;
    memset(f->light_m2, 0, sizeof f->light_m2), memset(f->light_n, 0, sizeof f->light_n);
    memset(f->entry_m2, 0, sizeof f->entry_m2), memset(f->entry_cost, 0, sizeof f->entry_cost);
    memset(f->entry_n, 0, sizeof f->entry_n), memset(f->entry_arrived, 0, sizeof f->entry_arrived);
    if (f->pilot) memset(f->pilot, 0, n * TR_FILM_ACC * sizeof *f->pilot);
    if (f->carry) memset(f->carry, 0, n * sizeof *f->carry);
    for (size_t p = 0; p < n; p++) f->quota[p] = 1;
    f->passes = 0, f->seed = 0, f->seconds = 0;
    memset(&f->stats, 0, sizeof f->stats);
}

typedef struct pass_job {
    const lucent_tracer *tr;
    tr_film *film;
    int tiles_x;
    tr_stats *stats; /* one per thread */
    lucent_progress *progress;
    double deadline;  /* lucent_clock_seconds() after which no tile starts (0: none) */
    _Atomic bool cut; /* a tile was skipped for the deadline */
} pass_job;

static void accumulate(double *a, const double v[3])
{
    double y = 0;
    for (int c = 0; c < 3; c++) a[c] += v[c], a[3 + c] += v[c] * v[c], y += tr_film_luminance[c] * v[c];
    a[6] += y * y;
}

/* One camera path through pixel (x, y) from stream `stream`; true when it met an object. */
static bool sample(const pass_job *job, int x, int y, uint64_t stream, tr_stats *stats, double v[3])
{
    lucent_rng rng;
    lucent_rng_init(job->film->seed, stream, &rng);
    double px = x + lucent_rng_uniform(&rng), py = y + lucent_rng_uniform(&rng);
    return tr_trace_path(job->tr, px, py, &rng, v, stats);
}

static uint64_t pixel_pass(const pass_job *job, int x, int y, tr_stats *stats)
{
    tr_film *f = job->film;
    size_t p = (size_t)y * (size_t)f->width + (size_t)x;
    double v[3];
    for (uint32_t i = 0; i < f->quota[p]; i++, f->count[p]++) {
        f->hits[p] += sample(job, x, y, (uint64_t)f->count[p] << 32 | p, stats, v);
        accumulate(f->acc + p * TR_FILM_ACC, v);
    }
    if (!f->adaptive) return f->quota[p];
    sample(job, x, y, PILOT_STREAM | f->passes << 32 | p, stats, v);
    accumulate(f->pilot + p * TR_FILM_ACC, v);
    return f->quota[p] + 1;
}

static lucent_status pass_tile(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end;
    pass_job *job = ctx;
    tr_film *f = job->film;
    int x0 = (int)(chunk % (uint64_t)job->tiles_x) * TILE, y0 = (int)(chunk / (uint64_t)job->tiles_x) * TILE;
    int x1 = x0 + TILE < f->width ? x0 + TILE : f->width, y1 = y0 + TILE < f->height ? y0 + TILE : f->height;
    uint64_t done = 0;
    if (job->deadline > 0 && (atomic_load(&job->cut) || lucent_clock_seconds() >= job->deadline)) {
        atomic_store(&job->cut, true);
        return LUCENT_OK;
    }
    tr_stats stats = {0}; /* counted on this thread's stack, not in the threads' array, whose neighbouring
                             counters share cache lines (the dragon: within the noise, 85 and 84-87 passes) */
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) done += pixel_pass(job, x, y, &stats);
    tr_film_add_stats(&job->stats[thread], &stats);
    lucent_progress_add(job->progress, done);
    return LUCENT_OK;
}

void tr_film_add_stats(tr_stats *into, const tr_stats *s)
{
    into->paths += s->paths, into->scatters += s->scatters, into->bounces += s->bounces;
    into->escaped += s->escaped, into->truncated += s->truncated, into->nonfinite += s->nonfinite;
    into->rays += s->rays, into->points += s->points, into->free_flights += s->free_flights, into->nee += s->nee;
    into->photons += s->photons;
    into->entry_ended += s->entry_ended;
}

uint64_t tr_film_pass_samples(const tr_film *f)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    uint64_t total = f->adaptive ? n : 0;
    for (size_t p = 0; p < n; p++) total += f->quota[p];
    return total;
}

lucent_status tr_film_pass(const lucent_tracer *tr, tr_film *f, lucent_pool *pool, lucent_progress *progress,
                           double deadline, bool *cut)
{
    int threads = pool ? lucent_pool_threads(pool) : 1;
    tr_stats *stats = calloc((size_t)threads, sizeof *stats);
    if (!stats) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "trace: out of memory");
    tr_film_allocate(f);
    pass_job job = {.tr = tr,
                    .film = f,
                    .tiles_x = (f->width + TILE - 1) / TILE,
                    .stats = stats,
                    .progress = progress,
                    .deadline = deadline};
    uint64_t tiles = (uint64_t)job.tiles_x * (uint64_t)((f->height + TILE - 1) / TILE);
    lucent_status s = lucent_parallel_for_share(pool, tiles, 1, pass_tile, &job, lucent_dist_share());
    for (int t = 0; t < threads; t++) tr_film_add_stats(&f->stats, &stats[t]);
    free(stats);
    if (f->adaptive && lucent_dist_size() > 1) s = tr_film_gather(f, f->pilot, TR_FILM_ACC, s);
    *cut = atomic_load(&job.cut);
    if (s == LUCENT_OK && !*cut) f->passes++;
    return s;
}

bool tr_film_owns(const tr_film *f, size_t p)
{
    lucent_share sh = lucent_dist_share();
    if (!sh.stride) return false;
    uint64_t tiles_x = (uint64_t)(f->width + TILE - 1) / TILE, x = p % (size_t)f->width, y = p / (size_t)f->width;
    return (y / TILE * tiles_x + x / TILE) % sh.stride == sh.offset;
}

lucent_status tr_film_gather(const tr_film *f, double *v, int per_pixel, lucent_status status)
{
    size_t n = (size_t)f->width * (size_t)f->height;
    if (status == LUCENT_OK)
        for (size_t p = 0; p < n; p++)
            if (!tr_film_owns(f, p))
                for (int k = 0; k < per_pixel; k++) v[p * (size_t)per_pixel + (size_t)k] = -INFINITY;
    return lucent_dist_max_f64(status, v, n * (size_t)per_pixel);
}

lucent_status tr_film_total(const tr_film *f, lucent_status status, tr_film **dest)
{
    *dest = NULL;
    tr_film *t = NULL;
    lucent_status s = status == LUCENT_OK ? tr_film_create(f->width, f->height, false, &t) : status;
    s = lucent_dist_agree(s);
    if (s != LUCENT_OK) {
        tr_film_destroy(t);
        return s;
    }
    size_t n = (size_t)f->width * (size_t)f->height;
    memcpy(t->acc, f->acc, n * TR_FILM_ACC * sizeof *t->acc);
    memcpy(t->count, f->count, n * sizeof *t->count);
    memcpy(t->hits, f->hits, n * sizeof *t->hits);
    memcpy(t->light, f->light, n * TR_FILM_ACC * sizeof *t->light); /* light paths run without MPI */
    t->light_passes = f->light_passes;
    t->adaptive = f->adaptive, t->seed = f->seed, t->passes = f->passes, t->seconds = f->seconds;
    t->stats = f->stats;
    uint64_t stats[12] = {t->stats.paths,        t->stats.scatters,  t->stats.bounces, t->stats.escaped,
                          t->stats.truncated,    t->stats.nonfinite, t->stats.rays,    t->stats.points,
                          t->stats.free_flights, t->stats.nee,       t->stats.photons, t->stats.entry_ended};
    s = lucent_dist_sum(LUCENT_OK, LUCENT_DIST_F64, t->acc, n * TR_FILM_ACC);
    s = lucent_dist_sum(s, LUCENT_DIST_U32, t->count, n);
    s = lucent_dist_sum(s, LUCENT_DIST_U32, t->hits, n);
    s = lucent_dist_sum(s, LUCENT_DIST_I64, stats, 12);
    if (s != LUCENT_OK) {
        tr_film_destroy(t);
        return s;
    }
    t->stats = (tr_stats){stats[0], stats[1], stats[2], stats[3], stats[4],  stats[5],
                          stats[6], stats[7], stats[8], stats[9], stats[10], stats[11]};
    *dest = t;
    return LUCENT_OK;
}
