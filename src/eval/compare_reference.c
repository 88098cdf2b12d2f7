/* compare's reference: traced as one run, or as two independent runs (seeds) sharing the budget
 * whose difference calibrates the paired test; written beside the report with what made it, and read
 * back by a later run (--reference DIR) once its scene and settings are found to match. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "eval/internal.h"
#include "lucent/scene.h"

/* ---- tracing ---- */

static lucent_status trace_run(const lucent_scene *scene, const eval_reference_desc *d, uint64_t seed, int spp,
                               double time_limit, const char *label, lucent_trace_result *dest)
{
    lucent_tracer *tr;
    lucent_status s = lucent_tracer_create(scene, NULL, &tr);
    if (s != LUCENT_OK) return s;
    s = lucent_tracer_render(
        tr,
        &(lucent_trace_desc){
            .spp = spp, .seed = seed, .pool = d->pool, .time_limit = time_limit > 0 ? time_limit : -1, .label = label},
        dest);
    lucent_tracer_destroy(tr);
    return s;
}

/* a and b weighted by their passes: the mean of all passes, and its variance. */
static lucent_status combine_image(const lucent_image *a, const lucent_image *b, double wa, double wb, bool variance,
                                   lucent_image **dest)
{
    lucent_status s = lucent_image_clone(a, dest);
    if (s != LUCENT_OK) return s;
    double t = wa + wb, ka = variance ? wa * wa / (t * t) : wa / t, kb = variance ? wb * wb / (t * t) : wb / t;
    for (size_t i = 0; i < (size_t)a->width * (size_t)a->height * (size_t)a->channels; i++)
        (*dest)->data[i] = (float)(ka * a->data[i] + kb * b->data[i]);
    return LUCENT_OK;
}

lucent_status eval_reference_combine(const lucent_trace_result *a, const lucent_trace_result *b,
                                     lucent_trace_result *dest)
{
    *dest = (lucent_trace_result){0};
    double wa = a->spp > 0 ? (double)a->spp : 1, wb = b->spp > 0 ? (double)b->spp : 1;
    lucent_status s = combine_image(a->image, b->image, wa, wb, false, &dest->image);
    if (s == LUCENT_OK) s = combine_image(a->variance, b->variance, wa, wb, true, &dest->variance);
    if (s == LUCENT_OK) s = combine_image(a->coverage, b->coverage, wa, wb, false, &dest->coverage);
    if (s != LUCENT_OK) {
        lucent_trace_result_free(dest);
        return s;
    }
    dest->spp = a->spp + b->spp, dest->samples = a->samples + b->samples, dest->seed = a->seed;
    dest->seconds = a->seconds + b->seconds;
    dest->samples_per_second = dest->seconds > 0 ? (double)dest->samples / dest->seconds : 0;
    dest->truncated = a->truncated + b->truncated, dest->escaped = a->escaped + b->escaped;
    dest->nonfinite = a->nonfinite + b->nonfinite;
    dest->cost = a->cost;
    dest->cost.photons += b->cost.photons, dest->cost.paths += b->cost.paths;
    return LUCENT_OK;
}

