/* The chart of `lucent fit`: r R(r) of the truth and of each engine's fit (and hand mapping, dashed), one
 * panel per channel over the radii the fit counts. */
#include <stdio.h>
#include <stdlib.h>

#include "lucent/engine.h"
#include "lucent/eval.h"

enum { MAX_CURVES = 1 + 2 * LUCENT_ENGINE_COUNT };

/* r R(r) of channel c of p over its first n bins into dest. */
static void weighted(const lucent_profile *p, int c, int n, double *dest)
{
    for (int j = 0; j < n; j++) dest[j] = p->r[j] * p->value[c][j];
}

lucent_status lucent_engine_report_write_svg(const char *path, const lucent_engine_report *report)
{
    const lucent_engine_target *t = &report->target;
    int n = 0;
    for (int c = 0; c < 3; c++) n = t->bins[c] > n ? t->bins[c] : n;
    double *y = malloc((size_t)3 * MAX_CURVES * (size_t)n * sizeof *y);
    if (!y) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    char labels[MAX_CURVES][80];
    lucent_plot_series s[3][MAX_CURVES];
    lucent_plot_panel panels[3];
    for (int c = 0; c < 3; c++) {
        int k = 0;
        double *row = y + (size_t)c * MAX_CURVES * (size_t)n;
        weighted(t->profile, c, n, row);
        snprintf(labels[0], sizeof labels[0], "truth (Monte Carlo)");
        s[c][k++] = (lucent_plot_series){
            .label = c == 0 ? labels[0] : NULL, .x = t->profile->r, .y = row, .count = n, .color = "#000000"};
        for (int i = 0; i < report->count; i++)
            for (int h = 0; h < 2; h++) {
                const lucent_engine_fit_result *r = h ? &report->hand[i] : &report->fits[i];
                if (!r->profile || (h && !r->param_count)) continue;
                double *v = row + (size_t)k * (size_t)n;
                weighted(r->profile, c, n, v);
                snprintf(labels[k], sizeof labels[k], "%s%s", lucent_engine_name(r->engine), h ? " (hand)" : "");
                s[c][k] = (lucent_plot_series){
                    .label = c == 0 ? labels[k] : NULL, .x = t->profile->r, .y = v, .count = n, .dashed = h};
                k++;
            }
        panels[c] = (lucent_plot_panel){.title = titles[c],
                                        .x_label = "r (mm)",
                                        .y_label = c == 0 ? "r R(r) (1/mm)" : NULL,
                                        .x_max = t->r99[c],
                                        .x_min = 0,
                                        .series = s[c],
                                        .series_count = k};
    }
    char title[200];
    snprintf(title, sizeof title, "%s: r R(r), the truth and each engine's model (dashed: the hand mapping)",
             t->material.name);
    lucent_plot_desc desc = {
        .title = title, .panels = panels, .panel_count = 3, .panel_width = 460, .panel_height = 380};
    lucent_status st = lucent_plot_write_svg(path, &desc);
    free(y);
    return st;
}
