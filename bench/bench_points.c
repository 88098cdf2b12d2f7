/* Benchmark of the points method (issue 13 item 5): GPU frame time against the number of surfels, per
 * pass, beside mesh-based ssss:preint on the same object, on data/scenes/dragon-marble.json at 512x512:
 * the dragon's four resolutions (res4 .. res1, 5k .. 437k vertices) and res1 after one Loop
 * subdivision (1.75M; with --big also two, 7M). Splats per second of the high-quality splatting
 * (visibility + attributes + normalisation, one splat = one surfel of level 0) beside the anchor:
 *   Botsch, Hornung, Zwicker & Kobbelt 2005, "High-quality surface splatting on today's GPUs": over
 *   20 M elliptical splats/s on a GeForce 6800 Ultra (2005).
 * and the diffusion's splats per second (every Gaussian's splats from the level it used, read from the
 * sidecar). Times: the best frame of rounds that render both methods in turn (>= 3 rounds, >= MIN_SECONDS
 * per method). Usage: bench_points [MIN_SECONDS] [--big] [--size PX] [--cases N]: --size renders PX x PX
 * (default 512), --cases stops after the first N resolutions (on a CPU rasteriser the diffusion of the
 * larger ones takes minutes a frame). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lucent/render.h"

enum { MAX_FRAMES = 100 };

typedef struct bench_case {
    const char *label, *mesh;
    int subdivide;
} bench_case;

static const bench_case k_cases[] = {
    {"res4", "dragon_vrip_res4.ply.gz", 0},     {"res3", "dragon_vrip_res3.ply.gz", 0},
    {"res2", "dragon_vrip_res2.ply.gz", 0},     {"res1", "dragon_vrip.ply.gz", 0},
    {"res1 + 1 Loop", "dragon_vrip.ply.gz", 1}, {"res1 + 2 Loop", "dragon_vrip.ply.gz", 2}};
static const char *const k_passes[] = {"shadow", "visibility", "attributes", "irradiance", "diffusion", "shade"};
enum { CASES = sizeof k_cases / sizeof k_cases[0], PASSES = sizeof k_passes / sizeof k_passes[0] };

static void fail(const char *what)
{
    fprintf(stderr, "bench_points: %s: %s\n", what, lucent_last_error());
    exit(1);
}

static double pass_ms(const lucent_frame_times *t, const char *name)
{
    for (int i = 0; i < t->pass_count; i++)
        if (!strcmp(t->pass_name[i], name)) return t->pass_ms[i];
    return 0;
}

/* The best frame (and its passes) of each method over interleaved rounds; setup_ms[m]: the CPU
 * preparation of method m's first frame (later frames prepare nothing). */
static void measure(lucent_renderer *r, const lucent_render_settings s[2], double min_seconds,
                    lucent_frame_times best[2], double setup_ms[2])
{
    lucent_frame_times t;
    double spent = 0;
    for (int m = 0; m < 2; m++) {
        if (lucent_render_frame(r, &s[m], &best[m]) != LUCENT_OK) fail("warm-up frame");
        setup_ms[m] = best[m].setup_ms;
    }
    for (int round = 0; round < MAX_FRAMES && (round < 3 || spent < 2e3 * min_seconds); round++)
        for (int m = 0; m < 2; m++) {
            if (lucent_render_frame(r, &s[m], &t) != LUCENT_OK) fail("frame");
            if (round == 0 || t.gpu_ms < best[m].gpu_ms) best[m] = t;
            spent += t.cpu_ms;
        }
}

/* From the sidecar: level 0's surfels and the splats the diffusion drew (per Gaussian, its level's). */
static void splat_counts(lucent_renderer *r, const lucent_render_settings *s, double *level0, double *diffusion)
{
    lucent_render_result res = {0};
    char *json = NULL;
    if (lucent_render(r, s, &res) != LUCENT_OK || lucent_render_sidecar(r, s, &res, &json) != LUCENT_OK)
        fail("sidecar");
    cJSON *root = cJSON_Parse(json), *pts = cJSON_GetObjectItem(root, "points");
    cJSON *levels = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(pts, "objects"), 0), "levels");
    cJSON *used = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(pts, "sog"), 0), "levels");
    *level0 = cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetArrayItem(levels, 0), "surfels"));
    *diffusion = 0;
    for (int k = 0; k < cJSON_GetArraySize(used); k++) {
        int l = (int)cJSON_GetNumberValue(cJSON_GetArrayItem(used, k));
        *diffusion += cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetArrayItem(levels, l), "surfels"));
    }
    cJSON_Delete(root);
    free(json);
    lucent_render_result_free(&res);
}

