/* The outputs of a CDRF fit to Monte Carlo spheres: JSON, CSV and the SVG chart. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "lucent/eval.h"

#define PI 3.14159265358979323846
enum { CURVE_POINTS = 91 };

static const char *const k_channel[] = {"R", "G", "B"};
static const char *const k_palette[] = {"#c0392b", "#27ae60", "#2e64c8", "#8e44ad",
                                        "#d35400", "#16a085", "#7f8c8d", "#2c3e50"};

static cJSON *fit_json(const lucent_cdrf_fit *fit)
{
    cJSON *fj = cJSON_CreateObject();
    lucent_json_add_numbers(fj, "sigma0", fit->sigma0, 3);
    lucent_json_add_numbers(fj, "kd", fit->kd, 3);
    lucent_json_add_numbers(fj, "rms", fit->rms, 3);
    lucent_json_add_numbers(fj, "chi2", fit->chi2, 3);
    lucent_json_add_numbers(fj, "lambert_kd", fit->lambert_kd, 3);
    lucent_json_add_numbers(fj, "lambert_rms", fit->lambert_rms, 3);
    lucent_json_add_numbers(fj, "lambert_chi2", fit->lambert_chi2, 3);
    return fj;
}

static cJSON *sphere_json(const lucent_cdrf_sphere_result *sp)
{
    cJSON *s = cJSON_CreateObject();
    cJSON_AddNumberToObject(s, "radius", sp->radius);
    lucent_json_add_numbers(s, "entered", sp->entered, 3);
    lucent_json_add_numbers(s, "exited", sp->exited, 3);
    lucent_json_add_numbers(s, "absorbed", sp->absorbed, 3);
    lucent_json_add_numbers(s, "theta", sp->theta, sp->bins);
    for (int c = 0; c < 3; c++) {
        cJSON *ch = cJSON_AddObjectToObject(s, k_channel[c]);
        lucent_json_add_numbers(ch, "radiance", sp->radiance[c], sp->bins);
        lucent_json_add_numbers(ch, "error", sp->radiance_se[c], sp->bins);
    }
    return s;
}

lucent_status lucent_cdrf_fit_write_json(const char *path, const lucent_cdrf_fit_report *r)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    cJSON_AddStringToObject(root, "material", r->material->name);
    cJSON_AddStringToObject(root, "variant", lucent_cdrf_variant_name(r->fit->variant));
    cJSON_AddStringToObject(root, "model", "L(theta) = k_d f(theta; sigma0 / r), theta = angle(normal, light)");
    cJSON_AddStringToObject(root, "units", "r and sigma0 in mm, theta in radians, L per unit irradiance");
    cJSON_AddNumberToObject(root, "photons_per_channel", (double)r->spheres[0].photons);
    cJSON_AddNumberToObject(root, "seed", (double)r->seed);
    cJSON_AddNumberToObject(root, "cone_radians", r->cone);
    cJSON_AddNumberToObject(root, "roughness", r->roughness);
    cJSON_AddItemToObject(root, "fit", fit_json(r->fit));
    cJSON *arr = cJSON_AddArrayToObject(root, "spheres");
    for (int i = 0; arr && i < r->sphere_count; i++) cJSON_AddItemToArray(arr, sphere_json(&r->spheres[i]));
    lucent_status st = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return st;
}

lucent_status lucent_cdrf_fit_write_csv(const char *path, const lucent_cdrf_fit_report *r)
{
    const lucent_cdrf_fit *fit = r->fit;
    lucent_strbuf b = {0};
    char *text = NULL;
    lucent_strbuf_printf(&b,
                         "# lucent cdrf-fit: %s; L per unit irradiance, *_se standard errors, *_fit = k_d f(theta; "
                         "sigma0 / r) (%s)\n",
                         r->material->name, lucent_cdrf_variant_name(fit->variant));
    lucent_strbuf_printf(&b, "radius_mm,theta_deg,R,R_se,R_fit,G,G_se,G_fit,B,B_se,B_fit\n");
    for (int i = 0; i < r->sphere_count; i++) {
        const lucent_cdrf_sphere_result *sp = &r->spheres[i];
        for (int j = 0; j < sp->bins; j++) {
            lucent_strbuf_printf(&b, "%.9g,%.9g", sp->radius, sp->theta[j] * 180 / PI);
            for (int c = 0; c < 3; c++)
                lucent_strbuf_printf(&b, ",%.9g,%.9g,%.9g", sp->radiance[c][j], sp->radiance_se[c][j],
                                     fit->kd[c] *
                                         lucent_cdrf_eval(fit->variant, sp->theta[j], fit->sigma0[c] / sp->radius));
            lucent_strbuf_printf(&b, "\n");
        }
    }
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

/* The series of channel c: per sphere its data (markers, error bars) and its fitted curve (dashed). */
static void channel_series(const lucent_cdrf_fit_report *r, int c, double *deg, const double *cx, double *cy,
                           char (*labels)[48], lucent_plot_series *series)
{
    const lucent_cdrf_fit *fit = r->fit;
    int n = r->sphere_count;
    for (int i = 0; i < n; i++) {
        const lucent_cdrf_sphere_result *sp = &r->spheres[i];
        double *d = deg + i * LUCENT_CDRF_MAX_BINS, *y = cy + (c * n + i) * CURVE_POINTS;
        for (int j = 0; j < sp->bins; j++) d[j] = sp->theta[j] * 180 / PI;
        for (int k = 0; k < CURVE_POINTS; k++)
            y[k] = fit->kd[c] * lucent_cdrf_eval(fit->variant, cx[k] * PI / 180, fit->sigma0[c] / sp->radius);
        char *l1 = labels[(c * n + i) * 2], *l2 = labels[(c * n + i) * 2 + 1];
        snprintf(l1, 48, "r = %g mm (MC)", sp->radius);
        snprintf(l2, 48, "r = %g mm (fit)", sp->radius);
        const char *col = k_palette[i % 8];
        series[(c * n + i) * 2] = (lucent_plot_series){.label = l1,
                                                       .x = d,
                                                       .y = sp->radiance[c],
                                                       .err = sp->radiance_se[c],
                                                       .count = sp->bins,
                                                       .color = col,
                                                       .markers = true};
        series[(c * n + i) * 2 + 1] =
            (lucent_plot_series){.label = l2, .x = cx, .y = y, .count = CURVE_POINTS, .color = col, .dashed = true};
    }
}

