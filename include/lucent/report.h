/* Lucent reports: SVG charts (line plots on linear or logarithmic axes, several panels side
 * by side, as in the thesis's profile figures). Text output is plain SVG 1.1, no scripts. */
#ifndef LUCENT_REPORT_H
#define LUCENT_REPORT_H

#include <stdbool.h>
#include <stdint.h>

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
    bool markers;                    /* draw a marker at every point (a circle unless marker says) */
    int marker;                      /* 0: circle; 1 square, 2 triangle, 3 diamond, 4 inverted
                                        triangle, 5 cross, 6 plus, 7 star (lucent_plot_marker_count) */
    const char *const *point_labels; /* NULL, or count texts written beside the points (NULL: none); each
                                        is placed where it overlaps no other label, marker or the
                                        legend when such a place lies within 3 label heights */
} lucent_plot_series;

/* How many marker shapes lucent_plot_series.marker names; the palette has 12 distinct colours, so
 * series s drawn with colour s % 12 and marker s % 8 differ from every other of the first 24. */
int lucent_plot_marker_count(void);

/* One panel (a pair of axes). Zero fields mean "the default". */
typedef struct lucent_plot_panel {
    const char *title;
    const char *x_label;
    const char *y_label;
    bool log_y;          /* logarithmic y axis (points with y <= 0 are skipped) */
    bool log_x;          /* logarithmic x axis (points with x <= 0 are skipped) */
    double x_min, x_max; /* both 0: fit the data */
    double y_min, y_max; /* both 0: fit the data (points outside [x_min, x_max] do not count) */
    const lucent_plot_series *series;
    int series_count;
    bool legend_outside;     /* the legend right of the axes, which give it room (else inside, in a
                                corner clear of the data where one is) */
    double band_y0, band_y1; /* a shaded horizontal band between these y (both 0: none) */
    const char *band_label;  /* its legend text */
} lucent_plot_panel;

/* A figure: panels side by side. */
typedef struct lucent_plot_desc {
    const char *title; /* above all panels (NULL: none) */
    int panel_width;   /* pixels per panel (0: 480) */
    int panel_height;  /* pixels (0: 360) */
    const lucent_plot_panel *panels;
    int panel_count;
} lucent_plot_desc;

/* The size the plots give a text of n characters at their font (12 px sans-serif): a width of about
 * 7 px per character and a height of 14 px, used to keep labels and the legend apart. */
void lucent_plot_text_box(int n, double *width, double *height);

/* Renders the figure as SVG text; free *dest with free(). The legend sits in the corner of the panel
 * where it covers no data point (the one covering fewest when every corner has some). */
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
    const char *error_image; /* signed map of the per-pixel relative error against the reference */
    double rel_rms;          /* relative RMS error over the object's pixels, pooled over R, G, B */
    double rel_rms_rgb[3];   /* per channel */
    double frame_ms;         /* GPU time of one frame (timer queries) */
    double setup_ms;         /* CPU preparation: kernels, LUTs, curvature, sigma0 (once per scene) */
    const char *settings;    /* what distinguishes this method's run (free text) */
    const char *crop_image;  /* NULL, or zoomed crops of the worst region: reference, method, error */
    int crop[3];             /* the worst region: x, y of its top-left pixel and its size */
    bool has_flip;           /* flip holds the method's mean FLIP against the reference */
    double flip;             /* mean LDR-FLIP of the tonemapped images over the object's pixels
                                (lucent_image_flip; Andersson et al. 2020): 0 identical, 1 the largest */
    const char *kind;        /* NULL: a real-time method of Lucent's GL renderer; else what made the
                                image ("external": an image another renderer made, e.g. an engine peer) */
    bool has_worst;          /* worst_share holds how concentrated the method's error is */
    double worst_share;      /* the share of its squared error in the worst 1% of the object's pixels
                                (lucent_compare_concentration, LUCENT_COMPARE_WORST_FRACTION) */
} lucent_compare_method;

/* One region of the image (the lit side, the terminator, ...; lucent_compare_region_name) with
 * every method's error there. Arrays hold one value per method, in the scene's method order. */
typedef struct lucent_compare_region {
    const char *name;          /* "lit", "terminator", "attached shadow", "cast shadow", "grazing view",
                                  "convex", "silhouette band" */
    uint64_t pixels;           /* of the object mask in the region (regions overlap) */
    double energy;             /* the region's share of the reference's sum of squares over the mask */
    double reference_noise;    /* the reference's own relative standard error over the region */
    const double *rel_rms;     /* per method: relative RMS error over the region */
    const double *ratio;       /* per method: sum m / sum r over the region (1: as bright as the reference) */
    const double *error_share; /* per method: the region's share of its squared error over the mask */
} lucent_compare_region;

/* Each light alone on both sides (rendering is linear in the lights): the reference and every
 * method with only this light on. Arrays hold one value per method, in the scene's method order. */
typedef struct lucent_compare_light {
    const char *name; /* "lights[0] (directional)" */
    int reference_spp;
    double reference_noise;
    const double *rel_rms;                /* per method, over the object mask */
    const double *ratio;                  /* per method: sum m / sum r */
    const lucent_compare_region *regions; /* the regions as this light alone makes them */
    int region_count;
} lucent_compare_light;