static lucent_scene *load(const char *scene, const bench_case *c, int size)
{
    char mesh[256], sub[64], width[48], height[48];
    snprintf(mesh, sizeof mesh, "objects[0].mesh=../meshes/%s", c->mesh);
    snprintf(sub, sizeof sub, "objects[0].subdivide=%d", c->subdivide);
    snprintf(width, sizeof width, "render.width=%d", size);
    snprintf(height, sizeof height, "render.height=%d", size);
    const char *sets[] = {mesh, sub, width, height};
    lucent_scene *sc = NULL;
    if (lucent_scene_load(scene, &(lucent_scene_load_desc){.overrides = sets, .override_count = 4}, &sc) != LUCENT_OK)
        fail("scene");
    return sc;
}

static void run_case(lucent_gl_context *ctx, const char *scene, const bench_case *c, double min_seconds, int size)
{
    lucent_scene *sc = load(scene, c, size);
    lucent_renderer *r = NULL;
    lucent_renderer_desc rd = lucent_renderer_defaults();
    if (lucent_renderer_create(ctx, sc, &rd, &r) != LUCENT_OK) fail("renderer");
    lucent_render_settings s[2] = {sc->render, sc->render};
    if (lucent_render_method_parse("points", &s[0].view.method, &s[0]) != LUCENT_OK) fail("points");
    if (lucent_render_method_parse("ssss:preint", &s[1].view.method, &s[1]) != LUCENT_OK) fail("ssss");
    lucent_frame_times best[2];
    double setup_ms[2];
    measure(r, s, min_seconds, best, setup_ms);
    double n, nd;
    splat_counts(r, &s[0], &n, &nd);
    double splat_ms = pass_ms(&best[0], "visibility") + pass_ms(&best[0], "attributes") + pass_ms(&best[0], "shade");
    double diff_ms = pass_ms(&best[0], "diffusion");
    printf("%-14s %9.0f %9.2f", c->label, n, best[0].gpu_ms);
    for (int p = 0; p < PASSES; p++) printf(" %9.2f", pass_ms(&best[0], k_passes[p]));
    printf(" %9.2f %6.2fx %8.2f %8.2f %9.0f\n", best[1].gpu_ms, best[0].gpu_ms / best[1].gpu_ms, n / splat_ms / 1e3,
           nd / diff_ms / 1e3, setup_ms[0]);
    lucent_renderer_destroy(r);
    lucent_scene_destroy(sc);
}

int main(int argc, char **argv)
{
    double min_seconds = argc > 1 && argv[1][0] != '-' ? atof(argv[1]) : 1.0;
    bool big = false;
    int size = 512, cases = CASES;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--big")) big = true;
        if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        if (!strcmp(argv[i], "--cases") && i + 1 < argc) cases = atoi(argv[++i]);
    }
    if (size < 16 || size > 8192 || cases < 1) {
        fprintf(stderr, "usage: bench_points [MIN_SECONDS] [--big] [--size 16..8192] [--cases N >= 1]\n");
        return 2;
    }
    char scene[1024], probe[1100];
    const char *slash = strrchr(__FILE__, '/');
    snprintf(scene, sizeof scene, "%.*s/../data/scenes/dragon-marble.json", (int)(slash ? slash - __FILE__ : 1),
             slash ? __FILE__ : ".");
    lucent_gl_context *ctx = NULL;
    if (lucent_gl_create(NULL, &ctx) != LUCENT_OK) fail("GL context");
    lucent_gl_info info;
    lucent_gl_get_info(ctx, &info);
    printf("bench_points: dragon-marble at %dx%d on %s | %s | %s\n", size, size, info.renderer, info.vendor,
           info.version);
    printf("frame and pass times: GPU ms, best of >= 3 interleaved rounds (>= %.1f s per method); splats/s in M\n",
           min_seconds);
    printf("%-14s %9s %9s", "dragon", "surfels", "points");
    for (int p = 0; p < PASSES; p++) printf(" %9s", k_passes[p]);
    printf(" %9s %7s %8s %8s %9s\n", "ssss", "pts/ss", "Msplat/s", "Mdiff/s", "setup ms");
    for (int i = 0; i < CASES && i < cases; i++) {
        if (k_cases[i].subdivide == 2 && !big) continue;
        snprintf(probe, sizeof probe, "%.*s/../meshes/%s", (int)(strrchr(scene, '/') - scene), scene, k_cases[i].mesh);
        if (access(probe, R_OK) != 0) {
            printf("%-14s (no %s: run make setup)\n", k_cases[i].label, probe);
            continue;
        }
        run_case(ctx, scene, &k_cases[i], min_seconds, size);
    }
    printf("anchor: Botsch et al. 2005, > 20 M elliptical splats/s (high-quality splatting, GeForce 6800 Ultra); "
           "Msplat/s here = level-0 surfels / (visibility + attributes + shade)\n");
    if (info.software)
        printf("note: %s is a CPU rasteriser: its times show the scaling and the ratios, not GPU speed.\n",
               info.renderer);
    if (!big && cases == CASES) printf("(res1 + 2 Loop, 7M surfels: bench_points %.1f --big)\n", min_seconds);
    if (cases < CASES) printf("(the first %d of %d resolutions: --cases %d)\n", cases, CASES, cases);
    lucent_gl_destroy(ctx);
    return 0;
}
