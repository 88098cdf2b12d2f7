/* kernel-eval's reports: the kernel slices (Freude Figure 6.2), the tables (6.3-6.5) and
 * results.json. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "lucent/eval.h"

/* ---- Kernel slices (Figure 6.2) ---- */

/* A(i, j) of channel c, per mm^2. */
static double model_at(const lucent_kernel *k, int c, int i, int j)
{
    int n = 2 * k->half + 1;
    double sum = 0;
    for (int r = 0; r < k->rank; r++) sum += k->sign[c][r] * k->a[c][r * n + i] * k->a[c][r * n + j];
    return sum / (k->h * k->h);
}

static bool drawn(const lucent_kernel_eval_model *e) { return e->plotted && e->kernel; }

lucent_status lucent_kernel_eval_write_slices(const char *path, const lucent_kernel_eval_result *res, bool diagonal)
{
    const lucent_kernel2d *gt = res->ground_truth;
    int n = 2 * gt->half + 1, curves = 1;
    for (int i = 0; i < res->model_count; i++) curves += drawn(&res->models[i]);
    double *buf = malloc((size_t)n * (size_t)(1 + 3 * curves) * sizeof *buf);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: slices");
    double *x = buf, scale = diagonal ? sqrt(2.0) : 1.0, reach = 0;
    for (int j = 0; j < n; j++) x[j] = (j - gt->half) * gt->h * scale;
    lucent_plot_series s[3][16];
    lucent_plot_panel panels[3];
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    static const char *const colors[] = {"#e67e22", "#2e64c8", "#27ae60", "#8e44ad", "#c0392b",
                                         "#8c564b", "#7f8c8d", "#d35400", "#2c3e50", "#f1c40f",
                                         "#1abc9c", "#e84393", "#6c5ce7", "#00b894", "#636e72"};
    for (int c = 0; c < 3; c++) {
        double *y = buf + n * (1 + (size_t)c * curves), peak = 0;
        for (int j = 0; j < n; j++) {
            y[j] = gt->value[c][(size_t)(diagonal ? j : gt->half) * n + j] / (gt->h * gt->h);
            peak = fmax(peak, y[j]);
        }
        for (int j = 0; j < n; j++)
            if (y[j] > 1e-2 * peak) reach = fmax(reach, fabs(x[j]));
        int m = 0;
        s[c][m++] = (lucent_plot_series){.label = "ground truth", .x = x, .y = y, .count = n, .color = "#000000"};
        for (int i = 0; i < res->model_count && m < 16; i++) {
            const lucent_kernel_eval_model *e = &res->models[i];
            if (!drawn(e)) continue;
            double *ym = buf + n * (1 + (size_t)c * curves + m);
            for (int j = 0; j < n; j++) ym[j] = model_at(e->kernel, c, diagonal ? j : gt->half, j);
            s[c][m] = (lucent_plot_series){
                .label = e->name, .x = x, .y = ym, .count = n, .color = colors[(m - 1) % 15], .dashed = true};
            m++;
        }
        panels[c] = (lucent_plot_panel){.title = titles[c],
                                        .x_label = diagonal ? "r along x = y (mm)" : "x (mm), y = 0",
                                        .y_label = c == 0 ? "kernel (1/mm^2)" : NULL,
                                        .series = s[c],
                                        .series_count = m,
                                        .y_min = 0,
                                        .y_max = 1.6 * peak};
    }
    if (reach <= 0) reach = gt->half * gt->h * scale;
    for (int c = 0; c < 3; c++) panels[c].x_min = -reach, panels[c].x_max = reach;
    char title[200];
    snprintf(title, sizeof title, "%s: kernel models against the ground truth, %s slice", res->material.name,
             diagonal ? "diagonal" : "axis (y = 0)");
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 3, .panel_width = 440};
    lucent_status st = lucent_plot_write_svg(path, &desc);
    free(buf);
    return st;
}

/* ---- Tables ---- */

static void md_row(lucent_strbuf *b, const char *name, const double v[3])
{
    lucent_strbuf_printf(b, "| %s | %.4g | %.4g | %.4g |\n", name, v[0], v[1], v[2]);
}

static double mean3(const double v[3]) { return (v[0] + v[1] + v[2]) / 3; }

static void table65(lucent_strbuf *b, const lucent_kernel_eval_result *res)
{
    lucent_strbuf_printf(b, "\n## SVD rank N against N Gaussians (Freude Table 6.5)\n\nImage-space RMS of the "
                            "separable convolutions (mean over R, G, B), kernel-space RMS in brackets.\n\n"
                            "| N | SVD | SoG | better |\n|---|---|---|---|\n");
    for (int n = 0; n < res->table65_count; n++) {
        const lucent_kernel_eval_model *a = &res->models[res->table65[n][0]], *g = &res->models[res->table65[n][1]];
        double ia = mean3(a->separable.rms), ig = mean3(g->separable.rms);
        double ka = mean3(a->kernel_rms), kg = mean3(g->kernel_rms);
        lucent_strbuf_printf(b, "| %d | %.4g (%.3g) | %.4g (%.3g) | %s |\n", n + 1, ia, ka, ig, kg,
                             ia < ig   ? "SVD"
                             : ia > ig ? "SoG"
                                       : "tie");
    }
}

