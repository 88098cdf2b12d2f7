/* `lucent compare`: every real-time method of a scene against the path-traced reference, in error
 * and in time, as an HTML report with images (and Markdown, CSV, JSON). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/eval.h"

enum { MAX_SCENES = LUCENT_COMPARE_MAX_SCENES, MAX_METHODS = LUCENT_COMPARE_MAX_METHODS, MAX_SETS = 64 };

#define DEFAULT_METHODS LUCENT_COMPARE_DEFAULT_METHODS

static const char k_usage[] =
    "usage: lucent compare SCENE.json [SCENE.json ...] [options] --out DIR\n"
    "\n"
    "Renders each scene with the path tracer (the reference) and with every real-time method, and\n"
    "writes DIR/report.html: the images side by side, per-pixel error maps, and per method the\n"
    "relative RMS error against the reference over the object's pixels and the GPU frame time.\n"
    "Also DIR/report.md, DIR/report.csv, DIR/results.json, and per scene DIR/SCENE/*.png|.exr.\n"
    "\n"
    "options:\n"
    "  --methods LIST   comma-separated methods (default " DEFAULT_METHODS ");\n"
    "                   any of lambert, cdrf, cdrf+translucency, ssss, ssss:<model>[rank], tsd,\n"
    "                   points, points:sog<N>|deon|brdf|disks\n"
    "  --peers LIST     real engines beside the methods, with `lucent fit`'s parameters: blender-cycles\n"
    "                   (Random Walk), blender-cycles-burley, blender-eevee; NAME:hand for the hand\n"
    "                   mapping (Blender 3.4, headless; $LUCENT_BLENDER names another program)\n"
    "  --peer-spp N     the peers' samples per pixel (default 64); --peer-seed S: their seed\n"
    "  --spp N          reference samples per pixel (default: the scene's render.spp)\n"
    "  --time S         at most S seconds per reference (default: no limit)\n"
    "  --frames N       GL frames timed per method; the median is reported (default 5)\n"
    "  --samples N      each method's image is the mean of N frames jittered over the pixel, as the\n"
    "                   reference averages each pixel's area (default 16; 1: the pixel's centre)\n"
    "  --scale F        multiply every scene's render.width and height by F (keeps each aspect)\n"
    "  --set KEY=VALUE  override a scene value, for every scene (repeatable; see docs/scenes.md)\n"
    "  --out DIR        output folder (default out/compare)\n"
    "  --reference DIR  reuse the references of an earlier run's --out DIR (DIR/SCENE/reference.json\n"
    "                   and its EXRs) instead of tracing: the scene and the settings the tracer reads\n"
    "                   must match (the budget and the seed may differ), else an error names the field\n"
    "  --reference-runs N  trace each reference as N independent runs sharing the budget, 1 or 2\n"
    "                   (default: 2 where light paths land one photon in many pixels, which\n"
    "                   calibrates the paired test's standard error, else 1)\n"
    "  --per-light      also each light alone, reference and methods (one more reference per light)\n"
    "  --title TEXT     the report's title\n"
    "  -h, --help       show this help\n"
    "\n"
    "examples:\n"
    "  lucent compare data/scenes/spheres-skin.json --spp 256 --out out/spheres\n"
    "  lucent compare data/scenes/dragon-marble.json --methods lambert,ssss:svd3 --set render.width=256 \\\n"
    "      --set render.height=256 --out out/dragon\n"
    "  lucent compare data/scenes/dragon-marble.json --methods ssss:svd3 --set render.width=256 \\\n"
    "      --set render.height=256 --set render.taps=25 --reference out/dragon --out out/dragon-taps25\n"
    "\n"
    "The methods are ranked by a paired test of their squared errors against the same reference; each\n"
    "method's phase shows a bar (method, frame k of n, elapsed, ETA) when stderr is a terminal. tsd and\n"
    "points take tens of seconds a frame on a software GL renderer (llvmpipe): asked for, they are\n"
    "announced first with an estimate.\n";

typedef struct options {
    const char *scenes[MAX_SCENES];
    int scene_count;
    char methods_text[1024];
    const char *methods[MAX_METHODS];
    int method_count;
    int spp, frames, samples;
    double time_limit, scale;
    const char *sets[MAX_SETS];
    int set_count;
    const char *out, *title, *reference;
    int reference_runs;
    bool per_light;
    char peers_text[512];
    const char *peers[MAX_METHODS];
    int peer_count, peer_spp, peer_seed;
} options;

/* ---- options ---- */

