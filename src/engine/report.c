/* The report of one material's engine parameters: JSON and Markdown, as text and as files (written
 * atomically); glTF's material extensions are one of its engines (gltf_model.c), and the pack's README
 * carries the Markdown (pack_readme.c). */
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "engine/internal.h"

static const char k_error_text[] =
    "The fit matches the total diffuse reflectance T (the engine's albedo or colour) and minimises over R, G, B the "
    "sum of e_p^2, e_p the relative RMS of r R(r) against the truth over r <= r99 (99% of T); delta_e: CIEDE2000 of "
    "the model's T against the truth's (linear sRGB, white D65)";

/* ---- JSON ---- */

static void add_material(cJSON *o, const char *key, const lucent_material *m)
{
    cJSON *j = cJSON_AddObjectToObject(o, key);
    cJSON_AddStringToObject(j, "name", m->name);
    lucent_json_add_numbers(j, "sigma_a", m->sigma_a, 3);
    lucent_json_add_numbers(j, "sigma_s", m->sigma_s, 3);
    lucent_json_add_numbers(j, "g", m->g, 3);
    lucent_json_add_number(j, "eta", m->eta);
}

static void add_truth(cJSON *root, const lucent_engine_target *t)
{
    add_material(root, "material", &t->material);
    if (t->layer_count > 1) {
        cJSON *a = cJSON_AddArrayToObject(root, "layers");
        for (int i = 0; a && i < t->layer_count; i++) {
            cJSON *l = cJSON_CreateObject();
            if (!l) break;
            cJSON_AddItemToArray(a, l);
            cJSON_AddStringToObject(l, "material", t->layers[i].material.name);
            lucent_json_add_number(l, "thickness_mm", t->layers[i].slab.thickness);
        }
    }
    cJSON *j = cJSON_AddObjectToObject(root, "truth");
    cJSON_AddStringToObject(j, "profile", "Monte Carlo, a thin beam at normal incidence on a half-space");
    lucent_json_add_number(j, "photons_per_channel", (double)t->photons);
    lucent_json_add_number(j, "seed", (double)t->seed);
    lucent_json_add_number(j, "dr_mm", t->profile->dr);
    lucent_json_add_numbers(j, "total", t->rd, 3);
    lucent_json_add_numbers(j, "total_se", t->rd_se, 3);
    lucent_json_add_numbers(j, "r99_mm", t->r99, 3);
    lucent_json_add_numbers(j, "coverage", t->coverage, 3);
    lucent_json_add_numbers(j, "noise", t->noise, 3);
}

static void add_params(cJSON *o, const lucent_engine_fit_result *r)
{
    cJSON *a = cJSON_AddArrayToObject(o, "parameters");
    for (int i = 0; a && i < r->param_count; i++) {
        const lucent_engine_param *p = &r->params[i];
        cJSON *j = cJSON_CreateObject();
        if (!j) break;
        cJSON_AddItemToArray(a, j);
        cJSON_AddStringToObject(j, "name", p->name);
        if (p->count == 0)
            cJSON_AddStringToObject(j, "value", p->text);
        else if (p->count == 1)
            lucent_json_add_number(j, "value", p->value[0]);
        else
            lucent_json_add_numbers(j, "value", p->value, 3);
        cJSON_AddStringToObject(j, "unit", p->unit);
    }
}

static void add_errors(cJSON *o, const lucent_engine_fit_result *r)
{
    lucent_json_add_numbers(o, "profile_error", r->profile_error, 3);
    lucent_json_add_number(o, "profile_error_rms", r->profile_error_rms);
    lucent_json_add_numbers(o, "total", r->total, 3);
    lucent_json_add_number(o, "delta_e2000", r->delta_e);
    lucent_json_add_number(o, "transmittance_error", r->transmit_error);
    if (r->burley.valid) {
        cJSON *b = cJSON_AddObjectToObject(o, "burley");
        lucent_json_add_numbers(b, "albedo", r->burley.albedo, 3);
        lucent_json_add_numbers(b, "d_mm", r->burley.d, 3);
    }
}

static cJSON *report_json(const lucent_engine_report *rep)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return NULL;
    add_truth(root, &rep->target);
    cJSON_AddStringToObject(root, "errors", k_error_text);
    cJSON *list = cJSON_AddArrayToObject(root, "engines");
    for (int i = 0; list && i < rep->count; i++) {
        const lucent_engine_fit_result *r = &rep->fits[i];
        cJSON *e = cJSON_CreateObject();
        if (!e) break;
        cJSON_AddItemToArray(list, e);
        cJSON_AddStringToObject(e, "engine", lucent_engine_name(r->engine));
        cJSON_AddStringToObject(e, "title", lucent_engine_title(r->engine));
        add_params(e, r);
        add_errors(e, r);
        cJSON_AddStringToObject(e, "cannot_express", r->cannot);
        cJSON_AddStringToObject(e, "notes", r->notes);
        if (rep->hand[i].param_count) {
            cJSON *h = cJSON_AddObjectToObject(e, "hand_mapping");
            add_params(h, &rep->hand[i]);
            add_errors(h, &rep->hand[i]);
        }
    }
    return root;
}

