/* Benchmark of the base layer that every Monte Carlo builds on: RNG throughput and the
 * scaling of lucent_parallel_for. No issue names an anchor for these; the figure beside
 * them is the scalar baseline measured in the same run (one thread), so scaling reads off
 * directly. Usage: bench_base [seconds_per_case] */
#include <stdlib.h>

#include "lucent/base.h"

typedef struct work {
    double sums[4096];
} work;

/* Each chunk draws 2^20 uniforms from its own stream: the pattern of the Monte Carlo code. */
static lucent_status draw_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)begin, (void)end, (void)thread;
    work *w = ctx;
    lucent_rng r;
    lucent_rng_init(1, chunk, &r);
    double s = 0;
    for (int i = 0; i < (1 << 20); i++) s += lucent_rng_uniform(&r);
    w->sums[chunk % 4096] = s;
    return LUCENT_OK;
}

static double numbers_per_second(int threads, int chunks)
{
    static work w;
    lucent_pool *pool = lucent_pool_create(threads);
    double t0 = lucent_clock_seconds();
    lucent_parallel_for(pool, (uint64_t)chunks, 1, draw_chunk, &w);
    double t = lucent_clock_seconds() - t0;
    lucent_pool_destroy(pool);
    return (double)chunks * (1 << 20) / t;
}

int main(int argc, char **argv)
{
    int chunks = argc > 1 ? atoi(argv[1]) : 256;
    if (chunks < 1) chunks = 256;
    int cores = lucent_cpu_count();
    printf("bench_base: %d chunks of 2^20 uniform doubles (xoshiro256**), %d cores\n", chunks, cores);
    double one = numbers_per_second(1, chunks);
    printf("  1 thread : %8.1f M numbers/s  (%.2f ns each)\n", one / 1e6, 1e9 / one);
    for (int t = 2; t <= cores; t *= 2) {
        double many = numbers_per_second(t, chunks);
        printf("  %d threads: %8.1f M numbers/s  speed-up %.2fx over 1 thread (ideal %dx)\n", t, many / 1e6, many / one,
               t);
    }
    return 0;
}
