/* Benchmark of texture-space diffusion (issue 14, item 4): TSD's GPU time per pass (irradiance,
 * stretch, dilate, the blur chain, the final geometry pass, compose) against the texture size,
 * 512^2 .. 4096^2, beside Lambert, the CDRF (LUT and closed form), ssss and points (when the
 * renderer has it) on the same scene, from GL timestamp queries, on whatever GL device runs it.
 * Anchor: Kubo et al. Table 1 (512x512, GeForce 9300M GS): the texture blurring method at 41.5 / 35.3
 * fps against Lambert's 575.2 / 693.2 fps (head / bunny), 13.9x / 19.6x Lambert's frame time; the
 * CDRF with LUT 1.17x / 1.44x.
 * Times: the best of >= 3 frames (more until MIN_SECONDS per case) after one warm-up frame.
 * Usage: bench_tsd [MIN_SECONDS_PER_CASE] [SCENE.json] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cache.h"
#include "lucent/render.h"

static void fail(const char *what)
{
    fprintf(stderr, "bench_tsd: %s: %s\n", what, lucent_last_error());
    exit(1);
}

static double pass_ms(const lucent_frame_times *t, const char *name)
{
    for (int i = 0; i < t->pass_count; i++)
        if (!strcmp(t->pass_name[i], name)) return t->pass_ms[i];
    return 0;
}

/* The best frame of a case (its passes from that frame). */
static lucent_frame_times best_frame(lucent_renderer *r, const lucent_render_settings *s, double min_seconds,
                                     int *frames)
{
    lucent_frame_times t, best = {0};
    if (lucent_render_frame(r, s, &t) != LUCENT_OK) fail("warm-up frame");
    double spent = 0;
    *frames = 0;
    for (int i = 0; i < 200 && (i < 3 || spent < min_seconds * 1e3); i++) {
        if (lucent_render_frame(r, s, &t) != LUCENT_OK) fail("frame");
        if (i == 0 || t.gpu_ms < best.gpu_ms) best = t;
        spent += t.cpu_ms, ++*frames;
    }
    return best;
}

int main(int argc, char **argv)
{
    double min_seconds = argc > 1 ? atof(argv[1]) : 1.0;
    char scene_path[1024];
    const char *slash = strrchr(__FILE__, '/');
    snprintf(scene_path, sizeof scene_path, "%.*s/../data/scenes/bunny-skin.json", (int)(slash ? slash - __FILE__ : 1),
             slash ? __FILE__ : ".");
    if (argc > 2) snprintf(scene_path, sizeof scene_path, "%s", argv[2]);
    lucent_scene *sc = NULL;
    if (lucent_scene_load(scene_path, NULL, &sc) != LUCENT_OK) fail("scene");
    lucent_gl_context *ctx = NULL;
    lucent_renderer *r = NULL;
    if (bench_renderer_create(sc, &ctx, &r) != LUCENT_OK) fail("GL context and renderer");
    lucent_gl_info info;
    lucent_gl_get_info(ctx, &info);
    size_t faces = 0;
    for (int i = 0; i < sc->object_count; i++) faces += sc->objects[i].mesh->face_count;
    printf("renderer: %s on %s | %s (%s); %zu triangles; %dx%d; best of >= 3 frames (>= %.1f s per case)\n", sc->name,
           info.renderer, info.version, info.platform, faces, sc->render.view.width, sc->render.view.height,
           min_seconds);

    /* the other methods on the same scene */
    static const char *const others[][2] = {{"lambert", "lambert"},
                                            {"cdrf (LUT)", "cdrf"},
                                            {"cdrf (closed form)", "cdrf"},
                                            {"ssss preint 25", "ssss:preint"},
                                            {"points", "points"}};
    printf("%-22s %10s %10s %10s %7s\n", "method", "frame ms", "geometry", "blur", "frames");
    double lambert_ms = 0;
    for (size_t m = 0; m < sizeof others / sizeof others[0]; m++) {
        lucent_render_settings s = sc->render;
        if (lucent_render_method_parse(others[m][1], &s.view.method, &s) != LUCENT_OK) {
            printf("%-22s (not in this renderer)\n", others[m][0]);
            continue;
        }
        s.cdrf.lut = m != 2;
        s.ssss.taps = 25;
        int frames;
        lucent_frame_times t = best_frame(r, &s, min_seconds, &frames);
        if (m == 0) lambert_ms = t.gpu_ms;
        printf("%-22s %10.3f %10.3f %10.3f %7d   (%.2fx lambert)\n", others[m][0], t.gpu_ms, pass_ms(&t, "geometry"),
               t.blur_ms, frames, t.gpu_ms / lambert_ms);
    }

    /* TSD per pass against the texture size */
    printf("\n%-10s %10s %10s %10s %10s %10s %10s %10s %10s %7s\n", "tsd size", "frame ms", "shadow", "irradiance",
           "stretch", "dilate", "blur", "geometry", "compose", "frames");
    for (int size = 512; size <= 4096; size *= 2) {
        lucent_render_settings s = sc->render;
        if (lucent_render_method_parse("tsd", &s.view.method, &s) != LUCENT_OK) fail("tsd");
        s.tsd.size = size;
        int frames;
        lucent_frame_times t = best_frame(r, &s, min_seconds, &frames);
        char label[16];
        snprintf(label, sizeof label, "%d^2", size);
        printf("%-10s %10.3f %10.3f %10.3f %10.3f %10.3f %10.3f %10.3f %10.3f %7d   (%.1fx lambert)\n", label, t.gpu_ms,
               pass_ms(&t, "shadow"), pass_ms(&t, "irradiance"), pass_ms(&t, "stretch"), pass_ms(&t, "dilate"),
               t.blur_ms, pass_ms(&t, "geometry"), pass_ms(&t, "compose"), frames, t.gpu_ms / lambert_ms);
    }
    printf("[Kubo Table 1: texture blurring 13.9x-19.6x Lambert's frame time (41.5 / 35.3 fps against 575.2 / 693.2 "
           "fps), CDRF with LUT 1.17x-1.44x]\n");
    if (info.software)
        printf("note: %s is a CPU rasteriser: its times show the ratios, not GPU speed; the texture passes scale with "
               "the texels, the others with the pixels.\n",
               info.renderer);
    lucent_renderer_destroy(r);
    lucent_gl_destroy(ctx);
    lucent_scene_destroy(sc);
    return 0;
}
