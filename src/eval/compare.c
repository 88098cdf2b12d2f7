/* lucent_compare_run: per scene the path-traced reference, every GL method, their measures over
 * the object mask (the relative RMS error, the paired test between methods, FLIP, the regions), their
 * frame times, each light alone when asked, and (with an output folder) the files. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval/compare_store.h"

lucent_compare_desc lucent_compare_defaults(void)
{
    return (lucent_compare_desc){.frames = 5, .title = LUCENT_COMPARE_DEFAULT_TITLE};
}

/* ---- the desc ---- */

static void default_methods(run *r)
{
    snprintf(r->method_text, sizeof r->method_text, "%s", LUCENT_COMPARE_DEFAULT_METHODS);
    r->d.method_count = 0;
    for (char *save = NULL, *t = strtok_r(r->method_text, ",", &save); t; t = strtok_r(NULL, ",", &save))
        r->methods[r->d.method_count++] = t;
    r->d.methods = r->methods;
}

static lucent_status resolve(const lucent_compare_desc *desc, run *r)
{
    lucent_compare_desc def = lucent_compare_defaults();
    r->d = *desc;
    if (!r->d.frames) r->d.frames = def.frames;
    if (!r->d.title) r->d.title = def.title;
    if (!desc->scenes || desc->scene_count < 1 || desc->scene_count > LUCENT_COMPARE_MAX_SCENES)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: scene_count: give 1 to %d scenes",
                            LUCENT_COMPARE_MAX_SCENES);
    if (desc->method_count < 0 || desc->method_count > LUCENT_COMPARE_MAX_METHODS ||
        (desc->method_count && !desc->methods))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: method_count: at most %d methods",
                            LUCENT_COMPARE_MAX_METHODS);
    if (desc->override_count < 0 || (desc->override_count && !desc->overrides))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: override_count: %d overrides without a list",
                            desc->override_count);
    if (desc->spp < 0 || desc->frames < 0 || !(desc->time_limit >= 0) || !(desc->scale >= 0) || !isfinite(desc->scale))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: spp, frames, time_limit and scale must be >= 0");
    if (desc->reference_runs < 0 || desc->reference_runs > 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: reference_runs: 0 (automatic), 1 or 2, got %d",
                            desc->reference_runs);
    if (desc->peer_count < 0 || (desc->peer_count && !desc->peers) ||
        (desc->method_count ? desc->method_count : 1) + desc->peer_count > LUCENT_COMPARE_MAX_METHODS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: peer_count: at most %d methods and peers",
                            LUCENT_COMPARE_MAX_METHODS);
    for (int i = 0; i < desc->peer_count; i++)
        if (eval_peer_check(desc->peers[i]) != LUCENT_OK)
            return lucent_error_context(LUCENT_ERR_INVALID_ARGUMENT, "compare");
    if (!desc->method_count) default_methods(r);
    for (int i = 0; i < r->d.method_count; i++) {
        lucent_render_settings probe = lucent_render_settings_defaults();
        lucent_status s = eval_method_settings(r->d.methods[i], &probe);
        if (s != LUCENT_OK) return lucent_error_context(s, "compare: methods[%d]", i);
    }
    return LUCENT_OK;
}

/* ---- one scene ---- */

lucent_status eval_write_image(const run *r, const scene_store *ss, const char *stem, const lucent_image *img,
                               const lucent_render_settings *rs)
{
    if (!r->d.out) return LUCENT_OK;
    lucent_tonemap_desc tm = eval_tonemap(rs);
    lucent_status s = lucent_compare_write_image(ss->dir, stem, img, &tm);
    static const char *const exts[] = {"exr", "png"};
    for (int k = 0; k < 2 && s == LUCENT_OK; k++) {
        char path[EVAL_PATH_SIZE];
        s = eval_path_printf(path, sizeof path, "%s/%s.%s", ss->dir, stem, exts[k]);
        eval_wrote(r->d.on_event, r->d.user, s, path);
    }
    return s;
}

