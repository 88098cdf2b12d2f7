/* Writers for `lucent profile`: JSON, CSV and the SVG chart. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "cli.h"
#include "profile_out.h"

static const char *const k_channel[] = {"R", "G", "B"};
static const char *const k_channel_color[] = {"#c0392b", "#27ae60", "#2e64c8"};

static void path_for(const profile_out_desc *d, const lucent_profile *p, const char *ext, char *dest,
                     size_t size)
{
    int n = d->compare ? snprintf(dest, size, "%s-%s.%s", d->prefix, p->model, ext)
                       : snprintf(dest, size, "%s.%s", d->prefix, ext);
    if (n >= (int)size) dest[size - 1] = '\0';
}

static lucent_status wrote(lucent_status s, const char *path)
{
    if (s == LUCENT_OK) cli_info("wrote %s", path);
    return s;
}

/* ---- JSON ---- */

static void add_material(cJSON *root, const lucent_material *m)
{
    cJSON *j = cJSON_AddObjectToObject(root, "material");
    cJSON_AddStringToObject(j, "name", m->name);
    cJSON_AddStringToObject(j, "units", "mm^-1");
    lucent_json_add_numbers(j, "sigma_a", m->sigma_a, 3);
    lucent_json_add_numbers(j, "sigma_s", m->sigma_s, 3);
    lucent_json_add_numbers(j, "g", m->g, 3);
    cJSON_AddNumberToObject(j, "eta", m->eta);
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

static lucent_status write_json(const profile_out_desc *d, const lucent_profile *p,
                                const lucent_sog *sog)
{
    char path[600];
    path_for(d, p, "json", path, sizeof path);
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "model", p->model);
    add_material(root, d->material);
    cJSON *units = cJSON_AddObjectToObject(root, "units");
    cJSON_AddStringToObject(units, "r", "mm");
    cJSON_AddStringToObject(units, "R_d", "mm^-2 (average over the bin's annulus)");
    cJSON_AddNumberToObject(root, "dr", p->dr);
    cJSON_AddNumberToObject(root, "bins", p->count);
    if (strcmp(p->model, "mc") == 0) {
        cJSON_AddNumberToObject(root, "photons_per_channel", (double)d->photons);
        cJSON_AddNumberToObject(root, "seed", (double)d->seed);
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
    if (sog) add_sog(root, sog);
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return wrote(s, path);
}

/* ---- CSV ---- */

static lucent_status write_csv(const profile_out_desc *d, const lucent_profile *p)
{
    char path[600], *text;
    path_for(d, p, "csv", path, sizeof path);
    lucent_strbuf b = {0};
    lucent_strbuf_printf(&b, "# lucent profile: %s, model %s; r in mm, R_d in mm^-2, *_se: standard error\n",
                         d->material->name, p->model);
    lucent_strbuf_printf(&b, "r_mm,R,R_se,G,G_se,B,B_se\n");
    for (int j = 0; j < p->count; j++) {
        lucent_strbuf_printf(&b, "%.9g", p->r[j]);
        for (int c = 0; c < 3; c++) lucent_strbuf_printf(&b, ",%.9g,%.9g", p->value[c][j], p->error[c][j]);
        lucent_strbuf_printf(&b, "\n");
    }
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return wrote(s, path);
}

/* ---- SVG ---- */

static bool has_error(const lucent_profile *p, int c)
{
    for (int j = 0; j < p->count; j++)
        if (p->error[c][j] > 0) return true;
    return false;
}

/* One model, RGB curves: linear near zero (the first 5% of the range), log over all of it. */
static lucent_status write_svg_single(const profile_out_desc *d, const lucent_profile *p,
                                      const lucent_profile *fit)
{
    lucent_plot_series s[6];
    int n = 0;
    char labels[3][64];
    for (int c = 0; c < 3; c++) {
        s[n++] = (lucent_plot_series){.label = k_channel[c], .x = p->r, .y = p->value[c],
                                      .err = has_error(p, c) ? p->error[c] : NULL, .count = p->count,
                                      .color = k_channel_color[c]};
        if (!fit) continue;
        snprintf(labels[c], sizeof labels[c], "%s: %d Gaussians", k_channel[c], d->sog);
        s[n++] = (lucent_plot_series){.label = labels[c], .x = fit->r, .y = fit->value[c],
                                      .count = fit->count, .color = k_channel_color[c], .dashed = true};
    }
    char title[160];
    snprintf(title, sizeof title, "%s: diffuse reflectance profile (%s)", d->material->name, p->model);
    lucent_plot_panel panels[2] = {
        {.title = "near zero (linear)", .x_label = "r (mm)", .y_label = "R_d(r) (1/mm^2)",
         .x_max = 0.05 * p->count * p->dr, .series = s, .series_count = n},
        {.title = "whole range (logarithmic)", .x_label = "r (mm)", .log_y = true, .series = s,
         .series_count = n}};
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 2};
    char path[600];
    snprintf(path, sizeof path, "%s.svg", d->prefix);
    return wrote(lucent_plot_write_svg(path, &desc), path);
}

/* Several models: one log panel per channel, one curve per model. */
static lucent_status write_svg_compare(const profile_out_desc *d)
{
    lucent_plot_series s[3][8];
    lucent_plot_panel panels[3];
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < d->count && i < 8; i++) {
            const lucent_profile *p = d->profiles[i];
            s[c][i] = (lucent_plot_series){.label = p->model, .x = p->r, .y = p->value[c],
                                           .err = has_error(p, c) ? p->error[c] : NULL,
                                           .count = p->count, .dashed = i > 0};
        }
        panels[c] = (lucent_plot_panel){.title = titles[c], .x_label = "r (mm)", .log_y = true,
                                        .y_label = c == 0 ? "R_d(r) (1/mm^2)" : NULL, .series = s[c],
                                        .series_count = d->count < 8 ? d->count : 8};
    }
    char title[160], path[600];
    snprintf(title, sizeof title, "%s: diffuse reflectance profiles", d->material->name);
    snprintf(path, sizeof path, "%s.svg", d->prefix);
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 3, .panel_width = 420};
    return wrote(lucent_plot_write_svg(path, &desc), path);
}

/* Fits the sum of Gaussians to p and tabulates it on p's grid. */
static lucent_status fit_sog(const profile_out_desc *d, const lucent_profile *p, lucent_sog *sog,
                             lucent_profile **fit)
{
    lucent_sog_desc desc = {.count = d->sog};
    lucent_status s = lucent_sog_fit(p, &desc, sog);
    lucent_profile_grid g = {.dr = p->dr, .count = p->count};
    if (s == LUCENT_OK) s = lucent_profile_from_sog(sog, &g, fit);
    return s;
}

lucent_status profile_out_write(const profile_out_desc *d)
{
    lucent_status s = LUCENT_OK;
    lucent_sog sog;
    lucent_profile *fit = NULL;
    for (int i = 0; i < d->count && s == LUCENT_OK; i++) {
        bool with_sog = d->sog > 0 && (!d->compare || i == 0);
        if (with_sog) s = fit_sog(d, d->profiles[i], &sog, &fit);
        if (s == LUCENT_OK) s = write_json(d, d->profiles[i], with_sog ? &sog : NULL);
        if (s == LUCENT_OK) s = write_csv(d, d->profiles[i]);
        if (s == LUCENT_OK && !d->compare) s = write_svg_single(d, d->profiles[i], fit);
    }
    if (s == LUCENT_OK && d->compare) s = write_svg_compare(d);
    lucent_profile_destroy(fit);
    return s;
}
