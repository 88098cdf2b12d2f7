/* `lucent trace`: the path-traced reference of a scene, with its standard errors and a JSON sidecar. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "lucent/trace.h"

enum { MAX_SETS = 64 };

static const char k_usage[] =
    "usage: lucent trace SCENE.json --out IMAGE.png [options]\n"
    "\n"
    "Renders SCENE.json (docs/scenes.md) with the volumetric path tracer (docs/trace.md): media inside\n"
    "the meshes, rough or smooth dielectric boundaries, next-event estimation through the boundary from\n"
    "every scattering vertex. Writes the tonemapped PNG, optionally the linear HDR image and its\n"
    "variance as EXR, and a JSON sidecar (samples, time, the per-pixel relative standard error over the\n"
    "object, the scene after overrides). Same seed and samples give the same image on any thread count.\n"
    "\n"
    "options:\n"
    "  --out FILE         the PNG (tonemapped with the scene's render.tonemap and exposure)\n"
    "  --exr FILE         the mean linear HDR radiance (RGB float EXR)\n"
    "  --variance FILE    the variance of that mean per channel (EXR)\n"
    "  --json FILE        the sidecar (default: --out with .json)\n"
    "  --spp N            samples per pixel (default: render.spp, 64)\n"
    "  --seed S           seed (default: render.seed, 1)\n"
    "  --time S           stop after S seconds (default: render.time_limit; 0: none)\n"
    "  --target-error E   stop once the RMS over object pixels of se(Y)/Y is at most E (at >= 16 spp)\n"
    "  --subsurface-only  drop the light reflected where camera rays first meet a surface\n"
    "  --boundary-nee-only  for comparison: next-event estimation only where the walk meets the\n"
    "                     boundary (Cycles' strategy), not through it from every vertex\n"
    "  --plain-flights    for comparison: every free flight in a medium asks for the boundary ahead\n"
    "                     (no distance bound)\n"
    "  --nee-every-vertex for comparison: next-event estimation from every volume vertex (no Russian\n"
    "                     roulette at deep ones or on the exit; each vertex traces its own guide ray)\n"
    "  --adaptive         adaptive sampling: each pass gives pixels samples by their relative variance\n"
    "                     (measured by a pilot that is not part of the image: still unbiased); --spp\n"
    "                     then counts passes of about 4 samples per pixel (and one pilot sample)\n"
    "  --set KEY=VALUE    change the scene before it is read (repeatable): render.width=256,\n"
    "                     objects[0].roughness=0.2, 'lights[0].direction=[1,0,0]'\n"
    "  -h, --help         show this help\n"
    "\n"
    "examples:\n"
    "  lucent trace data/scenes/bunny-skin.json --spp 256 --out out/bunny.png --exr out/bunny.exr\n"
    "  lucent trace data/scenes/spheres-skin.json --set render.width=384 --set render.height=128 \\\n"
    "      --time 60 --out out/spheres.png\n";

typedef struct trace_options {
    const char *scene, *out, *exr, *variance, *json;
    const char *sets[MAX_SETS];
    int set_count;
    lucent_trace_desc desc;
    bool subsurface_only, adaptive, boundary_nee_only, plain_flights, nee_every_vertex;
} trace_options;

static bool parse_seed(const char *v, uint64_t *dest)
{
    double s;
    if (!cli_parse_double(v, &s) || s < 1 || s > 9007199254740992.0 || s != floor(s)) return false;
    *dest = (uint64_t)s;
    return true;
}

static bool has_extension(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    return dot && strcasecmp(dot, ext) == 0;
}

/* Options that name a file. */
static bool file_option(int argc, char **argv, int *i, trace_options *o, const char **v)
{
    const char **slot = cli_option(argc, argv, i, "--out", v)        ? &o->out
                        : cli_option(argc, argv, i, "--exr", v)      ? &o->exr
                        : cli_option(argc, argv, i, "--variance", v) ? &o->variance
                        : cli_option(argc, argv, i, "--json", v)     ? &o->json
                                                                     : NULL;
    if (slot) *slot = *v;
    return slot != NULL;
}

