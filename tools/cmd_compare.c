/* `lucent compare`: every real-time method of a scene against the path-traced reference, in error
 * and in time, as an HTML report with images (and Markdown, CSV, JSON). */
#include <stdarg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "cli.h"
#include "lucent/render.h"
#include "lucent/report.h"
#include "lucent/trace.h"

enum { MAX_SCENES = 16, MAX_METHODS = 32, MAX_SETS = 64, NAME_SIZE = 64, PATH_SIZE = 1200 };

#define DEFAULT_METHODS "lambert,cdrf,cdrf+translucency,ssss:preint,ssss:svd1,ssss:svd3,ssss:guided,ssss:manual,ssss:jimenez"
#define ERROR_MAP_SCALE 0.5f /* a relative error of 50% is white in the heat maps */

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
    "                   any of lambert, cdrf, cdrf+translucency, ssss, ssss:<model>[rank]\n"
    "  --spp N          reference samples per pixel (default: the scene's render.spp)\n"
    "  --time S         at most S seconds per reference (default: no limit)\n"
    "  --frames N       GL frames timed per method; the median is reported (default 5)\n"
    "  --scale F        multiply every scene's render.width and height by F (keeps each aspect)\n"
    "  --set KEY=VALUE  override a scene value, for every scene (repeatable; see docs/scenes.md)\n"
    "  --out DIR        output folder (default out/compare)\n"
    "  --title TEXT     the report's title\n"
    "  -h, --help       show this help\n"
    "\n"
    "examples:\n"
    "  lucent compare data/scenes/spheres-skin.json --spp 256 --out out/spheres\n"
    "  lucent compare data/scenes/dragon-marble.json --methods lambert,ssss:svd3 --set render.width=256 \\\n"
    "      --set render.height=256 --out out/dragon\n";

typedef struct options {
    const char *scenes[MAX_SCENES];
    int scene_count;
    char methods_text[1024];
    const char *methods[MAX_METHODS];
    int method_count;
    int spp, frames;
    double time_limit, scale;
    const char *sets[MAX_SETS];
    int set_count;
    const char *out, *title;
} options;

/* ---- options ---- */