lucent_status lucent_engine_report_json(const lucent_engine_report *report, char **dest)
{
    *dest = NULL;
    cJSON *root = report_json(report);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "engine report: out of memory");
    size_t n = strlen(text);
    *dest = malloc(n + 2);
    if (*dest) memcpy(*dest, text, n), (*dest)[n] = '\n', (*dest)[n + 1] = '\0';
    cJSON_free(text);
    return *dest ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "engine report: out of memory");
}

lucent_status lucent_engine_report_write_json(const char *path, const lucent_engine_report *report)
{
    cJSON *root = report_json(report);
    if (!root) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}

/* ---- Markdown ---- */

static void md_value(lucent_strbuf *b, const lucent_engine_param *p)
{
    if (p->count == 0)
        lucent_strbuf_printf(b, "%s", p->text);
    else if (p->count == 1)
        lucent_strbuf_printf(b, "%.4g", p->value[0]);
    else
        lucent_strbuf_printf(b, "(%.4g, %.4g, %.4g)", p->value[0], p->value[1], p->value[2]);
}

static void md_errors(lucent_strbuf *b, const char *what, const lucent_engine_fit_result *r)
{
    lucent_strbuf_printf(b, "| %s | %.1f%% | %.1f%%, %.1f%%, %.1f%% | %.2f |", what, 100 * r->profile_error_rms,
                         100 * r->profile_error[0], 100 * r->profile_error[1], 100 * r->profile_error[2], r->delta_e);
    if (isfinite(r->transmit_error))
        lucent_strbuf_printf(b, " %.1f%% |\n", 100 * r->transmit_error);
    else
        lucent_strbuf_printf(b, " - |\n");
}

static void md_engine(lucent_strbuf *b, const lucent_engine_report *rep, int i)
{
    const lucent_engine_fit_result *r = &rep->fits[i];
    lucent_strbuf_printf(b, "\n## %s (`%s`)\n\n| parameter | value | unit |\n|---|---|---|\n",
                         lucent_engine_title(r->engine), lucent_engine_name(r->engine));
    for (int k = 0; k < r->param_count; k++) {
        lucent_strbuf_printf(b, "| %s | ", r->params[k].name);
        md_value(b, &r->params[k]);
        lucent_strbuf_printf(b, " | %s |\n", r->params[k].unit);
    }
    lucent_strbuf_printf(b,
                         "\n| | e_p (RMS) | e_p (R, G, B) | delta E 2000 | transmittance |\n|---|---|---|---|---|\n");
    md_errors(b, "fitted", r);
    if (rep->hand[i].param_count) md_errors(b, "hand mapping", &rep->hand[i]);
    if (r->cannot[0]) lucent_strbuf_printf(b, "\nCannot express: %s.\n", r->cannot);
    if (r->notes[0]) lucent_strbuf_printf(b, "\nNotes: %s.\n", r->notes);
}

lucent_status lucent_engine_report_markdown(const lucent_engine_report *report, char **dest)
{
    const lucent_engine_target *t = &report->target;
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b, "# Engine parameters for %s\n\n", t->material.name);
    if (t->layer_count > 1) {
        lucent_strbuf_printf(&b, "Layers, top first:");
        for (int i = 0; i < t->layer_count; i++)
            lucent_strbuf_printf(&b, "%s %s %.4g mm", i ? "," : "", t->layers[i].material.name,
                                 t->layers[i].slab.thickness);
        lucent_strbuf_printf(&b, ".\n\n");
    }
    lucent_strbuf_printf(&b,
                         "The truth: Lucent's Monte Carlo, %llu photons per channel; total diffuse reflectance T = "
                         "(%.4f, %.4f, %.4f); r99 = (%.3g, %.3g, %.3g) mm; the profile's own noise (%.1f%%, %.1f%%, "
                         "%.1f%%).\n\n%s.\n",
                         (unsigned long long)t->photons, t->rd[0], t->rd[1], t->rd[2], t->r99[0], t->r99[1], t->r99[2],
                         100 * t->noise[0], 100 * t->noise[1], 100 * t->noise[2], k_error_text);
    for (int i = 0; i < report->count; i++) md_engine(&b, report, i);
    return lucent_strbuf_finish(&b, dest);
}

lucent_status lucent_engine_report_write_markdown(const char *path, const lucent_engine_report *report)
{
    char *text = NULL;
    lucent_status s = lucent_engine_report_markdown(report, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}