static void image_space(lucent_strbuf *b, const lucent_kernel_eval_result *res)
{
    lucent_strbuf_printf(b, "\n## Image space (Freude Table 6.4)\n\nRMS (relative RMS) of the model's convolution "
                            "against the exact 2-D convolution.\n\n| model | R | G | B |\n|---|---|---|---|\n");
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < res->model_count; i++) {
            const lucent_kernel_eval_model *e = &res->models[i];
            if (!drawn(e) || (pass && !e->have_taps)) continue;
            const lucent_image_error_stats *st = pass ? &e->taps : &e->separable;
            lucent_strbuf_printf(b, "| %s%s |", e->name, pass ? ", taps" : ", separable");
            for (int c = 0; c < 3; c++) lucent_strbuf_printf(b, " %.4g (%.3g) |", st->rms[c], st->rel_rms[c]);
            lucent_strbuf_printf(b, "\n");
        }
}

lucent_status lucent_kernel_eval_write_tables(const char *path, const lucent_kernel_eval_result *res)
{
    lucent_strbuf b = {0};
    const lucent_kernel2d *gt = res->ground_truth;
    lucent_strbuf_printf(&b, "# %s: kernel models against the ground truth\n\n", res->material.name);
    lucent_strbuf_printf(&b,
                         "Profile %s; ground truth %d x %d cells of %.4g mm. Signal %s, %d x %d pixels at %.4g mm "
                         "per pixel (pixel kernel %d x %d), clamped borders.\n\n",
                         res->profile, 2 * gt->half + 1, 2 * gt->half + 1, gt->h, res->signal, res->signal_width,
                         res->signal_height, res->mm_per_pixel, res->kernel_pixels, res->kernel_pixels);
    lucent_strbuf_printf(&b, "## Kernel space (Freude Table 6.3)\n\nRMS of A - R_d over the grid cells (cell weights; "
                             "each channel sums to 1).\n\n| model | R | G | B |\n|---|---|---|---|\n");
    for (int i = 0; i < res->model_count; i++)
        if (drawn(&res->models[i])) md_row(&b, res->models[i].name, res->models[i].kernel_rms);
    image_space(&b, res);
    if (res->taps > 0) lucent_strbuf_printf(&b, "\nTaps: %d per pass.\n", res->taps);
    for (int i = 0; i < res->model_count; i++)
        if (res->models[i].skipped[0])
            lucent_strbuf_printf(&b, "\nSkipped %s: %s\n", res->models[i].name, res->models[i].skipped);
    if (res->table65_count > 0) table65(&b, res);
    char *text = NULL;
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

/* ---- JSON ---- */

static void json_stats(cJSON *j, const char *key, const lucent_image_error_stats *st)
{
    cJSON *o = cJSON_AddObjectToObject(j, key);
    lucent_json_add_numbers(o, "rms", st->rms, 3);
    lucent_json_add_numbers(o, "relative_rms", st->rel_rms, 3);
    lucent_json_add_numbers(o, "max_abs", st->max_abs, 3);
}

static void json_models(cJSON *root, const lucent_kernel_eval_result *res)
{
    cJSON *models = cJSON_AddArrayToObject(root, "models");
    for (int i = 0; i < res->model_count; i++) {
        const lucent_kernel_eval_model *e = &res->models[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddItemToArray(models, j);
        cJSON_AddStringToObject(j, "name", e->name);
        cJSON_AddStringToObject(j, "model", lucent_kernel_model_name(e->desc.model));
        cJSON_AddNumberToObject(j, "rank", e->desc.rank);
        if (!e->kernel) {
            cJSON_AddStringToObject(j, "skipped", e->skipped);
            continue;
        }
        lucent_json_add_numbers(j, "kernel_rms", e->kernel_rms, 3);
        json_stats(j, "separable", &e->separable);
        if (e->have_taps) json_stats(j, "taps", &e->taps);
    }
}

static void json_table65(cJSON *root, const lucent_kernel_eval_result *res)
{
    cJSON *t = cJSON_AddArrayToObject(root, "table65");
    for (int n = 0; n < res->table65_count; n++) {
        const lucent_kernel_eval_model *a = &res->models[res->table65[n][0]], *g = &res->models[res->table65[n][1]];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddItemToArray(t, j);
        cJSON_AddNumberToObject(j, "n", n + 1);
        lucent_json_add_numbers(j, "svd_kernel_rms", a->kernel_rms, 3);
        lucent_json_add_numbers(j, "sog_kernel_rms", g->kernel_rms, 3);
        lucent_json_add_numbers(j, "svd_image_rms", a->separable.rms, 3);
        lucent_json_add_numbers(j, "sog_image_rms", g->separable.rms, 3);
    }
}

lucent_status lucent_kernel_eval_write_json(const char *path, const lucent_kernel_eval_result *res)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    cJSON_AddStringToObject(root, "material", res->material.name);
    cJSON_AddStringToObject(root, "profile", res->profile);
    cJSON *gt = cJSON_AddObjectToObject(root, "ground_truth");
    cJSON_AddNumberToObject(gt, "cells", 2 * res->ground_truth->half + 1);
    cJSON_AddNumberToObject(gt, "cell_mm", res->ground_truth->h);
    cJSON *sig = cJSON_AddObjectToObject(root, "signal");
    cJSON_AddStringToObject(sig, "name", res->signal);
    cJSON_AddNumberToObject(sig, "width", res->signal_width);
    cJSON_AddNumberToObject(sig, "height", res->signal_height);
    cJSON_AddNumberToObject(sig, "mm_per_pixel", res->mm_per_pixel);
    cJSON_AddNumberToObject(sig, "kernel_pixels", res->kernel_pixels);
    cJSON_AddStringToObject(sig, "border", "clamp");
    cJSON_AddNumberToObject(root, "taps", res->taps);
    json_models(root, res);
    if (res->table65_count > 0) json_table65(root, res);
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}
