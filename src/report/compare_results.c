/* compare's results.json, and every report of a compare run written into one folder. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/json.h"
#include "lucent/eval.h"

static cJSON *method_json(const lucent_compare_method *m, const lucent_frame_times *times, double noise, int rank,
                          double vs_lambert)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "method", m->name);
    cJSON_AddNumberToObject(j, "rel_rms", m->rel_rms);
    if (isfinite(noise))
        cJSON_AddNumberToObject(j, "rel_rms_net", lucent_compare_net_error(m->rel_rms, noise));
    else
        cJSON_AddNullToObject(j, "rel_rms_net");
    if (rank > 0)
        cJSON_AddNumberToObject(j, "rank", rank);
    else
        cJSON_AddNullToObject(j, "rank");
    if (isfinite(vs_lambert)) cJSON_AddNumberToObject(j, "frame_vs_lambert", vs_lambert);
    lucent_json_add_numbers(j, "rel_rms_rgb", m->rel_rms_rgb, 3);
    cJSON_AddNumberToObject(j, "frame_ms", m->frame_ms);
    cJSON_AddNumberToObject(j, "setup_ms", m->setup_ms);
    cJSON_AddStringToObject(j, "settings", m->settings);
    cJSON *passes = cJSON_AddObjectToObject(j, "passes_ms");
    for (int p = 0; passes && p < times->pass_count; p++)
        cJSON_AddNumberToObject(passes, times->pass_name[p], times->pass_ms[p]);
    return j;
}

static cJSON *scene_json(const lucent_compare_scene_result *sr)
{
    const lucent_compare_scene *r = &sr->report;
    cJSON *sc = cJSON_CreateObject(), *methods;
    cJSON_AddStringToObject(sc, "name", r->name);
    cJSON_AddNumberToObject(sc, "width", r->width), cJSON_AddNumberToObject(sc, "height", r->height);
    cJSON_AddNumberToObject(sc, "reference_spp", r->reference_spp);
    cJSON_AddNumberToObject(sc, "reference_seconds", r->reference_seconds);
    bool known = lucent_compare_noise_known(r);
    if (known)
        cJSON_AddNumberToObject(sc, "reference_noise", r->reference_noise);
    else
        cJSON_AddNullToObject(sc, "reference_noise"); /* unknown: fewer than LUCENT_COMPARE_MIN_SPP */
    cJSON_AddBoolToObject(sc, "ranked", known);
    int order[LUCENT_COMPARE_MAX_METHODS], rank[LUCENT_COMPARE_MAX_METHODS];
    int n = r->method_count < LUCENT_COMPARE_MAX_METHODS ? r->method_count : LUCENT_COMPARE_MAX_METHODS;
    lucent_compare_scene clipped = *r;
    clipped.method_count = n;
    lucent_compare_rank(&clipped, order, rank);
    int l = lucent_compare_lambert_index(r);
    cJSON_AddNumberToObject(sc, "object_pixels", (double)sr->object_pixels);
    cJSON_AddStringToObject(sc, "device", r->device);
    cJSON_AddItemToObject(sc, "scene", cJSON_Parse(r->scene_json));
    methods = cJSON_AddArrayToObject(sc, "methods");
    for (int k = 0; methods && k < n; k++) {
        double q = l >= 0 && r->methods[l].frame_ms > 0 ? r->methods[k].frame_ms / r->methods[l].frame_ms : NAN;
        cJSON_AddItemToArray(methods,
                             method_json(&r->methods[k], &sr->times[k], known ? r->reference_noise : NAN, rank[k], q));
    }
    cJSON *skipped = cJSON_AddArrayToObject(sc, "skipped");
    for (int k = 0; skipped && k < r->skipped_count; k++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "method", r->skipped[k].method);
        cJSON_AddStringToObject(o, "reason", r->skipped[k].reason);
        cJSON_AddItemToArray(skipped, o);
    }
    return sc;
}

lucent_status lucent_compare_write_results_json(const char *path, const lucent_compare_result *result)
{
    cJSON *root = cJSON_CreateObject(), *scenes = cJSON_AddArrayToObject(root, "scenes");
    for (int i = 0; scenes && i < result->scene_count; i++)
        cJSON_AddItemToArray(scenes, scene_json(&result->scenes[i]));
    lucent_status s =
        root && scenes ? lucent_json_write_file(path, root) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    cJSON_Delete(root);
    return s;
}

/* Writes one of the four reports to DIR/NAME. */
static lucent_status write_one(const char *dir, const char *name, int which, const char *title,
                               const lucent_compare_result *result, const lucent_compare_scene *scenes,
                               lucent_eval_event_fn on_event, void *user)
{
    char path[1200];
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= sizeof path)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%.60s...: path too long", dir);
    int count = result->scene_count;
    lucent_status s = which == 0   ? lucent_compare_write_html(path, title, scenes, count)
                      : which == 1 ? lucent_compare_write_markdown(path, scenes, count)
                      : which == 2 ? lucent_compare_write_csv(path, scenes, count)
                                   : lucent_compare_write_results_json(path, result);
    if (s == LUCENT_OK && on_event) on_event(&(lucent_eval_event){.kind = LUCENT_EVAL_WROTE, .path = path}, user);
    return s;
}

lucent_status lucent_compare_write_reports(const char *dir, const char *title, const lucent_compare_result *result,
                                           lucent_eval_event_fn on_event, void *user)
{
    static const char *const names[] = {"report.html", "report.md", "report.csv", "results.json"};
    int count = result->scene_count;
    lucent_compare_scene *scenes = calloc((size_t)(count > 0 ? count : 1), sizeof *scenes);
    if (!scenes) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < count; i++) scenes[i] = result->scenes[i].report;
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < 4 && s == LUCENT_OK; k++)
        s = write_one(dir, names[k], k, title ? title : LUCENT_COMPARE_DEFAULT_TITLE, result, scenes, on_event, user);
    free(scenes);
    return s;
}