static int split_methods(options *o)
{
    o->method_count = 0;
    for (char *save = NULL, *t = strtok_r(o->methods_text, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        lucent_render_method m;
        if (o->method_count == MAX_METHODS) return cli_usage_error("compare", "at most %d methods", MAX_METHODS);
        if (lucent_render_method_parse(t, &m, NULL, NULL) != LUCENT_OK)
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
    static const char *const numeric[] = {"--spp", "--frames", "--time", "--scale"};
    for (int i = 1; i < argc; i++) {
        const char *v;
        int rc = -1;
        for (int k = 0; k < 4 && rc < 0; k++)
            if (cli_option(argc, argv, &i, numeric[k], &v)) rc = parse_number_option(numeric[k], v, o);
        if (rc > 0) return rc;
        if (rc == 0) continue;
        if (cli_option(argc, argv, &i, "--methods", &v)) {
            if (!v || strlen(v) >= sizeof o->methods_text) return cli_usage_error("compare", "--methods needs a list");
            snprintf(o->methods_text, sizeof o->methods_text, "%s", v);
        } else if (cli_option(argc, argv, &i, "--set", &v)) {
            if (!v || !strchr(v, '=')) return cli_usage_error("compare", "--set needs KEY=VALUE");
            if (o->set_count == MAX_SETS) return cli_usage_error("compare", "at most %d --set", MAX_SETS);
            o->sets[o->set_count++] = v;
        } else if (cli_option(argc, argv, &i, "--out", &v)) {
            if (!v || strlen(v) > 512) return cli_usage_error("compare", "--out needs a folder (at most 512 characters)");
            o->out = v;
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

/* ---- one scene ---- */

typedef struct method_run {
    char name[NAME_SIZE], image[PATH_SIZE], error_image[PATH_SIZE], settings[256];
    lucent_compare_method row;
    lucent_frame_times times;
} method_run;

typedef struct scene_run {
    lucent_scene *scene;
    char stem[NAME_SIZE];     /* the scene's folder under DIR */
    char reference[PATH_SIZE], chart[PATH_SIZE], device[300];
    lucent_trace_result ref;
    float *mask;              /* object pixels counted in the errors */
    uint64_t mask_pixels;
    method_run methods[MAX_METHODS];
    int method_count;
    lucent_compare_method rows[MAX_METHODS]; /* the report's view of methods[] */
    lucent_compare_scene report;
} scene_run;

/* snprintf into a path buffer; a path that does not fit is an error, not a truncated file name. */
static lucent_status path_printf(char *dest, size_t size, const char *fmt, ...) LUCENT_PRINTF(3, 4);
static lucent_status path_printf(char *dest, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(dest, size, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= size) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%.60s...: path too long", dest);
    return LUCENT_OK;
}

/* "ssss:svd3" -> "ssss-svd3", "cdrf+translucency" -> "cdrf-translucency": a file stem. */
static void file_stem(const char *name, char *dest, size_t size)
{
    snprintf(dest, size, "%s", name);
    for (char *p = dest; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '-'))
            *p = '-';
}

/* Writes img as DIR/REL.png (tonemapped as the scene says) and DIR/REL.exr (linear). */
static lucent_status write_pair(const char *dir, const char *rel, const lucent_image *img,
                                const lucent_render_settings *rs)
{
    char path[PATH_SIZE];
    lucent_image *t;
    lucent_status s = path_printf(path, sizeof path, "%s/%s.exr", dir, rel);
    if (s == LUCENT_OK) s = lucent_image_write(path, img, NULL);
    if (s == LUCENT_OK) s = lucent_image_clone(img, &t);
    if (s != LUCENT_OK) return s;
    lucent_image_tonemap(t, &(lucent_tonemap_desc){.op = rs->tonemap, .exposure = (float)rs->exposure});
    s = path_printf(path, sizeof path, "%s/%s.png", dir, rel);
    if (s == LUCENT_OK) s = lucent_image_write(path, t, NULL);
    lucent_image_destroy(t);
    return s;
}

/* Pixels fully covered by an object in the reference and whose 8 neighbours are too (silhouette
 * pixels mix object and background differently in the two renderers: the tracer averages over the
 * pixel, the GL renderer takes its centre). */
static lucent_status object_mask(scene_run *sr)
{
    const lucent_image *c = sr->ref.coverage;
    sr->mask = calloc((size_t)c->width * (size_t)c->height, sizeof *sr->mask);
    if (!sr->mask) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    sr->mask_pixels = 0;
    for (int y = 1; y + 1 < c->height; y++)
        for (int x = 1; x + 1 < c->width; x++) {
            bool inside = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) inside = inside && lucent_image_get(c, x + dx, y + dy, 0) >= 0.999f;
            sr->mask[(size_t)y * (size_t)c->width + (size_t)x] = inside;
            sr->mask_pixels += inside;
        }
    if (!sr->mask_pixels) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no object covers the image", sr->scene->path);
    return LUCENT_OK;
}

/* The reference's own relative standard error over the mask: sqrt(sum var / sum ref^2), the RMS
 * distance from the truth that the reference alone contributes to every method's error. */
static double reference_noise(const scene_run *sr)
{
    const lucent_image *m = sr->ref.image, *v = sr->ref.variance;
    double var = 0, sq = 0;
    for (size_t i = 0; i < (size_t)m->width * (size_t)m->height; i++)
        for (int c = 0; c < 3 && sr->mask[i] > 0.5f; c++) {
            double r = m->data[i * (size_t)m->channels + (size_t)c];
            var += v->data[i * (size_t)v->channels + (size_t)c], sq += r * r;
        }
    return sq > 0 ? sqrt(var / sq) : 0;
}

static lucent_status render_reference(scene_run *sr, const options *o, const char *dir)
{
    lucent_tracer *tr;
    char label[NAME_SIZE + 16];
    snprintf(label, sizeof label, "reference %s", sr->stem);
    lucent_status s = lucent_tracer_create(sr->scene, NULL, &tr);
    if (s != LUCENT_OK) return s;
    s = lucent_tracer_render(tr, &(lucent_trace_desc){.spp = o->spp, .pool = cli_pool(), .time_limit = o->time_limit, .label = label},
                              &sr->ref);
    lucent_tracer_destroy(tr);
    if (s == LUCENT_OK) s = write_pair(dir, "reference", sr->ref.image, &sr->scene->render);
    if (s == LUCENT_OK) s = object_mask(sr);
    snprintf(sr->reference, sizeof sr->reference, "%s/reference.png", sr->stem);
    return s;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Times `frames` frames of the method (the first render made the image) and keeps the median
 * frame's pass times. */
static lucent_status time_frames(lucent_renderer *r, const lucent_render_settings *rs, int frames, method_run *mr)
{
    lucent_frame_times t[64];
    double gpu[64];
    int n = frames < 64 ? frames : 64;
    for (int i = 0; i < n; i++) {
        lucent_status s = lucent_render_frame(r, rs, &t[i]);
        if (s != LUCENT_OK) return s;
        gpu[i] = t[i].gpu_ms;
    }
    qsort(gpu, (size_t)n, sizeof *gpu, cmp_double);
    for (int i = 0; i < n; i++)
        if (t[i].gpu_ms == gpu[n / 2]) mr->times = t[i];
    mr->row.frame_ms = gpu[n / 2];
    return LUCENT_OK;
}

/* Relative RMS errors over the mask, and the heat map of the per-pixel relative error. */
static lucent_status measure(scene_run *sr, const lucent_image *img, const char *dir, method_run *mr)
{
    lucent_image_error_stats e;
    lucent_image *err = NULL, *heat = NULL;
    lucent_status s = lucent_image_compare(img, sr->ref.image, sr->mask, &e);
    if (s != LUCENT_OK) return s;
    mr->row.rel_rms = e.rel_rms_all;
    for (int c = 0; c < 3; c++) mr->row.rel_rms_rgb[c] = e.rel_rms[c];
    s = lucent_image_error_map(img, sr->ref.image, true, 0.01f, &err);
    for (size_t i = 0; s == LUCENT_OK && i < (size_t)err->width * (size_t)err->height; i++) err->data[i] *= sr->mask[i];
    if (s == LUCENT_OK) s = lucent_image_heatmap(err, ERROR_MAP_SCALE, &heat);
    char path[PATH_SIZE], stem[NAME_SIZE];
    file_stem(mr->name, stem, sizeof stem);
    if (s == LUCENT_OK) s = path_printf(path, sizeof path, "%s/%s-error.png", dir, stem);
    if (s == LUCENT_OK) s = lucent_image_write(path, heat, NULL);
    if (s == LUCENT_OK) s = path_printf(mr->error_image, sizeof mr->error_image, "%s/%s-error.png", sr->stem, stem);
    lucent_image_destroy(err);
    lucent_image_destroy(heat);
    return s;
}

/* What distinguishes this run, for the table. */
static void describe(const lucent_render_settings *rs, method_run *mr)
{
    if (rs->method == LUCENT_METHOD_SSSS)
        snprintf(mr->settings, sizeof mr->settings, "%s rank %d, %d taps, %s profile, depth filter %s%s%s%s",
                 lucent_kernel_model_name(rs->kernel_model), rs->kernel_rank, rs->taps, rs->profile,
                 lucent_depth_filter_name(rs->depth_filter), rs->translucency ? ", " : "",
                 rs->translucency ? lucent_transmittance_name(rs->transmittance) : "",
                 rs->translucency ? " translucency" : "");
    else if (rs->method != LUCENT_METHOD_LAMBERT)
        snprintf(mr->settings, sizeof mr->settings, "%s, %s, sigma0 from %s%s%s", lucent_cdrf_variant_name(rs->cdrf_variant),
                 rs->cdrf_lut ? "LUT" : "closed form", rs->sigma0_source == LUCENT_SIGMA0_FIT ? "the sphere fit" : "the diffuse colour",
                 rs->method == LUCENT_METHOD_CDRF_TRANSLUCENCY ? ", translucency " : "",
                 rs->method == LUCENT_METHOD_CDRF_TRANSLUCENCY ? lucent_transmittance_name(rs->transmittance) : "");
    else
        snprintf(mr->settings, sizeof mr->settings, "Lambert + specular lobe");
}

static lucent_status run_method(scene_run *sr, lucent_renderer *r, const char *method, const options *o,
                                const char *dir, method_run *mr)
{
    lucent_render_settings rs = sr->scene->render;
    lucent_render_result res = {0};
    lucent_status s = lucent_render_method_parse(method, &rs.method, &rs.kernel_model, &rs.kernel_rank);
    snprintf(mr->name, sizeof mr->name, "%s", method);
    if (s == LUCENT_OK) s = lucent_render(r, &rs, &res);
    char stem[NAME_SIZE];
    file_stem(method, stem, sizeof stem);
    if (s == LUCENT_OK) s = write_pair(dir, stem, res.image, &rs);
    if (s == LUCENT_OK) s = measure(sr, res.image, dir, mr);
    if (s == LUCENT_OK) s = time_frames(r, &rs, o->frames, mr);
    mr->row.setup_ms = res.times.setup_ms;
    snprintf(mr->image, sizeof mr->image, "%s/%s.png", sr->stem, stem);
    describe(&rs, mr);
    lucent_render_result_free(&res);
    if (s != LUCENT_OK) return lucent_error_context(s, "%s: method %s", sr->stem, method);
    return LUCENT_OK;
}

static void fill_report(scene_run *sr, const lucent_gl_info *info)
{
    snprintf(sr->device, sizeof sr->device, "%.160s (%.128s)", info->renderer, info->version);
    for (int i = 0; i < sr->method_count; i++) {
        method_run *m = &sr->methods[i];
        m->row.name = m->name, m->row.image = m->image, m->row.error_image = m->error_image;
        m->row.settings = m->settings;
        sr->rows[i] = m->row;
    }
    sr->report = (lucent_compare_scene){.name = sr->stem,
                                        .description = sr->scene->description,
                                        .width = sr->scene->render.width,
                                        .height = sr->scene->render.height,
                                        .reference_image = sr->reference,
                                        .reference_spp = (int)sr->ref.spp,
                                        .reference_seconds = sr->ref.seconds,
                                        .reference_noise = reference_noise(sr),
                                        .device = sr->device,
                                        .chart = sr->chart,
                                        .scene_json = sr->scene->json,
                                        .methods = sr->rows,
                                        .method_count = sr->method_count};
}

static void print_scene(const scene_run *sr)
{
    const lucent_compare_scene *r = &sr->report;
    cli_info("%s: %d x %d; reference %d spp in %.1f s (its noise %.2f%%); %s", r->name, r->width, r->height,
             r->reference_spp, r->reference_seconds, 100 * r->reference_noise, r->device);
    cli_info("  %-22s %14s %13s %12s %12s", "method", "rel. RMS error", "net of noise", "frame ms", "setup ms");
    for (int i = 0; i < sr->method_count; i++)
        cli_info("  %-22s %13.2f%% %12.2f%% %12.3f %12.0f", sr->methods[i].name, 100 * sr->methods[i].row.rel_rms,
                 100 * lucent_compare_net_error(sr->methods[i].row.rel_rms, r->reference_noise),
                 sr->methods[i].row.frame_ms, sr->methods[i].row.setup_ms);
}

/* Loads the scene with the --set overrides and, for --scale, two more that resize it (read from a
 * first, mesh-less load), so that the scene's JSON records the size the images have. */
static lucent_status load_scene(const options *o, const char *path, lucent_scene **dest)
{
    const char *sets[MAX_SETS + 2];
    char size[2][48];
    int n = o->set_count;
    memcpy(sets, o->sets, (size_t)n * sizeof *sets);
    if (o->scale > 0) {
        lucent_scene *probe;
        lucent_status s = lucent_scene_load(path, &(lucent_scene_load_desc){.overrides = sets, .override_count = n,
                                                                            .skip_meshes = true},
                                            &probe);
        if (s != LUCENT_OK) return s;
        snprintf(size[0], sizeof size[0], "render.width=%ld", lround(fmax(1, probe->render.width * o->scale)));
        snprintf(size[1], sizeof size[1], "render.height=%ld", lround(fmax(1, probe->render.height * o->scale)));
        lucent_scene_destroy(probe);
        sets[n++] = size[0], sets[n++] = size[1];
    }
    return lucent_scene_load(path, &(lucent_scene_load_desc){.overrides = sets, .override_count = n}, dest);
}

static lucent_status compare_scene(const options *o, lucent_gl_context *gl, const char *path, scene_run *sr)
{
    lucent_status s = load_scene(o, path, &sr->scene);
    if (s != LUCENT_OK) return s;
    file_stem(sr->scene->name, sr->stem, sizeof sr->stem);
    char dir[PATH_SIZE], cache[PATH_SIZE];
    if ((s = path_printf(dir, sizeof dir, "%s/%s", o->out, sr->stem)) == LUCENT_OK) s = lucent_mkdir_p(dir);
    if (s == LUCENT_OK) s = render_reference(sr, o, dir);
    lucent_renderer *r = NULL;
    if (s == LUCENT_OK && (s = path_printf(cache, sizeof cache, "%s/.cache", o->out)) == LUCENT_OK) s = lucent_mkdir_p(cache);
    if (s == LUCENT_OK)
        s = lucent_renderer_create(gl, sr->scene, &(lucent_renderer_desc){.pool = cli_pool(), .cache_dir = cache}, &r);
    for (int i = 0; i < o->method_count && s == LUCENT_OK; i++, sr->method_count++)
        s = run_method(sr, r, o->methods[i], o, dir, &sr->methods[i]);
    lucent_renderer_destroy(r);
    lucent_gl_info info;
    lucent_gl_get_info(gl, &info);
    snprintf(sr->chart, sizeof sr->chart, "%s/errors.svg", sr->stem);
    fill_report(sr, &info);
    char chart[PATH_SIZE];
    if (s == LUCENT_OK) s = path_printf(chart, sizeof chart, "%s/errors.svg", dir);
    if (s == LUCENT_OK) s = lucent_compare_write_chart(chart, &sr->report);
    if (s == LUCENT_OK) print_scene(sr);
    return s;
}

/* ---- the whole run ---- */

static lucent_status write_results_json(const char *path, scene_run *runs, int count)
{
    cJSON *root = cJSON_CreateObject(), *scenes = cJSON_AddArrayToObject(root, "scenes");
    for (int i = 0; scenes && i < count; i++) {
        const lucent_compare_scene *r = &runs[i].report;
        cJSON *sc = cJSON_CreateObject(), *methods;
        cJSON_AddItemToArray(scenes, sc);
        cJSON_AddStringToObject(sc, "name", r->name);
        cJSON_AddNumberToObject(sc, "width", r->width), cJSON_AddNumberToObject(sc, "height", r->height);
        cJSON_AddNumberToObject(sc, "reference_spp", r->reference_spp);
        cJSON_AddNumberToObject(sc, "reference_seconds", r->reference_seconds);
        cJSON_AddNumberToObject(sc, "reference_noise", r->reference_noise);
        cJSON_AddNumberToObject(sc, "object_pixels", (double)runs[i].mask_pixels);
        cJSON_AddStringToObject(sc, "device", r->device);
        cJSON_AddItemToObject(sc, "scene", cJSON_Parse(r->scene_json));
        methods = cJSON_AddArrayToObject(sc, "methods");
        for (int k = 0; methods && k < r->method_count; k++) {
            const method_run *m = &runs[i].methods[k];
            cJSON *j = cJSON_CreateObject();
            cJSON_AddItemToArray(methods, j);
            cJSON_AddStringToObject(j, "method", m->name);
            cJSON_AddNumberToObject(j, "rel_rms", m->row.rel_rms);
            cJSON_AddNumberToObject(j, "rel_rms_net", lucent_compare_net_error(m->row.rel_rms, r->reference_noise));
            lucent_json_add_numbers(j, "rel_rms_rgb", m->row.rel_rms_rgb, 3);
            cJSON_AddNumberToObject(j, "frame_ms", m->row.frame_ms);
            cJSON_AddNumberToObject(j, "setup_ms", m->row.setup_ms);
            cJSON_AddStringToObject(j, "settings", m->settings);
            cJSON *passes = cJSON_AddObjectToObject(j, "passes_ms");
            for (int p = 0; passes && p < m->times.pass_count; p++)
                cJSON_AddNumberToObject(passes, m->times.pass_name[p], m->times.pass_ms[p]);
        }
    }
    lucent_status s = root && scenes ? lucent_json_write_file(path, root)
                                     : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    cJSON_Delete(root);
    return s;
}

static lucent_status write_reports(const options *o, scene_run *runs, int count)
{
    lucent_compare_scene reports[MAX_SCENES];
    for (int i = 0; i < count; i++) reports[i] = runs[i].report;
    char path[PATH_SIZE];
    const char *title = o->title ? o->title : "Lucent: real-time subsurface scattering against a path-traced reference";
    snprintf(path, sizeof path, "%s/report.html", o->out);
    lucent_status s = lucent_compare_write_html(path, title, reports, count);
    snprintf(path, sizeof path, "%s/report.md", o->out);
    if (s == LUCENT_OK) s = lucent_compare_write_markdown(path, reports, count);
    snprintf(path, sizeof path, "%s/report.csv", o->out);
    if (s == LUCENT_OK) s = lucent_compare_write_csv(path, reports, count);
    snprintf(path, sizeof path, "%s/results.json", o->out);
    if (s == LUCENT_OK) s = write_results_json(path, runs, count);
    return s;
}

static void free_runs(scene_run *runs, int count)
{
    for (int i = 0; runs && i < count; i++) {
        lucent_trace_result_free(&runs[i].ref);
        free(runs[i].mask);
        lucent_scene_destroy(runs[i].scene);
    }
    free(runs);
}

int cmd_compare(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    options o = {.frames = 5, .out = "out/compare"};
    snprintf(o.methods_text, sizeof o.methods_text, "%s", DEFAULT_METHODS);
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    scene_run *runs = calloc(MAX_SCENES, sizeof *runs);
    lucent_gl_context *gl = NULL;
    lucent_status s = runs ? lucent_mkdir_p(o.out) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) s = lucent_gl_create(NULL, &gl);
    int done = 0;
    for (; s == LUCENT_OK && done < o.scene_count; done++) s = compare_scene(&o, gl, o.scenes[done], &runs[done]);
    if (s == LUCENT_OK) s = write_reports(&o, runs, done);
    if (s == LUCENT_OK) cli_info("wrote %s/report.html (and report.md, report.csv, results.json)", o.out);
    free_runs(runs, o.scene_count);
    lucent_gl_destroy(gl);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
