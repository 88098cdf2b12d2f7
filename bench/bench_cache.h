/* The bake cache folder of the renderer benchmarks: the one `lucent render` uses (tools' cli_cache_dir:
 * $LUCENT_CACHE_DIR, else ~/.cache/lucent), so a benchmark's bakes are the CLI's. */
#ifndef LUCENT_BENCH_CACHE_H
#define LUCENT_BENCH_CACHE_H

#include <stdio.h>
#include <stdlib.h>

static inline const char *bench_cache_dir(char *buf, size_t size)
{
    const char *env = getenv("LUCENT_CACHE_DIR"), *home = getenv("HOME");
    if (env && *env) return env;
    if (!home) return NULL;
    snprintf(buf, size, "%s/.cache/lucent", home);
    return buf;
}

#endif
