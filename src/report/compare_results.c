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
    cJSON_AddStringToObject(j, "kind", m->kind ? m->kind : "gl");
    if (m->has_flip)
        cJSON_AddNumberToObject(j, "flip", m->flip);
    else
        cJSON_AddNullToObject(j, "flip");
    if (m->has_worst)
        cJSON_AddNumberToObject(j, "worst_share", m->worst_share);
    else
        cJSON_AddNullToObject(j, "worst_share");
    cJSON *passes = cJSON_AddObjectToObject(j, "passes_ms");
    for (int p = 0; passes && p < times->pass_count; p++)
        cJSON_AddNumberToObject(passes, times->pass_name[p], times->pass_ms[p]);
    return j;
}

/* A number, or null when it is not finite. */
static void add_number(cJSON *o, const char *key, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, key, v);
    else
        cJSON_AddNullToObject(o, key);
}

static void add_numbers(cJSON *o, const char *key, const double *v, int n)
{
    cJSON *a = cJSON_AddArrayToObject(o, key);
    for (int i = 0; a && i < n; i++)
        cJSON_AddItemToArray(a, isfinite(v[i]) ? cJSON_CreateNumber(v[i]) : cJSON_CreateNull());
}

static cJSON *regions_json(const lucent_compare_region *g, int count, int methods)
{
    cJSON *a = cJSON_CreateArray();
    for (int r = 0; a && r < count; r++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "region", g[r].name);
        cJSON_AddNumberToObject(o, "pixels", (double)g[r].pixels);
        add_number(o, "energy", g[r].energy);
        add_number(o, "reference_noise", g[r].reference_noise);
        add_numbers(o, "rel_rms", g[r].rel_rms, methods);
        add_numbers(o, "ratio", g[r].ratio, methods);
        add_numbers(o, "error_share", g[r].error_share, methods);
        cJSON_AddItemToArray(a, o);
    }
    return a;
}

/* The paired tests: per pair of methods (i < j) the difference of squared errors, its standard
 * error and z. */
static void pairs_json(cJSON *sc, const lucent_compare_scene *r, int n)
{
    cJSON *paired = cJSON_AddObjectToObject(sc, "paired_test");
    if (!paired) return;
    cJSON_AddNumberToObject(paired, "z_threshold", LUCENT_COMPARE_Z);
    cJSON_AddNumberToObject(paired, "reference_runs", r->reference_runs > 0 ? r->reference_runs : 1);
    if (r->se_inflation > 0)
        cJSON_AddNumberToObject(paired, "se_inflation", r->se_inflation);
    else
        cJSON_AddNullToObject(paired, "se_inflation");
    cJSON *pairs = cJSON_AddArrayToObject(paired, "pairs");
    for (int i = 0; pairs && r->pair_se && i < n; i++)
        for (int j = i + 1; j < n; j++) {
            cJSON *o = cJSON_CreateObject();
            double ei = r->methods[i].rel_rms, ej = r->methods[j].rel_rms;
            cJSON_AddStringToObject(o, "a", r->methods[i].name);
            cJSON_AddStringToObject(o, "b", r->methods[j].name);
            add_number(o, "d", ei * ei - ej * ej);
            add_number(o, "se", r->pair_se[(size_t)i * (size_t)r->method_count + (size_t)j]);
            double z = lucent_compare_pair_z(r, i, j);
            if (isinf(z))
                cJSON_AddStringToObject(o, "z", z > 0 ? "inf" : "-inf");
            else
                add_number(o, "z", z);
            cJSON_AddItemToArray(pairs, o);
        }
}

static cJSON *lights_json(const lucent_compare_scene *r, int methods)
{
    cJSON *a = cJSON_CreateArray();
    for (int l = 0; a && l < r->light_count; l++) {
        const lucent_compare_light *li = &r->lights[l];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "light", li->name);
        cJSON_AddNumberToObject(o, "reference_spp", li->reference_spp);
        add_number(o, "reference_noise", li->reference_noise);
        add_numbers(o, "rel_rms", li->rel_rms, methods);
        add_numbers(o, "ratio", li->ratio, methods);
        if (li->regions) cJSON_AddItemToObject(o, "regions", regions_json(li->regions, li->region_count, methods));
        cJSON_AddItemToArray(a, o);
    }
    return a;
}

static cJSON *provenance_json(const lucent_compare_provenance *p)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "lucent_version", p->version ? p->version : "unknown");
    cJSON_AddStringToObject(o, "revision", p->revision ? p->revision : "unknown");
    cJSON_AddStringToObject(o, "command", p->command ? p->command : "");
    cJSON_AddStringToObject(o, "date", p->date ? p->date : "unknown");
    cJSON_AddStringToObject(o, "machine", p->machine ? p->machine : "unknown");
    cJSON_AddNumberToObject(o, "cores", p->cores);
    cJSON_AddStringToObject(o, "gl_renderer", p->renderer ? p->renderer : "unknown");
    return o;
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
    if (n < r->method_count) clipped.pair_se = NULL; /* its rows are the whole scene's */
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
    pairs_json(sc, &clipped, n);
    if (r->reference_from) cJSON_AddStringToObject(sc, "reference_from", r->reference_from);
    if (r->regions) cJSON_AddItemToObject(sc, "regions", regions_json(r->regions, r->region_count, n));
    if (r->lights) cJSON_AddItemToObject(sc, "lights", lights_json(r, n));
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
    cJSON *root = cJSON_CreateObject();
    if (root && result->scene_count > 0 && result->scenes[0].report.provenance)
        cJSON_AddItemToObject(root, "provenance", provenance_json(result->scenes[0].report.provenance));
    cJSON *scenes = cJSON_AddArrayToObject(root, "scenes");
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