/* Where and how a run was made: what a result needs to be cited and reproduced. */
typedef struct lucent_compare_provenance {
    const char *version;  /* Lucent's (LUCENT_VERSION_STRING) */
    const char *revision; /* the git revision the program was built from ("unknown": none given) */
    const char *command;  /* the command line ("": none given) */
    const char *date;     /* when the run began, ISO 8601 UTC */
    const char *machine;  /* the system and processor: "Linux 6.1 x86_64, AMD EPYC 7B13" */
    int cores;            /* online processors */
    const char *renderer; /* the GL renderer of the real-time methods */
} lucent_compare_provenance;

typedef struct lucent_compare_skipped {
    const char *method; /* a method asked for that could not render the scene */
    const char *reason; /* why, naming the object and the material */
} lucent_compare_skipped;

typedef struct lucent_compare_scene {
    const char *name;
    const char *description;
    int width, height;
    const char *reference_image; /* the path tracer's tonemapped PNG */
    int reference_spp;
    double reference_seconds;
    double reference_noise;        /* the reference's own relative standard error over the object:
                                    differences below it are noise, not method error; NaN when
                                    unknown (fewer than LUCENT_COMPARE_MIN_SPP samples per pixel) */
    const char *error_scale_image; /* NULL, or the colour bar of the error maps */
    double error_scale;            /* the relative error drawn in full colour (0: 0.5) */
    const char *device;            /* the GL renderer that ran the methods */
    const char *chart;             /* an SVG of error against frame time (NULL: none) */
    const char *scene_json;        /* the scene after overrides: what made the images */
    const lucent_compare_method *methods;
    int method_count;
    const lucent_compare_skipped *skipped; /* methods left out of this scene, with why */
    int skipped_count;
    /* The paired test (lucent_compare_paired): method_count x method_count standard errors of
     * e_i^2 - e_j^2 (squared relative RMS errors, row i, column j), NULL when not measured: then methods
     * rank by the older rule (net errors within the reference's noise of each other tie). */
    const double *pair_se;
    double se_inflation;                  /* the factor two independent reference runs found the per-pixel variances to
                              understate the paired test's variance by (applied when > 1; 0: not measured) */
    int reference_runs;                   /* independent runs (seeds) combined into the reference (0 or 1: one) */
    const char *reference_from;           /* NULL, or the folder a reused reference came from (--reference) */
    const lucent_compare_region *regions; /* per region (NULL: none) */
    int region_count;
    const lucent_compare_light *lights; /* each light alone (NULL: not measured) */
    int light_count;
    const lucent_compare_provenance *provenance; /* the run's (NULL: none) */
} lucent_compare_scene;

/* How many standard errors of the paired test separate two methods (|z| >= 3): below, the reference
 * cannot tell them apart and they share a rank. */
#define LUCENT_COMPARE_Z 3.0

/* The fewest samples per pixel from which the reference's noise is estimated: the variance of a
 * pixel's mean comes from its samples' spread, and with fewer than 8 samples that estimate is itself
 * off by a factor (its relative spread is sqrt(2 / (n - 1)) for Gaussian samples, 53% at n = 8 and
 * undefined at n = 1; path-traced radiance is far from Gaussian, so worse). Below it the noise is
 * unknown, and with it every net error and every ranking. */
enum { LUCENT_COMPARE_MIN_SPP = 8 };

/* Whether a scene's reference noise is known: reference_spp >= LUCENT_COMPARE_MIN_SPP and a finite
 * reference_noise. Without it no method is ranked, tied or marked best. */
bool lucent_compare_noise_known(const lucent_compare_scene *scene);

/* Ranks the methods by their error (non-finite errors last): order[k] receives the index of the
 * k-th, rank[i] the 1-based rank of method i, where a method that the paired test does not separate
 * from the first of the group above it (|z| < LUCENT_COMPARE_Z, with pair_se) shares that group's
 * rank (a tie: the reference cannot tell them apart). Without pair_se the older rule holds: a net
 * error (lucent_compare_net_error) within the reference noise of the group's first ties. Returns
 * false, and leaves order in the given order and every rank 0, when the noise is unknown (no
 * ranking can be claimed). */
bool lucent_compare_rank(const lucent_compare_scene *scene, int *order, int *rank);

/* The z of the paired test between methods i and j of a ranked scene: (e_i^2 - e_j^2) / pair_se
 * (NaN without pair_se; 0 for equal errors with a zero standard error, +-inf for different ones). */
double lucent_compare_pair_z(const lucent_compare_scene *scene, int i, int j);

/* The index of the method named "lambert" (-1: none), whose frame time the others are given against. */
int lucent_compare_lambert_index(const lucent_compare_scene *scene);

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

/* Draws the net error against frame time, a colour and marker of its own and a label per method,
 * over the band of the reference's noise (the raw error when the noise is unknown), as SVG. */
lucent_status lucent_compare_write_chart(const char *path, const lucent_compare_scene *scene);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_REPORT_H */