lucent_status lucent_cdrf_fit_write_svg(const char *path, const lucent_cdrf_fit_report *r)
{
    int n = r->sphere_count;
    lucent_plot_series *series = calloc((size_t)(6 * n), sizeof *series);
    double *deg = calloc((size_t)(n * LUCENT_CDRF_MAX_BINS), sizeof *deg);
    double *cx = calloc(CURVE_POINTS, sizeof *cx), *cy = calloc((size_t)(3 * n * CURVE_POINTS), sizeof *cy);
    char(*labels)[48] = calloc((size_t)(6 * n), sizeof *labels);
    lucent_status s = LUCENT_OK;
    if (!series || !deg || !cx || !cy || !labels) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    lucent_plot_panel panels[3];
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    for (int k = 0; s == LUCENT_OK && k < CURVE_POINTS; k++) cx[k] = 180.0 * k / (CURVE_POINTS - 1);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        channel_series(r, c, deg, cx, cy, labels, series);
        panels[c] = (lucent_plot_panel){.title = titles[c],
                                        .x_label = "theta (degrees, normal to light)",
                                        .x_min = 0,
                                        .x_max = 180,
                                        .y_label = c == 0 ? "radiance toward the camera" : NULL,
                                        .series = series + c * 2 * n,
                                        .series_count = 2 * n};
    }
    const lucent_cdrf_fit *fit = r->fit;
    char title[200];
    snprintf(title, sizeof title, "%s: CDRF (%s) fitted to Monte Carlo spheres; sigma0 = %.3g, %.3g, %.3g mm",
             r->material->name, lucent_cdrf_variant_name(fit->variant), fit->sigma0[0], fit->sigma0[1], fit->sigma0[2]);
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 3, .panel_width = 440};
    if (s == LUCENT_OK) s = lucent_plot_write_svg(path, &desc);
    free(series), free(deg), free(cx), free(cy), free(labels);
    return s;
}
