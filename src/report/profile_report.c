/* The outputs of a diffuse reflectance profile: JSON, CSV and the SVG charts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "lucent/eval.h"

static const char *const k_channel[] = {"R", "G", "B"};
static const char *const k_channel_color[] = {"#c0392b", "#27ae60", "#2e64c8"};

/* ---- JSON ---- */

static void fill_material(cJSON *j, const lucent_material *m)
{
    if (!j) return;
    cJSON_AddStringToObject(j, "name", m->name);
    cJSON_AddStringToObject(j, "units", "mm^-1");
    lucent_json_add_numbers(j, "sigma_a", m->sigma_a, 3);
    lucent_json_add_numbers(j, "sigma_s", m->sigma_s, 3);
    lucent_json_add_numbers(j, "g", m->g, 3);
    cJSON_AddNumberToObject(j, "eta", m->eta);
}

static void add_material(cJSON *root, const lucent_material *m)
{
    fill_material(cJSON_AddObjectToObject(root, "material"), m);
}

/* "layers": [{"material": {...}, "thickness_mm": d or "inf"}, ...], top first. */
static void add_layers(cJSON *root, const lucent_layer *layers, int count)
{
    cJSON *a = cJSON_AddArrayToObject(root, "layers");
    for (int i = 0; a && i < count; i++) {
        cJSON *l = cJSON_CreateObject();
        if (!l || !cJSON_AddItemToArray(a, l)) {
            cJSON_Delete(l);
            return;
        }
        fill_material(cJSON_AddObjectToObject(l, "material"), &layers[i].material);
        double d = layers[i].slab.thickness;
        isinf(d) ? (void)cJSON_AddStringToObject(l, "thickness_mm", "inf")
                 : (void)lucent_json_add_number(l, "thickness_mm", d);
    }
}

static void add_sog(cJSON *root, const lucent_sog *sog)
{
    cJSON *j = cJSON_AddObjectToObject(root, "sum_of_gaussians");
    cJSON_AddStringToObject(j, "form", "R(r) = sum_i w_i exp(-r^2 / (2 v_i)) / (2 pi v_i), v in mm^2");
    cJSON_AddNumberToObject(j, "count", sog->count);
    for (int c = 0; c < 3; c++) {
        cJSON *ch = cJSON_AddObjectToObject(j, k_channel[c]);
        lucent_json_add_numbers(ch, "variance", sog->variance[c], sog->count);
        lucent_json_add_numbers(ch, "weight", sog->weight[c], sog->count);
        cJSON_AddNumberToObject(ch, "relative_rms", sog->rms[c]);
    }
}

lucent_status lucent_profile_write_json(const char *path, const lucent_profile_report *r)
{
    const lucent_profile *p = r->profile;
    cJSON *root = cJSON_CreateObject();
    if (!root) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    cJSON_AddStringToObject(root, "model", p->model);
    add_material(root, r->material);
    if (r->layers && r->layer_count > 0) add_layers(root, r->layers, r->layer_count);
    cJSON *units = cJSON_AddObjectToObject(root, "units");
    cJSON_AddStringToObject(units, "r", "mm");
    cJSON_AddStringToObject(units, "R_d", "mm^-2 (average over the bin's annulus)");
    cJSON_AddNumberToObject(root, "dr", p->dr);
    cJSON_AddNumberToObject(root, "bins", p->count);
    if (strcmp(p->model, "mc") == 0) {
        cJSON_AddNumberToObject(root, "photons_per_channel", (double)r->photons);
        cJSON_AddNumberToObject(root, "seed", (double)r->seed);
    }
    double total[3];
    for (int c = 0; c < 3; c++) total[c] = lucent_profile_total(p, c);
    lucent_json_add_numbers(root, "total_on_grid", total, 3);
    lucent_json_add_numbers(root, "r", p->r, p->count);
    for (int c = 0; c < 3; c++) {
        cJSON *ch = cJSON_AddObjectToObject(root, k_channel[c]);
        lucent_json_add_numbers(ch, "value", p->value[c], p->count);
        lucent_json_add_numbers(ch, "error", p->error[c], p->count);
    }
    if (r->sog) add_sog(root, r->sog);
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}