static int parse_option(int argc, char **argv, int *i, trace_options *o)
{
    const char *v = NULL, *name = argv[*i];
    bool *flag = strcmp(name, "--subsurface-only") == 0     ? &o->subsurface_only
                 : strcmp(name, "--adaptive") == 0          ? &o->adaptive
                 : strcmp(name, "--boundary-nee-only") == 0 ? &o->boundary_nee_only
                 : strcmp(name, "--plain-flights") == 0     ? &o->plain_flights
                 : strcmp(name, "--nee-every-vertex") == 0  ? &o->nee_every_vertex
                                                            : NULL;
    if (flag) {
        *flag = true;
        return CLI_OK;
    }
    if (file_option(argc, argv, i, o, &v)) {
        if (!v) return cli_usage_error("trace", "%s needs a file name", name);
    } else if (cli_option(argc, argv, i, "--spp", &v)) {
        if (!cli_parse_int(v, &o->desc.spp) || o->desc.spp < 1 || o->desc.spp > (1 << 24))
            return cli_usage_error("trace", "--spp needs a whole number from 1 to 16777216");
    } else if (cli_option(argc, argv, i, "--seed", &v)) {
        if (!parse_seed(v, &o->desc.seed)) return cli_usage_error("trace", "--seed needs a whole number >= 1");
    } else if (cli_option(argc, argv, i, "--time", &v)) {
        if (!cli_parse_double(v, &o->desc.time_limit) || !(o->desc.time_limit > 0))
            return cli_usage_error("trace", "--time needs a number of seconds > 0");
    } else if (cli_option(argc, argv, i, "--target-error", &v)) {
        if (!cli_parse_double(v, &o->desc.target_error) || !(o->desc.target_error > 0))
            return cli_usage_error("trace", "--target-error needs a relative error > 0 (0.05 for 5%%)");
    } else if (cli_option(argc, argv, i, "--set", &v)) {
        if (!v || !strchr(v, '=')) return cli_usage_error("trace", "--set needs KEY=VALUE");
        if (o->set_count == MAX_SETS) return cli_usage_error("trace", "at most %d --set options", MAX_SETS);
        o->sets[o->set_count++] = v;
    } else {
        return cli_usage_error("trace", "unknown option '%s'", name);
    }
    return CLI_OK;
}

static int parse_args(int argc, char **argv, trace_options *o)
{
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] != '-') {
            if (o->scene) return cli_usage_error("trace", "unexpected argument '%s'", argv[i]);
            o->scene = argv[i];
            continue;
        }
        int rc = parse_option(argc, argv, &i, o);
        if (rc != CLI_OK) return rc;
    }
    if (!o->scene) return cli_usage_error("trace", "expected a scene file");
    if (!o->out) return cli_usage_error("trace", "--out is required");
    if (!has_extension(o->out, ".png")) return cli_usage_error("trace", "--out '%s': use .png", o->out);
    if (o->exr && !has_extension(o->exr, ".exr")) return cli_usage_error("trace", "--exr '%s': use .exr", o->exr);
    if (o->variance && !has_extension(o->variance, ".exr"))
        return cli_usage_error("trace", "--variance '%s': use .exr", o->variance);
    return CLI_OK;
}

static lucent_status write_png(const char *path, const lucent_image *img, const lucent_render_settings *r)
{
    lucent_image *t;
    lucent_status s = lucent_image_clone(img, &t);
    if (s != LUCENT_OK) return s;
    lucent_image_tonemap(t, &(lucent_tonemap_desc){.op = r->view.tonemap, .exposure = (float)r->view.exposure});
    s = lucent_image_write(path, t, NULL);
    lucent_image_destroy(t);
    return s;
}

static char *sidecar_path(const trace_options *o)
{
    if (o->json) return strdup(o->json);
    size_t n = strlen(o->out);
    char *p = malloc(n + 6);
    if (!p) return NULL;
    memcpy(p, o->out, n - 4);
    strcpy(p + n - 4, ".json");
    return p;
}

static lucent_tracer_desc tracer_options(const trace_options *o)
{
    return (lucent_tracer_desc){.subsurface_only = o->subsurface_only,
                                .adaptive = o->adaptive,
                                .boundary_nee_only = o->boundary_nee_only,
                                .plain_flights = o->plain_flights,
                                .nee_every_vertex = o->nee_every_vertex};
}