static lucent_status make_mask(scene_store *ss)
{
    const lucent_image *c = ss->ref.result.coverage;
    ss->mask = malloc((size_t)c->width * (size_t)c->height * sizeof *ss->mask);
    if (!ss->mask) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    ss->mask_pixels = lucent_compare_object_mask(c, ss->mask);
    if (!ss->mask_pixels)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no object covers the image", ss->scene->path);
    return LUCENT_OK;
}

/* Whether the reference folder dir is the output folder (its files are then read and not rewritten). */
static bool same_folder(const char *a, const char *b)
{
    char ra[4096], rb[4096];
    return a && b && realpath(a, ra) && realpath(b, rb) && !strcmp(ra, rb);
}

/* The reference: traced, or read from the folder of an earlier run (desc.reference); written with
 * what made it, so that a later run can reuse it. */
static lucent_status reference(const run *r, scene_store *ss)
{
    char label[EVAL_NAME_SIZE + 16];
    snprintf(label, sizeof label, "reference %s", ss->stem);
    lucent_status s;
    bool reused = r->d.reference != NULL, in_place = false;
    if (reused) {
        char dir[EVAL_PATH_SIZE];
        s = eval_path_printf(dir, sizeof dir, "%s/%s", r->d.reference, ss->stem);
        if (s == LUCENT_OK) s = eval_reference_read(dir, ss->scene, &ss->ref);
        snprintf(ss->reference_from, sizeof ss->reference_from, "%s", r->d.reference);
        in_place = r->d.out && same_folder(r->d.reference, r->d.out);
    } else {
        s = eval_reference_trace(ss->scene,
                                 &(eval_reference_desc){.spp = r->d.spp,
                                                        .time_limit = r->d.time_limit,
                                                        .runs = r->d.reference_runs,
                                                        .pool = r->d.pool,
                                                        .label = label},
                                 &ss->ref);
    }
    if (s == LUCENT_OK && r->d.out && !in_place) {
        s = eval_write_image(r, ss, "reference", ss->ref.result.image, &ss->scene->render);
        if (s == LUCENT_OK) s = eval_reference_write(ss->dir, ss->scene, &ss->ref, r->d.on_event, r->d.user);
    } else if (s == LUCENT_OK && in_place) { /* reference.exr was read: only its PNG again */
        lucent_tonemap_desc tm = eval_tonemap(&ss->scene->render);
        lucent_image *t = NULL;
        char path[EVAL_PATH_SIZE];
        s = lucent_image_clone(ss->ref.result.image, &t);
        if (s == LUCENT_OK) lucent_image_tonemap(t, &tm);
        if (s == LUCENT_OK) s = eval_path_printf(path, sizeof path, "%s/reference.png", ss->dir);
        if (s == LUCENT_OK) s = eval_wrote(r->d.on_event, r->d.user, lucent_image_write(path, t, NULL), path);
        lucent_image_destroy(t);
    }
    if (s == LUCENT_OK) s = make_mask(ss);
    snprintf(ss->reference, sizeof ss->reference, "%s/reference.png", ss->stem);
    return s;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Times the frames (the first render made the image) and keeps the median frame's pass times. */
static lucent_status time_frames(const run *r, lucent_renderer *rend, const lucent_render_settings *rs,
                                 lucent_compare_method *row, lucent_frame_times *times, lucent_progress *bar)
{
    lucent_frame_times t[LUCENT_COMPARE_MAX_FRAMES];
    double gpu[LUCENT_COMPARE_MAX_FRAMES];
    int n = r->d.frames < LUCENT_COMPARE_MAX_FRAMES ? r->d.frames : LUCENT_COMPARE_MAX_FRAMES;
    for (int i = 0; i < n; i++) {
        lucent_status s = lucent_render_frame(rend, rs, &t[i]);
        if (s != LUCENT_OK) return s;
        gpu[i] = t[i].gpu_ms;
        lucent_progress_add(bar, 1);
    }
    qsort(gpu, (size_t)n, sizeof *gpu, cmp_double);
    for (int i = 0; i < n; i++)
        if (t[i].gpu_ms == gpu[n / 2]) *times = t[i];
    row->frame_ms = gpu[n / 2];
    return LUCENT_OK;
}

/* Copies the size x size square at (x0, y0) of src, zoomed zoom times (nearest), to column block k
 * (of width size x zoom + GAP) of dest. */
enum { CROP_GAP = 4 };
static void paste_crop(const lucent_image *src, int x0, int y0, int size, int zoom, int k, lucent_image *dest)
{
    for (int y = 0; y < size * zoom; y++)
        for (int x = 0; x < size * zoom; x++)
            for (int c = 0; c < 3; c++)
                lucent_image_set(dest, k * (size * zoom + CROP_GAP) + x, y, c,
                                 lucent_image_get(src, x0 + x / zoom, y0 + y / zoom, c));
}

/* The worst region of a method, zoomed: the reference, the method (both tonemapped as their PNGs)
 * and the signed error map side by side, into DIR/STEM-worst.png. */
static lucent_status write_crop(const run *r, scene_store *ss, const lucent_image *img, const lucent_image *heat,
                                const lucent_render_settings *rs, int m, const char *stem)
{
    lucent_compare_method *row = &ss->rows[m];
    method_store *ms = &ss->methods[m];
    const lucent_image *ref = ss->ref.result.image;
    int size = (ref->width < ref->height ? ref->width : ref->height) / 6;
    size = size < 8 ? (ref->width < 8 || ref->height < 8 ? (ref->width < ref->height ? ref->width : ref->height) : 8)
                    : size;
    int zoom = size >= 160 ? 1 : 160 / size, x0, y0;
    lucent_status s = lucent_compare_worst_region(img, ref, ss->mask, size, &x0, &y0);
    lucent_image *a = NULL, *b = NULL, *out = NULL;
    if (s == LUCENT_OK) s = lucent_image_clone(ref, &a);
    if (s == LUCENT_OK) s = lucent_image_clone(img, &b);
    if (s == LUCENT_OK) s = lucent_image_create(3 * size * zoom + 2 * CROP_GAP, size * zoom, 3, &out);
    if (s == LUCENT_OK) {
        lucent_tonemap_desc tr = eval_tonemap(&ss->scene->render), tm = eval_tonemap(rs);
        lucent_image_tonemap(a, &tr);
        lucent_image_tonemap(b, &tm);
        for (size_t i = 0; i < (size_t)out->width * (size_t)out->height * 3; i++) out->data[i] = 1; /* white gaps */
        paste_crop(a, x0, y0, size, zoom, 0, out);
        paste_crop(b, x0, y0, size, zoom, 1, out);
        paste_crop(heat, x0, y0, size, zoom, 2, out);
    }
    char path[EVAL_PATH_SIZE];
    if (s == LUCENT_OK) s = eval_path_printf(path, sizeof path, "%s/%s-worst.png", ss->dir, stem);
    if (s == LUCENT_OK) s = eval_wrote(r->d.on_event, r->d.user, lucent_image_write(path, out, NULL), path);
    if (s == LUCENT_OK) s = eval_path_printf(ms->crop_image, sizeof ms->crop_image, "%s/%s-worst.png", ss->stem, stem);
    row->crop[0] = x0, row->crop[1] = y0, row->crop[2] = size;
    lucent_image_destroy(a), lucent_image_destroy(b), lucent_image_destroy(out);
    return s;
}

/* The mean FLIP of the method's image against the reference's, both tonemapped as their PNGs. */
static lucent_status measure_flip(scene_store *ss, const lucent_image *img, const lucent_render_settings *rs,
                                  lucent_compare_method *row)
{
    lucent_image *a = NULL, *b = NULL;
    lucent_status s = lucent_image_clone(ss->ref.result.image, &a);
    if (s == LUCENT_OK) s = lucent_image_clone(img, &b);
    if (s == LUCENT_OK) {
        lucent_tonemap_desc tr = eval_tonemap(&ss->scene->render), tm = eval_tonemap(rs);
        lucent_image_tonemap(a, &tr);
        lucent_image_tonemap(b, &tm);
        s = lucent_image_flip(a, b, LUCENT_FLIP_PPD, ss->mask, NULL, &row->flip);
        row->has_flip = s == LUCENT_OK && isfinite(row->flip);
    }
    lucent_image_destroy(a), lucent_image_destroy(b);
    return s;
}

/* Relative RMS errors over the mask, FLIP, the signed error map and the worst region's crops. */
static lucent_status measure(const run *r, scene_store *ss, const lucent_image *img, const lucent_render_settings *rs,
                             int m)
{
    lucent_compare_method *row = &ss->rows[m];
    method_store *ms = &ss->methods[m];
    lucent_image_error_stats e;
    lucent_status s = lucent_image_compare(img, ss->ref.result.image, ss->mask, &e);
    if (s != LUCENT_OK) return s;
    row->rel_rms = e.rel_rms_all;
    for (int c = 0; c < 3; c++) row->rel_rms_rgb[c] = e.rel_rms[c];
    s = measure_flip(ss, img, rs, row);
    if (s == LUCENT_OK)
        s = lucent_compare_concentration(img, ss->ref.result.image, ss->mask, LUCENT_COMPARE_WORST_FRACTION,
                                         &row->worst_share);
    row->has_worst = s == LUCENT_OK;
    char stem[EVAL_NAME_SIZE], path[EVAL_PATH_SIZE];
    eval_file_stem(ms->name, stem, sizeof stem);
    if (s == LUCENT_OK)
        s = eval_path_printf(ms->error_image, sizeof ms->error_image, "%s/%s-error.png", ss->stem, stem);
    if (s != LUCENT_OK || !r->d.out) return s;
    lucent_image *heat = NULL;
    s = lucent_compare_error_map(img, ss->ref.result.image, ss->mask, &heat);
    if (s == LUCENT_OK) s = eval_path_printf(path, sizeof path, "%s/%s-error.png", ss->dir, stem);
    if (s == LUCENT_OK) s = eval_wrote(r->d.on_event, r->d.user, lucent_image_write(path, heat, NULL), path);
    if (s == LUCENT_OK) s = write_crop(r, ss, img, heat, rs, m, stem);
    lucent_image_destroy(heat);
    return s;
}

/* Tells of a method that cannot render the scene's materials; it takes no row. */
static void skip_method(const run *r, scene_store *ss, const char *method, const char *why)
{
    char reason[EVAL_PATH_SIZE];
    snprintf(reason, sizeof reason, "scene %s: %s", ss->stem, why);
    int k = ss->skipped_count++;
    snprintf(ss->skipped_name[k], sizeof ss->skipped_name[k], "%s", method);
    snprintf(ss->skipped_why[k], sizeof ss->skipped_why[k], "%s", why);
    ss->skipped[k] = (lucent_compare_skipped){.method = ss->skipped_name[k], .reason = ss->skipped_why[k]};
    if (r->d.on_event)
        r->d.on_event(
            &(lucent_eval_event){
                .kind = LUCENT_EVAL_SKIPPED, .name = method, .reason = reason, .index = r->scene_index},
            r->d.user);
}

/* Renders and measures method i of the run into the scene's next row, its progress on a bar of its
 * own ("frame k of n": the first render, then the timed frames). */
static lucent_status run_method(const run *r, scene_store *ss, lucent_renderer *rend, int i)
{
    const char *method = r->d.methods[i];
    int m = ss->method_count;
    method_store *ms = &ss->methods[m];
    lucent_render_settings rs = ss->scene->render;
    lucent_render_result res = {0};
    lucent_status s = eval_method_settings(method, &rs);
    char why[512];
    eval_image_samples(r->d.samples, &rs);
    if (s == LUCENT_OK && eval_method_unavailable(&rs, ss->scene, why, sizeof why)) {
        skip_method(r, ss, method, why);
        return LUCENT_OK;
    }
    ss->method_count++;
    snprintf(ms->name, sizeof ms->name, "%s", method);
    char label[EVAL_NAME_SIZE * 2 + 24];
    snprintf(label, sizeof label, "%s %d/%d %s", ss->stem, i + 1, r->d.method_count, method);
    int frames = r->d.frames < LUCENT_COMPARE_MAX_FRAMES ? r->d.frames : LUCENT_COMPARE_MAX_FRAMES;
    lucent_progress *bar = lucent_progress_begin(label, (uint64_t)frames + 1);
    lucent_progress_set_unit(bar, "frame");
    if (s == LUCENT_OK) s = lucent_render(rend, &rs, &res);
    lucent_progress_add(bar, 1);
    char stem[EVAL_NAME_SIZE];
    eval_file_stem(method, stem, sizeof stem);
    if (s == LUCENT_OK) s = eval_write_image(r, ss, stem, res.image, &rs);
    if (s == LUCENT_OK) s = measure(r, ss, res.image, &rs, m);
    if (s == LUCENT_OK) s = time_frames(r, rend, &rs, &ss->rows[m], &ss->times[m], bar);
    lucent_progress_end(bar);
    ss->rows[m].setup_ms = res.times.setup_ms;
    snprintf(ms->image, sizeof ms->image, "%s/%s.png", ss->stem, stem);
    eval_method_describe(&rs, ms->settings, sizeof ms->settings);
    if (s == LUCENT_OK) ss->images[m] = res.image, res.image = NULL; /* kept for the paired tests */
    lucent_render_result_free(&res);
    if (s != LUCENT_OK) return lucent_error_context(s, "%s: method %s", ss->stem, method);
    return LUCENT_OK;
}

/* Peer i (compare_peers.c) renders the scene; its image is measured as a method's, without frame times. */
static lucent_status run_peer(const run *r, scene_store *ss, int i, const char *cache_dir)
{
    const char *peer = r->d.peers[i];
    if (ss->method_count == LUCENT_COMPARE_MAX_METHODS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: at most %d methods and peers", ss->stem,
                            LUCENT_COMPARE_MAX_METHODS);
    int m = ss->method_count++;
    method_store *ms = &ss->methods[m];
    char stem[EVAL_NAME_SIZE];
    eval_peer_result pr = {0};
    snprintf(ms->name, sizeof ms->name, "%s", peer);
    eval_file_stem(peer, stem, sizeof stem);
    lucent_status s = eval_peer_render(&(eval_peer_desc){.spec = peer,
                                                         .scene = ss->scene,
                                                         .spp = r->d.peer_spp,
                                                         .seed = r->d.peer_seed ? r->d.peer_seed : 1,
                                                         .blender = r->d.blender,
                                                         .cache_dir = cache_dir,
                                                         .pool = r->d.pool},
                                       &pr);
    if (s == LUCENT_OK) s = eval_write_image(r, ss, stem, pr.image, &ss->scene->render);
    if (s == LUCENT_OK) s = measure(r, ss, pr.image, &ss->scene->render, m);
    ss->rows[m].frame_ms = ss->rows[m].setup_ms = NAN; /* not a real-time method: its seconds are in settings */
    snprintf(ms->image, sizeof ms->image, "%s/%s.png", ss->stem, stem);
    snprintf(ms->settings, sizeof ms->settings, "%s", pr.settings);
    if (s == LUCENT_OK) ss->images[m] = pr.image, pr.image = NULL; /* kept for the paired tests and regions */
    lucent_image_destroy(pr.image);
    return s == LUCENT_OK ? s : lucent_error_context(s, "%s", ss->stem);
}

lucent_status eval_load_scene(const run *r, const char *path, const char *const *extra, int extra_count,
                              lucent_scene **dest)
{
    int n = r->d.override_count;
    const char **sets = malloc(((size_t)n + (size_t)extra_count + 2) * sizeof *sets);
    if (!sets) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (n) memcpy(sets, r->d.overrides, (size_t)n * sizeof *sets);
    for (int k = 0; k < extra_count; k++) sets[n++] = extra[k];
    char size[2][48];
    lucent_status s = LUCENT_OK;
    if (r->d.scale > 0) {
        lucent_scene *probe;
        lucent_scene_load_desc probe_desc = {.overrides = sets, .override_count = n, .skip_meshes = true};
        s = lucent_scene_load(path, &probe_desc, &probe);
        if (s == LUCENT_OK) {
            eval_scale_overrides(probe, r->d.scale, size[0], size[1]);
            lucent_scene_destroy(probe);
            sets[n++] = size[0], sets[n++] = size[1];
        }
    }
    lucent_scene_load_desc load = {.overrides = sets, .override_count = n};
    if (s == LUCENT_OK) s = lucent_scene_load(path, &load, dest);
    free(sets);
    return s;
}

/* The paired test of every pair of methods, its standard error calibrated on the reference's two runs
 * when there are two. */
static lucent_status pair_tests(scene_store *ss)
{
    int n = ss->method_count;
    lucent_status s = LUCENT_OK;
    ss->inflation = 0;
    if (ss->ref.runs == 2 && n >= 2) {
        const lucent_trace_result *a = &ss->ref.run[0], *b = &ss->ref.run[1];
        s = lucent_compare_noise_inflation((const lucent_image *const *)ss->images, n, a->image, a->variance, b->image,
                                           b->variance, ss->mask, 0, &ss->inflation);
        /* the runs are of the same estimator; the combined reference's noise is the runs' mean's */
    }
    for (int i = 0; i < n && s == LUCENT_OK; i++)
        for (int j = 0; j < n && s == LUCENT_OK; j++) {
            lucent_compare_pair p = {0};
            if (i != j)
                s = lucent_compare_paired(ss->images[i], ss->images[j], ss->ref.result.image, ss->ref.result.variance,
                                          ss->mask, ss->inflation, &p);
            ss->pair_se[(size_t)i * (size_t)n + (size_t)j] = p.se;
        }
    return s;
}

/* The reference and the renderer's methods, into ss. */
static lucent_status measure_scene(const run *r, const char *path, scene_store *ss)
{
    lucent_status s = eval_load_scene(r, path, NULL, 0, &ss->scene);
    if (s != LUCENT_OK) return s;
    eval_file_stem(ss->scene->name, ss->stem, sizeof ss->stem);
    if (r->d.out && (s = eval_path_printf(ss->dir, sizeof ss->dir, "%s/%s", r->d.out, ss->stem)) == LUCENT_OK)
        s = eval_make_dirs(ss->dir);
    if (s == LUCENT_OK) s = reference(r, ss);
    char cache[EVAL_PATH_SIZE];
    const char *cache_dir = NULL;
    if (s == LUCENT_OK && r->d.out && (s = eval_path_printf(cache, sizeof cache, "%s/.cache", r->d.out)) == LUCENT_OK) {
        s = eval_make_dirs(cache);
        cache_dir = cache;
    }
    lucent_renderer *rend = NULL;
    if (s == LUCENT_OK)
        s = lucent_renderer_create(r->gl, ss->scene, &(lucent_renderer_desc){.pool = r->d.pool, .cache_dir = cache_dir},
                                   &rend);
    for (int i = 0; i < r->d.method_count && s == LUCENT_OK; i++) s = run_method(r, ss, rend, i);
    lucent_renderer_destroy(rend);
    ss->renderer_count = ss->method_count;
    for (int i = 0; i < r->d.peer_count && s == LUCENT_OK; i++) s = run_peer(r, ss, i, cache_dir);
    if (s == LUCENT_OK) s = pair_tests(ss);
    if (s == LUCENT_OK) s = eval_scene_regions(r, ss);
    if (s == LUCENT_OK && r->d.per_light) s = eval_scene_lights(r, cache_dir, ss); /* the renderer's methods */
    return s;
}

static void fill_report(const run *r, scene_store *ss, lucent_compare_scene *dest)
{
    for (int i = 0; i < ss->method_count; i++) {
        method_store *m = &ss->methods[i];
        ss->rows[i].name = m->name, ss->rows[i].image = m->image, ss->rows[i].error_image = m->error_image;
        ss->rows[i].settings = m->settings;
        ss->rows[i].crop_image = m->crop_image[0] ? m->crop_image : NULL;
    }
    const lucent_trace_result *ref = &ss->ref.result;
    /* below LUCENT_COMPARE_MIN_SPP the variance of the reference's mean cannot be estimated */
    double noise =
        ref->spp >= LUCENT_COMPARE_MIN_SPP ? lucent_compare_reference_noise(ref->image, ref->variance, ss->mask) : NAN;
    *dest = (lucent_compare_scene){.name = ss->stem,
                                   .description = ss->scene->description,
                                   .width = ref->image->width,
                                   .height = ref->image->height,
                                   .reference_image = ss->reference,
                                   .reference_spp = (int)ref->spp,
                                   .reference_seconds = ref->seconds,
                                   .reference_noise = noise,
                                   .error_scale_image = ss->dir[0] ? "error-scale.png" : NULL,
                                   .error_scale = LUCENT_COMPARE_ERROR_MAP_SCALE,
                                   .device = ss->device,
                                   .chart = ss->chart,
                                   .scene_json = ss->scene->json,
                                   .methods = ss->rows,
                                   .method_count = ss->method_count,
                                   .skipped = ss->skipped,
                                   .skipped_count = ss->skipped_count,
                                   .pair_se = ss->pair_se,
                                   .se_inflation = ss->inflation,
                                   .reference_runs = ss->ref.runs,
                                   .reference_from = ss->reference_from[0] ? ss->reference_from : NULL,
                                   .regions = ss->region_count ? ss->regions : NULL,
                                   .region_count = ss->region_count,
                                   .lights = ss->light_count ? ss->lights : NULL,
                                   .light_count = ss->light_count,
                                   .provenance = &r->provenance};
}

static lucent_status compare_scene(const run *r, const char *path, scene_store *ss, lucent_compare_scene_result *dest)
{
    lucent_status s = measure_scene(r, path, ss);
    for (int i = 0; i < LUCENT_COMPARE_MAX_METHODS; i++) lucent_image_destroy(ss->images[i]), ss->images[i] = NULL;
    if (s != LUCENT_OK) return s;
    snprintf(ss->device, sizeof ss->device, "%s", r->device);
    snprintf(ss->chart, sizeof ss->chart, "%s/errors.svg", ss->stem);
    *dest = (lucent_compare_scene_result){
        .reference = &ss->ref.result, .mask = ss->mask, .object_pixels = ss->mask_pixels, .times = ss->times};
    fill_report(r, ss, &dest->report);
    if (!r->d.out) return LUCENT_OK;
    char chart[EVAL_PATH_SIZE];
    s = eval_path_printf(chart, sizeof chart, "%s/errors.svg", ss->dir);
    if (s == LUCENT_OK) s = lucent_compare_write_chart(chart, &dest->report);
    return eval_wrote(r->d.on_event, r->d.user, s, chart);
}

/* ---- the run ---- */

static lucent_status compare_all(run *r, lucent_compare_result *dest)
{
    lucent_compare_store *st = dest->store;
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < r->d.scene_count && s == LUCENT_OK; i++) {
        st->count = i + 1;
        r->scene_index = i;
        s = compare_scene(r, r->d.scenes[i], &st->scenes[i], &dest->scenes[i]);
        if (s != LUCENT_OK) break;
        dest->scene_count = i + 1;
        if (r->d.on_event)
            r->d.on_event(&(lucent_eval_event){.kind = LUCENT_EVAL_SCENE_DONE, .name = st->scenes[i].stem, .index = i},
                          r->d.user);
    }
    if (s == LUCENT_OK && r->d.out) { /* the error maps' colour bar, once */
        lucent_image *bar = NULL;
        char path[EVAL_PATH_SIZE];
        s = eval_path_printf(path, sizeof path, "%s/error-scale.png", r->d.out);
        if (s == LUCENT_OK) s = lucent_compare_error_scale_image(&bar);
        if (s == LUCENT_OK) s = eval_wrote(r->d.on_event, r->d.user, lucent_image_write(path, bar, NULL), path);
        lucent_image_destroy(bar);
    }
    if (s == LUCENT_OK && r->d.out)
        s = lucent_compare_write_reports(r->d.out, r->d.title, dest, r->d.on_event, r->d.user);
    return s;
}

