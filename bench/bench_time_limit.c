/* Benchmark of the reference's time limit (issue 12, section 2): `lucent compare --time S` and
 * `lucent trace --time S` stop the path tracer after S seconds of rendering. The limit used to be
 * checked between passes only, so a pass begun just before it ran to its end (and the guiding
 * field's photon pre-pass was never cut): on a loaded machine runs overshot 2-3x. It is now checked
 * before every tile of a pass (src/trace/film.c) and every photon chunk of the field, which gets at
 * most a quarter of the limit (src/trace/field.c). Anchor: the acceptance, a 20 s limit ends within 10% of 20 s (18-22 s).
 * The scene: the demo's dragon in marble at 256 x 256 (data/scenes/dragon-marble.json; needs the
 * meshes of scripts/fetch_meshes.sh), the heaviest default scene per pass.
 * Usage: bench_time_limit [SECONDS (default 20)] [SCENE.json] */
#include <stdio.h>
#include <stdlib.h>

#include "lucent/lucent.h"

#ifndef LUCENT_SOURCE_DIR
#define LUCENT_SOURCE_DIR "."
#endif

int main(int argc, char **argv)
{
    double limit = argc > 1 ? atof(argv[1]) : 20;
    const char *path = argc > 2 ? argv[2] : LUCENT_SOURCE_DIR "/data/scenes/dragon-marble.json";
    const char *sets[] = {"render.width=256", "render.height=256"};
    lucent_scene *sc = NULL;
    lucent_tracer *tr = NULL;
    lucent_trace_result res = {0};
    lucent_pool *pool = lucent_pool_create(0);
    if (lucent_scene_load(path, &(lucent_scene_load_desc){.overrides = sets, .override_count = 2}, &sc) != LUCENT_OK ||
        lucent_tracer_create(sc, NULL, &tr) != LUCENT_OK) {
        fprintf(stderr, "bench_time_limit: %s\n", lucent_last_error());
        return 1;
    }
    double t0 = lucent_clock_seconds();
    lucent_status s =
        lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1000000, .time_limit = limit, .pool = pool}, &res);
    double wall = lucent_clock_seconds() - t0;
    if (s != LUCENT_OK) {
        fprintf(stderr, "bench_time_limit: %s\n", lucent_last_error());
        return 1;
    }
    printf("time limit %.1f s on %s (256 x 256, %d threads): ended after %.2f s (%+.1f%%; anchor: within 10%%), "
           "%llu whole passes, %.2f samples per pixel\n",
           limit, sc->name, lucent_pool_threads(pool), wall, 100 * (wall / limit - 1), (unsigned long long)res.spp,
           (double)res.samples / (256.0 * 256.0));
    lucent_trace_result_free(&res);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
    lucent_pool_destroy(pool);
    return 0;
}