lucent_status eval_reference_trace(const lucent_scene *scene, const eval_reference_desc *d, eval_reference *dest)
{
    *dest = (eval_reference){0};
    int spp = d->spp > 0 ? d->spp : scene->render.trace.spp;
    double time = d->time_limit > 0 ? d->time_limit : scene->render.trace.time_limit;
    uint64_t seed = scene->render.trace.seed;
    char label[EVAL_NAME_SIZE + 40];
    if (d->runs == 1 || spp < 2) { /* one pass cannot be shared by two runs */
        dest->runs = 1;
        return trace_run(scene, d, seed, spp, time, d->label, &dest->result);
    }
    /* Two halves. The first tells whether light paths correlate pixels (photons): then the second is
     * a run of its own with another seed; else the first run goes on (its pixels are independent). */
    int first = (spp + 1) / 2;
    lucent_tracer *tr;
    lucent_status s = lucent_tracer_create(scene, NULL, &tr);
    if (s != LUCENT_OK) return s;
    snprintf(label, sizeof label, "%s, run 1 of 2", d->label);
    s = lucent_tracer_render(
        tr,
        &(lucent_trace_desc){
            .spp = first, .seed = seed, .pool = d->pool, .time_limit = time > 0 ? time / 2 : -1, .label = label},
        &dest->run[0]);
    if (s == LUCENT_OK && d->runs == 0 && dest->run[0].cost.photons == 0) {
        dest->runs = 1; /* one estimate, continued */
        lucent_trace_result_free(&dest->run[0]);
        s = lucent_tracer_render(tr,
                                 &(lucent_trace_desc){.spp = spp - first > 0 ? spp - first : 1,
                                                      .pool = d->pool,
                                                      .time_limit = time > 0 ? time / 2 : -1,
                                                      .label = d->label},
                                 &dest->result);
        lucent_tracer_destroy(tr);
        return s;
    }
    lucent_tracer_destroy(tr);
    dest->runs = 2;
    snprintf(label, sizeof label, "%s, run 2 of 2", d->label);
    if (s == LUCENT_OK)
        s = trace_run(scene, d, seed + 1, spp - first > 0 ? spp - first : 1, time > 0 ? time / 2 : 0, label,
                      &dest->run[1]);
    if (s == LUCENT_OK) s = eval_reference_combine(&dest->run[0], &dest->run[1], &dest->result);
    return s;
}

void eval_reference_free(eval_reference *r)
{
    lucent_trace_result_free(&r->result);
    lucent_trace_result_free(&r->run[0]);
    lucent_trace_result_free(&r->run[1]);
    *r = (eval_reference){0};
}

/* ---- what made a reference ---- */

/* The settings of a group that the tracer reads, except those that set the budget (spp, time_limit)
 * and the seed: the same scene traced longer or with another seed is the same reference. */
static bool identity_key(const char *group, const char *key)
{
    if (!strcmp(group, "trace")) return strcmp(key, "spp") && strcmp(key, "time_limit") && strcmp(key, "seed");
    if (!strcmp(group, "view")) return !strcmp(key, "width") || !strcmp(key, "height") || !strcmp(key, "background");
    return false;
}

lucent_status eval_reference_identity(const lucent_scene *scene, cJSON **dest)
{
    *dest = NULL;
    cJSON *id = NULL;
    lucent_status s = lucent_json_parse_text(scene->json, scene->path, &id);
    if (s != LUCENT_OK) return s;
    cJSON_DeleteItemFromObjectCaseSensitive(id, "name");
    cJSON_DeleteItemFromObjectCaseSensitive(id, "description");
    cJSON_DeleteItemFromObjectCaseSensitive(id, "render");
    cJSON *render = cJSON_AddObjectToObject(id, "render");
    for (int g = 0; render && g < lucent_settings_group_count(); g++) {
        const lucent_settings_group *grp = lucent_settings_group_get(g);
        for (int k = 0; k < grp->count; k++) {
            if (!identity_key(grp->name, grp->settings[k].key)) continue;
            char text[256];
            lucent_setting_format(&scene->render, &grp->settings[k], text, sizeof text);
            cJSON_AddStringToObject(render, grp->settings[k].key, text);
        }
    }
    if (!render) {
        cJSON_Delete(id);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    *dest = id;
    return LUCENT_OK;
}

/* The path of the first place where a and b differ ("objects[0].material"), into path; false when
 * they are equal. */
static bool first_difference(const cJSON *a, const cJSON *b, char *path, size_t size)
{
    if (cJSON_Compare(a, b, true)) return false;
    size_t len = strlen(path);
    if (cJSON_IsObject(a) && cJSON_IsObject(b)) {
        const cJSON *x;
        cJSON_ArrayForEach(x, a)
        {
            const cJSON *y = cJSON_GetObjectItemCaseSensitive(b, x->string);
            snprintf(path + len, size - len, "%s%s", len ? "." : "", x->string);
            if (!y || first_difference(x, y, path, size)) return true;
        }
        cJSON_ArrayForEach(x, b) if (!cJSON_GetObjectItemCaseSensitive(a, x->string))
        {
            snprintf(path + len, size - len, "%s%s", len ? "." : "", x->string);
            return true;
        }
    } else if (cJSON_IsArray(a) && cJSON_IsArray(b) && cJSON_GetArraySize(a) == cJSON_GetArraySize(b)) {
        for (int i = 0; i < cJSON_GetArraySize(a); i++) {
            snprintf(path + len, size - len, "[%d]", i);
            if (first_difference(cJSON_GetArrayItem(a, i), cJSON_GetArrayItem(b, i), path, size)) return true;
        }
    }
    path[len] = '\0';
    if (!len) snprintf(path, size, "(the whole scene)");
    return true;
}

static void value_text(const cJSON *item, char *dest, size_t size)
{
    char *t = item ? cJSON_PrintUnformatted(item) : NULL;
    snprintf(dest, size, "%.120s", t ? t : "nothing");
    free(t);
}

/* The item at a path that first_difference made, or NULL. */
static const cJSON *at_path(const cJSON *root, const char *path)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", path);
    const cJSON *cur = root;
    for (char *p = buf; cur && *p;) {
        if (*p == '[') {
            cur = cJSON_GetArrayItem(cur, atoi(p + 1));
            char *close = strchr(p, ']');
            p = close ? close + 1 : p + strlen(p);
        } else {
            if (*p == '.') p++;
            size_t n = strcspn(p, ".[");
            char key[256];
            snprintf(key, sizeof key, "%.*s", (int)n, p);
            cur = cJSON_GetObjectItemCaseSensitive(cur, key);
            p += n;
        }
    }
    return cur;
}