/* The run's provenance: what the application gave, the machine, the date and the GL renderer. */
static void provenance(run *r)
{
    lucent_gl_info info;
    lucent_gl_get_info(r->gl, &info);
    snprintf(r->device, sizeof r->device, "%.160s (%.128s)", info.renderer, info.version);
    eval_machine(r->machine, sizeof r->machine, &r->provenance.cores);
    eval_date(r->date, sizeof r->date);
    r->provenance.version = LUCENT_VERSION_STRING;
    r->provenance.revision = r->d.revision ? r->d.revision : "unknown";
    r->provenance.command = r->d.command ? r->d.command : "";
    r->provenance.date = r->date, r->provenance.machine = r->machine, r->provenance.renderer = r->device;
}

lucent_status lucent_compare_run(const lucent_compare_desc *desc, lucent_compare_result *dest)
{
    *dest = (lucent_compare_result){0};
    run *r = calloc(1, sizeof *r);
    if (!r) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = resolve(desc, r);
    if (s != LUCENT_OK) {
        free(r);
        return s;
    }
    dest->store = calloc(1, sizeof *dest->store);
    if (dest->store) dest->store->scenes = calloc((size_t)r->d.scene_count, sizeof *dest->store->scenes);
    if (dest->store) dest->store->run = r;
    dest->scenes = calloc((size_t)r->d.scene_count, sizeof *dest->scenes);
    if (!dest->store || !dest->store->scenes || !dest->scenes) {
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        if (!dest->store) free(r);
    }
    if (s == LUCENT_OK && r->d.out) s = eval_make_dirs(r->d.out);
    lucent_gl_context *owned = NULL;
    r->gl = desc->gl;
    if (s == LUCENT_OK && !r->gl && (s = lucent_gl_create(NULL, &owned)) == LUCENT_OK) r->gl = owned;
    if (s == LUCENT_OK) {
        provenance(r);
        eval_warn_slow(r);
        s = compare_all(r, dest);
    }
    lucent_gl_destroy(owned);
    r->gl = NULL;
    if (s != LUCENT_OK) lucent_compare_result_free(dest);
    return s;
}

void lucent_compare_result_free(lucent_compare_result *result)
{
    if (!result) return;
    lucent_compare_store *st = result->store;
    for (int i = 0; st && st->scenes && i < st->count; i++) {
        scene_store *ss = &st->scenes[i];
        eval_reference_free(&ss->ref);
        free(ss->mask);
        free(ss->region_bits);
        lucent_trace_probe_free(&ss->probe);
        for (int k = 0; k < LUCENT_COMPARE_MAX_METHODS; k++) lucent_image_destroy(ss->images[k]);
        lucent_scene_destroy(ss->scene);
    }
    if (st) free(st->scenes), free(st->run);
    free(st);
    free(result->scenes);
    *result = (lucent_compare_result){0};
}