/* ---- CSV ---- */

lucent_status lucent_profile_write_csv(const char *path, const lucent_material *m, const lucent_profile *p)
{
    char *text;
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b, "# lucent profile: %s, model %s; r in mm, R_d in mm^-2, *_se: standard error\n", m->name,
                         p->model);
    lucent_strbuf_printf(&b, "r_mm,R,R_se,G,G_se,B,B_se\n");
    for (int j = 0; j < p->count; j++) {
        lucent_strbuf_printf(&b, "%.9g", p->r[j]);
        for (int c = 0; c < 3; c++) lucent_strbuf_printf(&b, ",%.9g,%.9g", p->value[c][j], p->error[c][j]);
        lucent_strbuf_printf(&b, "\n");
    }
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

/* ---- SVG ---- */

static bool has_error(const lucent_profile *p, int c)
{
    for (int j = 0; j < p->count; j++)
        if (p->error[c][j] > 0) return true;
    return false;
}

/* One model, RGB curves: linear near zero (the first 5% of the range), log over all of it. */
static lucent_status write_single(const char *path, const lucent_material *m, const lucent_profile *p,
                                  const lucent_profile *fit, int gaussians)
{
    lucent_plot_series s[6];
    int n = 0;
    char labels[3][64];
    for (int c = 0; c < 3; c++) {
        s[n++] = (lucent_plot_series){.label = k_channel[c],
                                      .x = p->r,
                                      .y = p->value[c],
                                      .err = has_error(p, c) ? p->error[c] : NULL,
                                      .count = p->count,
                                      .color = k_channel_color[c]};
        if (!fit) continue;
        snprintf(labels[c], sizeof labels[c], "%s: %d Gaussians", k_channel[c], gaussians);
        s[n++] = (lucent_plot_series){.label = labels[c],
                                      .x = fit->r,
                                      .y = fit->value[c],
                                      .count = fit->count,
                                      .color = k_channel_color[c],
                                      .dashed = true};
    }
    char title[160];
    snprintf(title, sizeof title, "%s: diffuse reflectance profile (%s)", m->name, p->model);
    lucent_plot_panel panels[2] = {
        {.title = "near zero (linear)",
         .x_label = "r (mm)",
         .y_label = "R_d(r) (1/mm^2)",
         .x_max = 0.05 * p->count * p->dr,
         .series = s,
         .series_count = n},
        {.title = "whole range (logarithmic)", .x_label = "r (mm)", .log_y = true, .series = s, .series_count = n}};
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 2};
    return lucent_plot_write_svg(path, &desc);
}

lucent_status lucent_profile_write_svg(const char *path, const lucent_material *m, const lucent_profile *p,
                                       const lucent_sog *sog)
{
    lucent_profile *fit = NULL;
    lucent_status s = LUCENT_OK;
    if (sog) s = lucent_profile_from_sog(sog, &(lucent_profile_grid){.dr = p->dr, .count = p->count}, &fit);
    if (s == LUCENT_OK) s = write_single(path, m, p, fit, sog ? sog->count : 0);
    lucent_profile_destroy(fit);
    return s;
}

lucent_status lucent_profile_write_compare_svg(const char *path, const lucent_material *m,
                                               const lucent_profile *const *profiles, int count)
{
    lucent_plot_series s[3][8];
    lucent_plot_panel panels[3];
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    int shown = count < 8 ? count : 8;
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < shown; i++) {
            const lucent_profile *p = profiles[i];
            s[c][i] = (lucent_plot_series){.label = p->model,
                                           .x = p->r,
                                           .y = p->value[c],
                                           .err = has_error(p, c) ? p->error[c] : NULL,
                                           .count = p->count,
                                           .dashed = i > 0};
        }
        panels[c] = (lucent_plot_panel){.title = titles[c],
                                        .x_label = "r (mm)",
                                        .log_y = true,
                                        .y_label = c == 0 ? "R_d(r) (1/mm^2)" : NULL,
                                        .series = s[c],
                                        .series_count = shown};
    }
    char title[160];
    snprintf(title, sizeof title, "%s: diffuse reflectance profiles", m->name);
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 3, .panel_width = 420};
    return lucent_plot_write_svg(path, &desc);
}