static int split_methods(options *o)
{
    o->method_count = 0;
    for (char *save = NULL, *t = strtok_r(o->methods_text, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        lucent_render_method m;
        if (o->method_count == MAX_METHODS) return cli_usage_error("compare", "at most %d methods", MAX_METHODS);
        if (lucent_render_method_parse(t, &m, NULL) != LUCENT_OK)
            return cli_usage_error("compare", "--methods: %s", lucent_last_error());
        o->methods[o->method_count++] = t;
    }
    return o->method_count ? CLI_OK : cli_usage_error("compare", "--methods needs at least one method");
}

static int parse_number_option(const char *name, const char *v, options *o)
{
    if (!strcmp(name, "--spp"))
        return cli_parse_int(v, &o->spp) && o->spp >= 1 ? CLI_OK
                                                        : cli_usage_error("compare", "--spp needs a whole number >= 1");
    if (!strcmp(name, "--frames"))
        return cli_parse_int(v, &o->frames) && o->frames >= 1 && o->frames <= 1000
                   ? CLI_OK
                   : cli_usage_error("compare", "--frames needs a whole number from 1 to 1000");
    if (!strcmp(name, "--samples"))
        return cli_parse_int(v, &o->samples) && o->samples >= 1 && o->samples <= 256
                   ? CLI_OK
                   : cli_usage_error("compare", "--samples needs a whole number from 1 to 256");
    if (!strcmp(name, "--scale"))
        return cli_parse_double(v, &o->scale) && o->scale > 0 && o->scale <= 16
                   ? CLI_OK
                   : cli_usage_error("compare", "--scale needs a factor in (0, 16]");
    return cli_parse_double(v, &o->time_limit) && o->time_limit > 0
               ? CLI_OK
               : cli_usage_error("compare", "--time needs a number of seconds > 0");
}

static int parse_args(int argc, char **argv, options *o)
{
    static const char *const numeric[] = {"--spp", "--frames", "--samples", "--time", "--scale"};
    for (int i = 1; i < argc; i++) { /* the peers: their names are checked by lucent_compare_run */
        const char *v;
        if (cli_option(argc, argv, &i, "--peer-spp", &v) && !(cli_parse_int(v, &o->peer_spp) && o->peer_spp >= 1))
            return cli_usage_error("compare", "--peer-spp needs a whole number >= 1");
        if (cli_option(argc, argv, &i, "--peer-seed", &v) && !(cli_parse_int(v, &o->peer_seed) && o->peer_seed >= 1))
            return cli_usage_error("compare", "--peer-seed needs a whole number >= 1");
        if (!cli_option(argc, argv, &i, "--peers", &v)) continue;
        if (!v || strlen(v) >= sizeof o->peers_text) return cli_usage_error("compare", "--peers needs a list");
        snprintf(o->peers_text, sizeof o->peers_text, "%s", v);
        for (char *save = NULL, *t = strtok_r(o->peers_text, ",", &save); t && o->peer_count < MAX_METHODS;
             t = strtok_r(NULL, ",", &save))
            o->peers[o->peer_count++] = t;
    }
    for (int i = 1; i < argc; i++) {
        const char *v;
        int rc = -1;
        for (int k = 0; k < (int)(sizeof numeric / sizeof numeric[0]) && rc < 0; k++)
            if (cli_option(argc, argv, &i, numeric[k], &v)) rc = parse_number_option(numeric[k], v, o);
        if (rc > 0) return rc;
        if (rc == 0) continue;
        if (cli_option(argc, argv, &i, "--peers", &v) || cli_option(argc, argv, &i, "--peer-spp", &v) ||
            cli_option(argc, argv, &i, "--peer-seed", &v)) {
            continue;
        } else if (cli_option(argc, argv, &i, "--methods", &v)) {
            if (!v || strlen(v) >= sizeof o->methods_text) return cli_usage_error("compare", "--methods needs a list");
            snprintf(o->methods_text, sizeof o->methods_text, "%s", v);
        } else if (cli_option(argc, argv, &i, "--set", &v)) {
            if (!v || !strchr(v, '=')) return cli_usage_error("compare", "--set needs KEY=VALUE");
            if (o->set_count == MAX_SETS) return cli_usage_error("compare", "at most %d --set", MAX_SETS);
            o->sets[o->set_count++] = v;
        } else if (cli_option(argc, argv, &i, "--out", &v)) {
            if (!v || strlen(v) > 512)
                return cli_usage_error("compare", "--out needs a folder (at most 512 characters)");
            o->out = v;
        } else if (cli_option(argc, argv, &i, "--reference", &v)) {
            if (!v || strlen(v) > 512)
                return cli_usage_error("compare", "--reference needs a folder (at most 512 characters)");
            o->reference = v;
        } else if (cli_option(argc, argv, &i, "--reference-runs", &v)) {
            if (!v || !cli_parse_int(v, &o->reference_runs) || o->reference_runs < 1 || o->reference_runs > 2)
                return cli_usage_error("compare", "--reference-runs needs 1 or 2");
        } else if (!strcmp(argv[i], "--per-light")) {
            o->per_light = true;
        } else if (cli_option(argc, argv, &i, "--title", &v)) {
            if (!v) return cli_usage_error("compare", "--title needs a text");
            o->title = v;
        } else if (argv[i][0] == '-') {
            return cli_usage_error("compare", "unknown option '%s'", argv[i]);
        } else {
            if (o->scene_count == MAX_SCENES) return cli_usage_error("compare", "at most %d scenes", MAX_SCENES);
            o->scenes[o->scene_count++] = argv[i];
        }
    }
    if (!o->scene_count) return cli_usage_error("compare", "give at least one scene file");
    return split_methods(o);
}

/* ---- the run ---- */

static void print_scene(const lucent_compare_scene *r)
{
    int order[MAX_METHODS], rank[MAX_METHODS], l = lucent_compare_lambert_index(r);
    bool ranked = lucent_compare_rank(r, order, rank);
    char noise[32] = "unknown";
    if (ranked) snprintf(noise, sizeof noise, "%.2f%%", 100 * r->reference_noise);
    cli_info("%s: %d x %d; reference %d spp in %.1f s (its noise %s); %s", r->name, r->width, r->height,
             r->reference_spp, r->reference_seconds, noise, r->device);
    if (!ranked)
        fprintf(stderr,
                "lucent: warning: %s: the reference has %d spp, fewer than the %d from which its noise can be "
                "estimated: its noise is unknown, and no method is ranked or marked best\n",
                r->name, r->reference_spp, LUCENT_COMPARE_MIN_SPP);
    cli_info("  %-4s %-22s %14s %13s %12s %10s %12s %8s %7s %9s", "rank", "method", "rel. RMS error", "net of noise",
             "frame ms", "x Lambert", "setup ms", "z next", "FLIP", "worst 1%");
    for (int k = 0; k < r->method_count; k++) {
        int i = order[k];
        const lucent_compare_method *m = &r->methods[i];
        char rk[16] = "-", net[24] = "unknown", ratio[24] = "-", z[24] = "-", flip[24] = "-", worst[24] = "-";
        if (ranked) {
            bool tie = false;
            for (int j = 0; j < r->method_count; j++) tie |= j != i && rank[j] == rank[i];
            snprintf(rk, sizeof rk, "%s%d", tie ? "=" : "", rank[i]);
            snprintf(net, sizeof net, "%.2f%%", 100 * lucent_compare_net_error(m->rel_rms, r->reference_noise));
            double zn = k + 1 < r->method_count ? fabs(lucent_compare_pair_z(r, i, order[k + 1])) : NAN;
            if (isinf(zn))
                snprintf(z, sizeof z, "exact");
            else if (isfinite(zn))
                snprintf(z, sizeof z, "%.1f", zn);
        }
        if (l >= 0 && r->methods[l].frame_ms > 0)
            snprintf(ratio, sizeof ratio, "%.2f", m->frame_ms / r->methods[l].frame_ms);
        if (m->has_flip) snprintf(flip, sizeof flip, "%.4f", m->flip);
        if (m->has_worst) snprintf(worst, sizeof worst, "%.1f%%", 100 * m->worst_share);
        cli_info("  %-4s %-22s %13.2f%% %13s %12.3f %10s %12.0f %8s %7s %9s", rk, m->name, 100 * m->rel_rms, net,
                 m->frame_ms, ratio, m->setup_ms, z, flip, worst);
    }
    if (ranked && r->pair_se)
        cli_info(
            "  (=: the paired test of the squared errors cannot tell them apart, |z| < %.0f; z next: the "
            "separation from the next row; worst 1%%: the share of the squared error in the worst 1%% of the object's "
            "pixels%s)",
            LUCENT_COMPARE_Z, r->se_inflation > 1 ? ", its standard error calibrated on two reference runs" : "");
    else if (ranked)
        cli_info("  (= : tied, net errors within the reference's noise of each other)");
}

/* Prints each scene's table once it is measured. */
static void on_event(const lucent_eval_event *e, void *user)
{
    const lucent_compare_result *result = user;
    if (e->kind == LUCENT_EVAL_SCENE_DONE) print_scene(&result->scenes[e->index].report);
    if (e->kind == LUCENT_EVAL_SKIPPED)
        fprintf(stderr, "lucent compare: warning: %s skipped (%s)\n", e->name, e->reason);
    if (e->kind == LUCENT_EVAL_SLOW) fprintf(stderr, "lucent compare: warning: %s\n", e->reason);
}

extern const char lucent_cli_revision[]; /* generated/revision.c (cmake/revision.cmake) */

/* The command line as a shell would read it back ("lucent compare ..."), for the report's provenance
 * (the common options main.c took, --quiet, --threads, --part, are not in argv any more). */
static void command_line(int argc, char **argv, char *dest, size_t size)
{
    size_t n = (size_t)snprintf(dest, size, "lucent");
    for (int i = 0; i < argc && n < size; i++) {
        const char *a = argv[i];
        bool plain = *a != '\0';
        for (const char *p = a; *p; p++)
            plain &= (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
                     strchr("-_./=:,+@%", *p) != NULL;
        n += (size_t)snprintf(dest + n, size - n, plain ? " %s" : " '", a);
        for (const char *p = a; !plain && *p && n < size; p++)
            n += (size_t)snprintf(dest + n, size - n, *p == '\'' ? "'\\''" : "%c", *p);
        if (!plain && n < size) n += (size_t)snprintf(dest + n, size - n, "'");
    }
}

int cmd_compare(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    options o = {.frames = lucent_compare_defaults().frames, .out = "out/compare"};
    snprintf(o.methods_text, sizeof o.methods_text, "%s", DEFAULT_METHODS);
    int rc = parse_args(argc, argv, &o);
    if (rc == CLI_OK) rc = cli_check_folder(o.out);
    if (rc != CLI_OK) return rc;
    lucent_compare_result result;
    static char command[8192];
    command_line(argc, argv, command, sizeof command);
    lucent_compare_desc d = {.scenes = o.scenes,
                             .scene_count = o.scene_count,
                             .methods = o.methods,
                             .method_count = o.method_count,
                             .overrides = o.sets,
                             .override_count = o.set_count,
                             .spp = o.spp,
                             .time_limit = o.time_limit,
                             .frames = o.frames,
                             .samples = o.samples,
                             .scale = o.scale,
                             .out = o.out,
                             .title = o.title,
                             .pool = cli_pool(),
                             .on_event = on_event,
                             .user = &result,
                             .reference_runs = o.reference_runs,
                             .reference = o.reference,
                             .per_light = o.per_light,
                             .revision = lucent_cli_revision,
                             .command = command,

                             .peers = o.peers,
                             .peer_count = o.peer_count,
                             .peer_spp = o.peer_spp,
                             .peer_seed = (uint64_t)o.peer_seed};
    lucent_status s = lucent_compare_run(&d, &result);
    if (s == LUCENT_OK) cli_wrote("wrote %s/report.html (and report.md, report.csv, results.json)", o.out);
    lucent_compare_result_free(&result);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
