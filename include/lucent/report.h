/* Lucent reports: SVG charts (line plots on linear or logarithmic axes, several panels side
 * by side, as in the thesis's profile figures). Text output is plain SVG 1.1, no scripts. */
#ifndef LUCENT_REPORT_H
#define LUCENT_REPORT_H

#include <stdbool.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One curve: count points (x[i], y[i]); optional symmetric errors err[i] drawn as a band. */
typedef struct lucent_plot_series {
    const char *label;  /* legend text (NULL: not in the legend) */
    const double *x;
    const double *y;
    const double *err;  /* NULL: no band */
    int count;
    const char *color;  /* any SVG colour ("#c0392b", "red"); NULL: from the palette */
    bool dashed;
    bool markers;       /* draw a small circle at every point */
} lucent_plot_series;

/* One panel (a pair of axes). Zero fields mean "the default". */
typedef struct lucent_plot_panel {
    const char *title;
    const char *x_label;
    const char *y_label;
    bool log_y;         /* logarithmic y axis (points with y <= 0 are skipped) */
    double x_min, x_max; /* both 0: fit the data */
    double y_min, y_max; /* both 0: fit the data (points outside [x_min, x_max] do not count) */
    const lucent_plot_series *series;
    int series_count;
} lucent_plot_panel;

/* A figure: panels side by side. */
typedef struct lucent_plot_desc {
    const char *title;   /* above all panels (NULL: none) */
    int panel_width;     /* pixels per panel (0: 480) */
    int panel_height;    /* pixels (0: 360) */
    const lucent_plot_panel *panels;
    int panel_count;
} lucent_plot_desc;

/* Renders the figure as SVG text; free *dest with free(). */
lucent_status lucent_plot_svg(const lucent_plot_desc *desc, char **dest);

/* Renders the figure and writes it to path atomically. */
lucent_status lucent_plot_write_svg(const char *path, const lucent_plot_desc *desc);

/* Fills ticks with "nice" linear tick positions (1, 2 or 5 times a power of ten) covering
 * [lo, hi]; returns how many (at most max_ticks). */
int lucent_plot_nice_ticks(double lo, double hi, int max_ticks, double *dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_REPORT_H */
