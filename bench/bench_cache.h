/* The bake cache folder of the renderer benchmarks: the one `lucent render` uses (tools' cli_cache_dir:
 * $LUCENT_CACHE_DIR, else ~/.cache/lucent), so a benchmark's bakes are the CLI's; and the GL context
 * and renderer every renderer benchmark starts with. */
#ifndef LUCENT_BENCH_CACHE_H
#define LUCENT_BENCH_CACHE_H

#include <stdio.h>
#include <stdlib.h>

#include "lucent/render.h"

static inline const char *bench_cache_dir(char *buf, size_t size)
{
    const char *env = getenv("LUCENT_CACHE_DIR"), *home = getenv("HOME");
    if (env && *env) return env;
    if (!home) return NULL;
    snprintf(buf, size, "%s/.cache/lucent", home);
    return buf;
}

/* A GL context and a renderer of sc with the default photon counts and the CLI's bake cache. */
static inline lucent_status bench_renderer_create(const lucent_scene *sc, lucent_gl_context **ctx,
                                                  lucent_renderer **dest)
{
    static char cache[1024];
    lucent_renderer_desc rd = lucent_renderer_defaults();
    rd.cache_dir = bench_cache_dir(cache, sizeof cache);
    lucent_status s = lucent_gl_create(NULL, ctx);
    return s == LUCENT_OK ? lucent_renderer_create(*ctx, sc, &rd, dest) : s;
}

#endif
