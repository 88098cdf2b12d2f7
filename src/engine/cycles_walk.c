/* Cycles' random walk as Blender 3.4 runs it (integrator/subsurface_random_walk.h), in a half-space z > 0
 * at unit extinction, one channel: the walk enters through a diffuse interface (a cosine-weighted direction
 * about the inward normal, sample_cos_hemisphere), flies exponential distances, scatters by
 * Henyey-Greenstein g for its first SUBSURFACE_RANDOM_WALK_SIMILARITY_LEVEL = 9 bounces and isotropically
 * after them with the similarity-reduced coefficients (sigma_s* = sigma_s (1 - g), sigma_t* = sigma_t -
 * sigma_s + sigma_s*), multiplies its throughput by sigma_s / sigma_t at each scattering, leaves where it
 * crosses the surface (index-matched: no Fresnel), and gives up after BSSRDF_MAX_BOUNCES = 256 flights.
 * Cycles' guided (Dwivedi) sampling changes the variance, not the expectation, and is left out. The exit
 * radius is scored in bins (bin averages, as lucent_mc_result.rd_r). The Henyey-Greenstein sampler and the
 * basis are src/base/optics.h's; chunks of photons take RNG streams of their own (deterministic). */
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "engine/internal.h"

enum { CW_MAX_BOUNCES = 256, CW_SIMILARITY_LEVEL = 9, CW_CHUNK = 4096 };

typedef struct cw_ctx {
    double alpha, g, dr;
    int nr;
    uint64_t seed;
    double *sums; /* per chunk: nr bins + the total, + the total's square sum */
} cw_ctx;

/* One photon: its weight on leaving (0 when it does not) and where. */
static double walk_one(const cw_ctx *c, lucent_rng *rng, double *radius)
{
    double st_star = 1.0 - c->alpha * c->g, alpha_star = c->alpha * (1.0 - c->g) / st_star;
    double u1 = lucent_rng_uniform(rng), u2 = lucent_rng_uniform(rng);
    v3 p = {0, 0, 0}, d = lucent_around((v3){0, 0, 1}, sqrt(u1), 2.0 * M_PI * u2); /* cosine about +z */
    double w = 1.0;
    for (int bounce = 0; bounce < CW_MAX_BOUNCES; bounce++) {
        bool similar = bounce > CW_SIMILARITY_LEVEL;
        double sigma_t = similar ? st_star : 1.0, a = similar ? alpha_star : c->alpha;
        if (bounce > 0) {
            double g = similar ? 0.0 : c->g;
            d = lucent_hg_sample(d, g, lucent_rng_uniform(rng), lucent_rng_uniform(rng));
        }
        double t = -log(1.0 - lucent_rng_uniform(rng)) / sigma_t;
        if (p.z + t * d.z <= 0.0) { /* leaves: where the path crosses z = 0 */
            double s = d.z < 0.0 ? -p.z / d.z : 0.0;
            *radius = hypot(p.x + s * d.x, p.y + s * d.y);
            return w;
        }
        p = v3_madd(p, d, t);
        w *= a;
    }
    return 0.0;
}

static lucent_status cw_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)thread;
    const cw_ctx *c = ctx;
    double *s = c->sums + chunk * (uint64_t)(c->nr + 2);
    lucent_rng rng;
    lucent_rng_init(c->seed, chunk, &rng);
    for (uint64_t i = begin; i < end; i++) {
        double r = 0.0, w = walk_one(c, &rng, &r);
        if (w <= 0.0) continue;
        int b = (int)(r / c->dr);
        if (b < c->nr) s[b] += w;
        s[c->nr] += w, s[c->nr + 1] += w * w;
    }
    return LUCENT_OK;
}

lucent_status eng_cycles_walk(double alpha, double g, uint64_t photons, uint64_t seed, double dr, int nr,
                              lucent_pool *pool, double *rd_r, double *total, double *total_se)
{
    uint64_t chunks = (photons + CW_CHUNK - 1) / CW_CHUNK;
    cw_ctx c = {.alpha = alpha, .g = g, .dr = dr, .nr = nr, .seed = seed};
    c.sums = calloc(chunks * (uint64_t)(nr + 2), sizeof *c.sums);
    if (!c.sums) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = lucent_parallel_for(pool, photons, CW_CHUNK, cw_chunk, &c);
    if (s == LUCENT_OK) {
        double sum = 0.0, sq = 0.0;
        memset(rd_r, 0, (size_t)nr * sizeof *rd_r);
        for (uint64_t k = 0; k < chunks; k++) { /* in chunk order: the same sums whatever the thread count */
            const double *a = c.sums + k * (uint64_t)(nr + 2);
            for (int j = 0; j < nr; j++) rd_r[j] += a[j];
            sum += a[nr], sq += a[nr + 1];
        }
        double n = (double)photons;
        for (int j = 0; j < nr; j++) rd_r[j] /= n * M_PI * (2 * j + 1) * dr * dr;
        *total = sum / n;
        *total_se = sqrt(fmax(sq / n - *total * *total, 0.0) / n);
    }
    free(c.sums);
    return s;
}