/* ---- files ---- */

enum { RUN_FILES = 2 };
static const char *const k_run_stem[RUN_FILES] = {"reference-run1", "reference-run2"};

static lucent_status write_exr(const char *dir, const char *stem, const lucent_image *img, lucent_eval_event_fn fn,
                               void *user)
{
    char path[EVAL_PATH_SIZE];
    lucent_status s = eval_path_printf(path, sizeof path, "%s/%s.exr", dir, stem);
    if (s == LUCENT_OK) s = eval_wrote(fn, user, lucent_image_write(path, img, NULL), path);
    return s;
}

/* stem.exr (the image; the reference's own was written with its PNG), stem-variance.exr and
 * stem-coverage.exr. */
static lucent_status write_result(const char *dir, const char *stem, const lucent_trace_result *r, bool image,
                                  lucent_eval_event_fn fn, void *user)
{
    char name[EVAL_NAME_SIZE + 16];
    lucent_status s = image ? write_exr(dir, stem, r->image, fn, user) : LUCENT_OK;
    snprintf(name, sizeof name, "%s-variance", stem);
    if (s == LUCENT_OK) s = write_exr(dir, name, r->variance, fn, user);
    snprintf(name, sizeof name, "%s-coverage", stem);
    if (s == LUCENT_OK) s = write_exr(dir, name, r->coverage, fn, user);
    return s;
}

static cJSON *result_json(const lucent_trace_result *r)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "spp", (double)r->spp);
    cJSON_AddNumberToObject(j, "samples", (double)r->samples);
    cJSON_AddNumberToObject(j, "seed", (double)r->seed);
    cJSON_AddNumberToObject(j, "seconds", r->seconds);
    cJSON_AddNumberToObject(j, "photons", (double)r->cost.photons);
    return j;
}

