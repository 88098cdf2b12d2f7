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
    const char *label; /* legend text (NULL: not in the legend) */
    const double *x;
    const double *y;
    const double *err; /* NULL: no band */
    int count;
    const char *color; /* any SVG colour ("#c0392b", "red"); NULL: from the palette */
    bool dashed;
    bool markers; /* draw a small circle at every point */
} lucent_plot_series;

/* One panel (a pair of axes). Zero fields mean "the default". */
typedef struct lucent_plot_panel {
    const char *title;
    const char *x_label;
    const char *y_label;
    bool log_y;          /* logarithmic y axis (points with y <= 0 are skipped) */
    double x_min, x_max; /* both 0: fit the data */
    double y_min, y_max; /* both 0: fit the data (points outside [x_min, x_max] do not count) */
    const lucent_plot_series *series;
    int series_count;
} lucent_plot_panel;

/* A figure: panels side by side. */
typedef struct lucent_plot_desc {
    const char *title; /* above all panels (NULL: none) */
    int panel_width;   /* pixels per panel (0: 480) */
    int panel_height;  /* pixels (0: 360) */
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

/* ---- The comparison report (lucent compare) ------------------------------------------------
 * Every real-time method of a scene beside the path-traced reference: images, error heat maps,
 * relative RMS errors over the object's pixels and frame times, as HTML (one page, every scene),
 * Markdown and CSV. Image paths are relative to the report. */
typedef struct lucent_compare_method {
    const char *name;        /* "lambert", "ssss:preint", ... */
    const char *image;       /* the method's tonemapped PNG */
    const char *error_image; /* heat map of the per-pixel relative error against the reference */
    double rel_rms;          /* relative RMS error over the object's pixels, pooled over R, G, B */
    double rel_rms_rgb[3];   /* per channel */
    double frame_ms;         /* GPU time of one frame (timer queries) */
    double setup_ms;         /* CPU preparation: kernels, LUTs, curvature, sigma0 (once per scene) */
    const char *settings;    /* what distinguishes this method's run (free text) */
} lucent_compare_method;

typedef struct lucent_compare_scene {
    const char *name;
    const char *description;
    int width, height;
    const char *reference_image; /* the path tracer's tonemapped PNG */
    int reference_spp;
    double reference_seconds;
    double reference_noise; /* the reference's own relative standard error over the object:
                                    differences below it are noise, not method error */
    const char *device;     /* the GL renderer that ran the methods */
    const char *chart;      /* an SVG of error against frame time (NULL: none) */
    const char *scene_json; /* the scene after overrides: what made the images */
    const lucent_compare_method *methods;
    int method_count;
} lucent_compare_scene;

/* A method's relative RMS error with the reference's own noise taken out: sqrt(max(e^2 - n^2, 0)).
 * The reference is the truth plus noise independent of the method, so E[e^2] = d^2 + n^2 with d the
 * method's distance from the truth and n the reference's relative standard error (both pooled over
 * the same pixels and channels, relative to the same sum of squares). */
double lucent_compare_net_error(double rel_rms, double reference_noise);

/* Writes the HTML report of count scenes to path (atomically); title heads the page. */
lucent_status lucent_compare_write_html(const char *path, const char *title, const lucent_compare_scene *scenes,
                                        int count);

/* Writes the tables as Markdown (one table per scene) to path. */
lucent_status lucent_compare_write_markdown(const char *path, const lucent_compare_scene *scenes, int count);

/* Writes one CSV row per scene and method: scene,method,rel_rms,rel_rms_r,rel_rms_g,rel_rms_b,
 * frame_ms,setup_ms,reference_spp,reference_noise,rel_rms_net (lucent_compare_net_error). */
lucent_status lucent_compare_write_csv(const char *path, const lucent_compare_scene *scenes, int count);

/* Draws error against frame time, one marker per method, and writes it as SVG to path. */
lucent_status lucent_compare_write_chart(const char *path, const lucent_compare_scene *scene);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_REPORT_H */