static lucent_status write_outputs(const trace_options *o, const lucent_scene *sc, const lucent_trace_result *r)
{
    char *json = sidecar_path(o);
    if (!json) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = write_png(o->out, r->image, &sc->render);
    if (s == LUCENT_OK) cli_wrote("wrote %s", o->out);
    if (s == LUCENT_OK && o->exr && (s = lucent_image_write(o->exr, r->image, NULL)) == LUCENT_OK)
        cli_wrote("wrote %s", o->exr);
    if (s == LUCENT_OK && o->variance && (s = lucent_image_write(o->variance, r->variance, NULL)) == LUCENT_OK)
        cli_wrote("wrote %s", o->variance);
    lucent_tracer_desc tracer = tracer_options(o);
    lucent_trace_sidecar_desc side = {.scene = sc,
                                      .scene_file = o->scene,
                                      .tracer = &tracer,
                                      .result = r,
                                      .threads = lucent_pool_threads(cli_pool())};
    if (s == LUCENT_OK && (s = lucent_trace_write_sidecar(json, &side)) == LUCENT_OK) cli_wrote("wrote %s", json);
    free(json);
    return s;
}

/* The estimate's size as the run made it: passes of adaptive sampling are not samples per pixel, and a
 * pass cut by the time limit keeps its finished tiles' samples without counting as a pass. */
static void summary(const lucent_trace_result *r, bool adaptive)
{
    double per_pixel = (double)r->samples / r->image->width / r->image->height;
    char size[96];
    if (adaptive)
        snprintf(size, sizeof size, "%llu adaptive passes (%.1f samples per pixel on average)",
                 (unsigned long long)r->spp, per_pixel);
    else
        snprintf(size, sizeof size, "%llu spp", (unsigned long long)r->spp);
    char rate[64] = "";
    if (!g_cli.merging) snprintf(rate, sizeof rate, " (%.0f samples/s)", r->samples_per_second);
    cli_info("trace: %s in %.2f s%s; relative standard error over the object: median %.3g, p90 %.3g, rms %.3g "
             "(%llu pixels)",
             size, r->seconds, rate, r->error.median, r->error.p90, r->error.rms, (unsigned long long)r->error.pixels);
    if (!adaptive && r->samples != r->spp * (uint64_t)r->image->width * (uint64_t)r->image->height)
        cli_info("trace: the time limit cut the last pass: %.1f samples per pixel on average", per_pixel);
    const lucent_trace_cost *c = &r->cost;
    double paths = c->paths ? (double)c->paths : 1.0, vertices = (double)(c->scatters + c->bounces);
    cli_info("trace: per path %.1f scatterings, %.1f surface events, %.1f ray and %.2f distance queries; %.2f ray "
             "queries per vertex, %.0f%% of flights without one, next-event estimates at %.0f%% of volume vertices",
             (double)c->scatters / paths, (double)c->bounces / paths, (double)c->rays / paths,
             (double)c->points / paths, vertices > 0 ? (double)c->rays / vertices : 0.0,
             vertices > 0 ? 100.0 * (double)c->free_flights / vertices : 0.0,
             c->scatters ? 100.0 * (double)c->nee / (double)c->scatters : 0.0);
    if (r->truncated || r->escaped || r->nonfinite)
        cli_info("trace: %llu paths truncated by max_bounces/max_scatter, %llu left a mesh through a hole, "
                 "%llu non-finite contributions dropped",
                 (unsigned long long)r->truncated, (unsigned long long)r->escaped, (unsigned long long)r->nonfinite);
}

static lucent_status run(const trace_options *o)
{
    lucent_scene *sc = NULL;
    lucent_tracer *tr = NULL;
    lucent_trace_result r = {0};
    lucent_tracer_desc tracer = tracer_options(o);
    lucent_status s = lucent_scene_load(
        o->scene, &(lucent_scene_load_desc){.overrides = o->sets, .override_count = o->set_count}, &sc);
    if (s == LUCENT_OK) s = lucent_tracer_create(sc, &tracer, &tr);
    lucent_trace_desc d = o->desc;
    d.pool = cli_pool();
    if (s == LUCENT_OK) s = lucent_tracer_render(tr, &d, &r);
    if (s == LUCENT_OK) summary(&r, o->adaptive);
    if (s == LUCENT_OK) s = write_outputs(o, sc, &r);
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
    return s;
}

int cmd_trace(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    trace_options o = {0};
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    char *json = sidecar_path(&o);
    const char *outs[4] = {o.out, o.exr, o.variance, json}, *ins[1] = {o.scene};
    static const char *const flags[4] = {"--out", "--exr", "--variance", "--json"};
    rc = cli_check_outputs("trace", ins, 1, outs, flags, 4);
    free(json);
    if (rc != CLI_OK) return rc;
    return run(&o) == LUCENT_OK ? CLI_OK : cli_fail();
}