lucent_status eval_reference_write(const char *dir, const lucent_scene *scene, const eval_reference *ref,
                                   lucent_eval_event_fn fn, void *user)
{
    lucent_status s = write_result(dir, "reference", &ref->result, false, fn, user);
    for (int k = 0; k < RUN_FILES && ref->runs == 2 && s == LUCENT_OK; k++)
        s = write_result(dir, k_run_stem[k], &ref->run[k], true, fn, user);
    cJSON *root = cJSON_CreateObject(), *id = NULL;
    if (s == LUCENT_OK) s = eval_reference_identity(scene, &id);
    if (s == LUCENT_OK && root) {
        cJSON_AddStringToObject(root, "what", "a path-traced reference of lucent compare (docs/compare.md)");
        cJSON_AddNumberToObject(root, "runs", ref->runs);
        cJSON_AddItemToObject(root, "result", result_json(&ref->result));
        cJSON *runs = cJSON_AddArrayToObject(root, "run_results");
        for (int k = 0; runs && ref->runs == 2 && k < 2; k++) cJSON_AddItemToArray(runs, result_json(&ref->run[k]));
        cJSON_AddItemToObject(root, "identity", id);
        id = NULL;
        char path[EVAL_PATH_SIZE];
        s = eval_path_printf(path, sizeof path, "%s/reference.json", dir);
        if (s == LUCENT_OK) s = eval_wrote(fn, user, lucent_json_write_file(path, root), path);
    } else if (s == LUCENT_OK) {
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    cJSON_Delete(id);
    cJSON_Delete(root);
    return s;
}

static lucent_status load_image(const char *dir, const char *stem, const char *suffix, int w, int h, int channels,
                                lucent_image **dest)
{
    char path[EVAL_PATH_SIZE];
    lucent_status s = eval_path_printf(path, sizeof path, "%s/%s%s.exr", dir, stem, suffix);
    if (s == LUCENT_OK) s = lucent_image_load(path, dest);
    if (s != LUCENT_OK) return s;
    if ((*dest)->width != w || (*dest)->height != h || (*dest)->channels < channels)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: %dx%d with %d channels, the reference.json says %dx%d (at least %d channels)", path,
                            (*dest)->width, (*dest)->height, (*dest)->channels, w, h, channels);
    if (channels == 1 && (*dest)->channels != 1) {
        lucent_image *c;
        s = lucent_image_convert_channels(*dest, 1, &c);
        lucent_image_destroy(*dest);
        *dest = s == LUCENT_OK ? c : NULL;
    }
    return s;
}

/* The numbers of one run's result (no images). */
static lucent_status read_numbers(const lucent_json_node *n, lucent_trace_result *dest)
{
    double spp, samples, seed, seconds, photons;
    lucent_status s = lucent_json_number(n, "spp", &spp);
    if (s == LUCENT_OK) s = lucent_json_number(n, "samples", &samples);
    if (s == LUCENT_OK) s = lucent_json_number(n, "seed", &seed);
    if (s == LUCENT_OK) s = lucent_json_number(n, "seconds", &seconds);
    if (s == LUCENT_OK) s = lucent_json_number_or(n, "photons", 0, &photons);
    if (s != LUCENT_OK) return s;
    const struct {
        const char *key;
        double v, hi;
    } range[] = {{"spp", spp, 1e12},
                 {"samples", samples, 1e18},
                 {"seed", seed, 9007199254740992.0},
                 {"seconds", seconds, 1e12},
                 {"photons", photons, 1e19}};
    for (size_t k = 0; k < sizeof range / sizeof range[0]; k++)
        if (!(range[k].v >= 0 && range[k].v <= range[k].hi))
            return lucent_json_fail(n, range[k].key, LUCENT_ERR_INVALID_ARGUMENT, "expected 0 to %g, got %g",
                                    range[k].hi, range[k].v);
    dest->spp = (uint64_t)spp, dest->samples = (uint64_t)samples, dest->seed = (uint64_t)seed;
    dest->seconds = seconds, dest->cost.photons = (uint64_t)photons;
    dest->samples_per_second = seconds > 0 ? samples / seconds : 0;
    return LUCENT_OK;
}

static lucent_status read_images(const char *dir, const char *stem, int w, int h, lucent_trace_result *dest)
{
    lucent_status s = load_image(dir, stem, "", w, h, 3, &dest->image);
    if (s == LUCENT_OK) s = load_image(dir, stem, "-variance", w, h, 3, &dest->variance);
    if (s == LUCENT_OK) s = load_image(dir, stem, "-coverage", w, h, 1, &dest->coverage);
    return s;
}

/* A setting that the reference's identity does not name was added since it was made, which traced with
 * that setting's default: the scene's matches it when it holds the default (its key is dropped from
 * mine), and is named as the difference otherwise. */
static void drop_new_defaults(const cJSON *ref, cJSON *mine)
{
    const cJSON *rr = cJSON_GetObjectItemCaseSensitive(ref, "render");
    cJSON *mr = cJSON_GetObjectItemCaseSensitive(mine, "render");
    if (!cJSON_IsObject(rr) || !cJSON_IsObject(mr)) return;
    lucent_render_settings d = lucent_render_settings_defaults();
    for (int g = 0; g < lucent_settings_group_count(); g++) {
        const lucent_settings_group *grp = lucent_settings_group_get(g);
        for (int k = 0; k < grp->count; k++) {
            const char *key = grp->settings[k].key;
            if (!identity_key(grp->name, key) || cJSON_GetObjectItemCaseSensitive(rr, key)) continue;
            char text[256];
            lucent_setting_format(&d, &grp->settings[k], text, sizeof text);
            const cJSON *m = cJSON_GetObjectItemCaseSensitive(mr, key);
            if (cJSON_IsString(m) && strcmp(m->valuestring, text) == 0)
                cJSON_DeleteItemFromObjectCaseSensitive(mr, key);
        }
    }
}

/* Checks that the reference in dir was made of the same scene and settings as scene. */
static lucent_status check_identity(const lucent_json_node *root, const lucent_scene *scene, const char *file)
{
    lucent_json_node idn;
    lucent_status s = lucent_json_object(root, "identity", true, &idn);
    cJSON *mine = NULL;
    if (s == LUCENT_OK) s = eval_reference_identity(scene, &mine);
    if (s != LUCENT_OK) return s;
    drop_new_defaults(idn.json, mine);
    char path[512] = "";
    if (first_difference(idn.json, mine, path, sizeof path)) {
        char was[128], is[128];
        value_text(at_path(idn.json, path), was, sizeof was);
        value_text(at_path(mine, path), is, sizeof is);
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                         "%s: %s: the reference was made with %s, the scene %s has %s: a reference is reused only "
                         "for the same scene and settings (the budget and the seed may differ); trace it again "
                         "without --reference",
                         file, path, was, scene->path, is);
    }
    cJSON_Delete(mine);
    return s;
}

lucent_status eval_reference_parse(const char *text, const char *file, const lucent_scene *scene, eval_reference *dest)
{
    *dest = (eval_reference){0};
    cJSON *json = NULL;
    lucent_status s = lucent_json_parse_text(text, file, &json);
    if (s != LUCENT_OK) return s;
    lucent_json_node root = lucent_json_root(json, file, ""), res, runs, item;
    s = check_identity(&root, scene, file);
    double count = 0;
    if (s == LUCENT_OK) s = lucent_json_number(&root, "runs", &count);
    if (s == LUCENT_OK && count != 1 && count != 2)
        s = lucent_json_fail(&root, "runs", LUCENT_ERR_INVALID_ARGUMENT, "must be 1 or 2, got %g", count);
    if (s == LUCENT_OK) s = lucent_json_object(&root, "result", true, &res);
    if (s == LUCENT_OK) s = read_numbers(&res, &dest->result);
    dest->runs = s == LUCENT_OK ? (int)count : 0;
    int nruns = 0;
    if (s == LUCENT_OK && dest->runs == 2) s = lucent_json_array(&root, "run_results", true, &runs, &nruns);
    if (s == LUCENT_OK && dest->runs == 2 && nruns != 2)
        s = lucent_json_fail(&root, "run_results", LUCENT_ERR_INVALID_ARGUMENT, "expected 2 runs, got %d", nruns);
    for (int k = 0; k < RUN_FILES && s == LUCENT_OK && dest->runs == 2; k++) {
        s = lucent_json_element(&runs, k, &item);
        if (s == LUCENT_OK) s = read_numbers(&item, &dest->run[k]);
    }
    cJSON_Delete(json);
    return s;
}

lucent_status eval_reference_read(const char *dir, const lucent_scene *scene, eval_reference *dest)
{
    *dest = (eval_reference){0};
    char file[EVAL_PATH_SIZE];
    lucent_status s = eval_path_printf(file, sizeof file, "%s/reference.json", dir);
    char *text = NULL;
    size_t size = 0;
    if (s == LUCENT_OK) s = lucent_read_file(file, &text, &size);
    if (s == LUCENT_OK) s = eval_reference_parse(text, file, scene, dest);
    free(text);
    int w = scene->render.view.width, h = scene->render.view.height;
    if (s == LUCENT_OK) s = read_images(dir, "reference", w, h, &dest->result);
    for (int k = 0; k < RUN_FILES && s == LUCENT_OK && dest->runs == 2; k++)
        s = read_images(dir, k_run_stem[k], w, h, &dest->run[k]);
    if (s != LUCENT_OK) eval_reference_free(dest);
    return s;
}
