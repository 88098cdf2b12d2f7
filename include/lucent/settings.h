/* Lucent render settings: what the GL renderer and the path tracer are asked to do, as one struct
 * nested by group, and the table that describes every setting once (its key in scene files, type,
 * default, range and a one-line doc). The table generates the defaults, the scene reader with its
 * range checks, the JSON sidecar, compare's method descriptions, the `--help` listings and the
 * viewer's panel; nothing else states a setting's name, default or range.
 *
 * Groups and the code that reads them:
 *   view          image size, method, shadow maps, background, tonemapping (src/scene, src/gl)
 *   ssss          the screen-space blur and its kernel (src/gl/methods/ssss.c)
 *   translucency  light through thin parts (src/gl/methods/translucency.c)
 *   cdrf          the curvature-dependent reflectance (src/gl/methods/cdrf.c)
 *   points        surfels, splatting and splat-based diffusion (src/gl/methods/points.c)
 *   tsd           texture-space diffusion (src/gl/methods/tsd.c)
 *   trace         the path tracer (src/trace/settings.c)
 * In scene files every setting is a member of the "render" object under its key ("render.taps");
 * keys are unique across groups. `lucent render --settings` lists the table. */
#ifndef LUCENT_SETTINGS_H
#define LUCENT_SETTINGS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- The vocabulary of the settings ---------------------------------------------------------- */

/* The GL renderer's methods (src/gl/methods/, one file each). */
typedef enum lucent_render_method {
    LUCENT_METHOD_LAMBERT = 0,       /* Lambert diffuse + a specular lobe */
    LUCENT_METHOD_CDRF,              /* Kubo's curvature-dependent reflectance */
    LUCENT_METHOD_CDRF_TRANSLUCENCY, /* the CDRF with depth-based transmission (the blog) */
    LUCENT_METHOD_SSSS,              /* screen-space separable subsurface scattering */
    LUCENT_METHOD_POINTS,            /* surfels: splatting and splat-based diffusion (Kim et al.) */
    LUCENT_METHOD_TSD,               /* texture-space diffusion (d'Eon, Luebke & Enderton 2007) */
    LUCENT_METHOD_BURLEY,            /* Burley's profile sampled on a disk as Unity HDRP samples it */
    LUCENT_METHOD_COUNT
} lucent_render_method;

typedef enum lucent_depth_filter {
    LUCENT_DEPTH_FOLLOW = 0, /* Jimenez's follow-surface lerp toward the centre sample */
    LUCENT_DEPTH_GAUSSIAN,   /* a Gaussian weight on the depth difference (as Blender's EEVEE) */
    LUCENT_DEPTH_NONE        /* no depth awareness */
} lucent_depth_filter;

typedef enum lucent_transmittance_model {
    LUCENT_TRANSMIT_SLAB = 0, /* Monte Carlo slab transmittance of the material (cached per material) */
    LUCENT_TRANSMIT_PROFILE   /* Jimenez 2010: the profile's power beyond the thickness, times the albedo */
} lucent_transmittance_model;

typedef enum lucent_sigma0_source {
    LUCENT_SIGMA0_FIT = 0, /* fitted to Monte Carlo spheres of the material (cached per material) */
    LUCENT_SIGMA0_DIFFUSE  /* sigma0 = d_c^2 from the diffuse colour (Kubo Eq. 6) */
} lucent_sigma0_source;

typedef enum lucent_points_style {
    LUCENT_POINTS_DIFFUSION = 0, /* Kim et al.: splat-based diffusion with a sum of Gaussians */
    LUCENT_POINTS_BRDF,          /* high-quality splatting (Botsch et al. 2005) with a BRDF, no diffusion */
    LUCENT_POINTS_DISKS          /* flat opaque disks, no blending (Kim et al.'s Figure 2, left) */
} lucent_points_style;

typedef enum lucent_sog_source {
    LUCENT_SOG_FIT = 0, /* Lucent's sum-of-Gaussians fit of the material's profile (lucent/bake.h) */
    LUCENT_SOG_DEON     /* d'Eon & Luebke 2007's six-Gaussian skin table */
} lucent_sog_source;

/* ---- The groups (defaults and ranges: the table, `lucent render --settings`, docs/scenes.md) -- */

typedef struct lucent_view_settings {
    int width, height;           /* pixels */
    lucent_render_method method; /* the GL renderer's method */
    int shadow_map_size;         /* texels per side of each light's shadow map */
    int samples;                 /* pixel samples: lucent_render's image is the mean of this many frames, the
                                    camera jittered over the pixel (as TAA accumulates); 1: the centre */
    int bounce;                  /* light between surfaces: surfels per side of each light's reflective
                                    shadow map (one bounce, docs/render.md); 0: none */
    double background[3];        /* linear RGB (an environment light shows through) */
    lucent_tonemap_op tonemap;   /* for PNG output */
    double exposure;             /* stops */
} lucent_view_settings;

typedef struct lucent_ssss_settings {
    int kernel;         /* a lucent_kernel_model (lucent/kernel.h) */
    int rank;           /* passes of the separable model (svd, sog) */
    int taps;           /* per 1-D pass, odd */
    char profile[32];   /* the profile the kernel is built from: dipole, better-dipole,
                                         burley, mc */
    double strength;    /* blend of blurred and unblurred diffuse, times each object's
                                         sss_strength */
    double width_scale; /* an artist's multiplier on the physical kernel width */
    lucent_depth_filter depth_filter;
} lucent_ssss_settings;

typedef struct lucent_translucency_settings {
    bool enabled;                             /* ssss: light through thin parts */
    lucent_transmittance_model transmittance; /* how much passes a thickness */
    double curvature;                         /* cdrf+translucency: transmitted light times
                                                 1 + this x sigma0 x curvature (the CDRF blog) */
    bool sheet; /* thin parts (with the slab model): the sheet tables behind the tracer's boundary, the
                   forward lobe and the diffuse rest (docs/render.md, "Thin parts"), in place of T(s) / pi */
} lucent_translucency_settings;

typedef struct lucent_cdrf_settings {
    int variant;                 /* a lucent_cdrf_variant (lucent/cdrf.h) */
    bool lut;                    /* the LUT texture (true) or the closed form */
    lucent_sigma0_source sigma0; /* where sigma0 comes from when an object does not give it */
    int curvature_smooth;        /* n-ring smoothing of the per-vertex curvature */
    bool tail;                   /* past the terminator, the material's profile (a sum of Gaussians)
                                    where it exceeds Kubo's one Gaussian of sigma0 */
    bool curved_parts;           /* cdrf and ssss: the factor of the material's Monte Carlo spheres (the
                                    spheres bake) in place of Kubo's CDRF or Lambert's max(n.l, 0) */
} lucent_cdrf_settings;

typedef struct lucent_points_settings {
    lucent_points_style style;
    double radius_scale;  /* times every surfel's radius */
    double depth_epsilon; /* visibility splats pushed back along the view ray, in splat radii */
    double cutoff;        /* a splat's radius in standard deviations of its Gaussian */
    int sog;              /* Gaussians of the fit */
    lucent_sog_source sog_source;
    double sog_cutoff;    /* a diffusion splat's support in standard deviations */
    double decimation;    /* spacing ratio of consecutive surfel levels */
    double level_spacing; /* a Gaussian is splatted from the coarsest level whose spacing is at most
                             this times its standard deviation */
    int neighbours;       /* k of the radii from the k nearest */
    double filter_px;     /* radius of the screen-space prefilter, pixels */
    int impulse;          /* >= 0: only that surfel of each object is lit (the impulse response) */
    bool weights;         /* debug: the image is the splats' summed Gaussian weight before normalisation */
} lucent_points_settings;
typedef struct lucent_tsd_settings {
    int size;      /* texels along a side of each object's texture */
    int gaussians; /* of the fitted sum of Gaussians */
    int taps;      /* per 1-D pass, odd */
    int sog;       /* 0 auto (d'Eon's table for skin, else the fit), 1 d'Eon's table, 2 the fit */
    bool seams;    /* the blur's taps follow texture seams into the chart across */
} lucent_tsd_settings;

typedef enum lucent_burley_source {
    LUCENT_BURLEY_PARAMS_FIT = 0, /* lucent fit's HDRP parameters (lucent/engine.h): T, and d fitted */
    LUCENT_BURLEY_PARAMS_HAND     /* the hand mapping: d = 1 / sigma_tr, colour T */
} lucent_burley_source;

typedef struct lucent_burley_settings {
    lucent_burley_source params; /* where each material's (A, d) come from */
    int samples;                 /* disk samples per pixel (HDRP's sample budget) */
} lucent_burley_settings;

typedef struct lucent_trace_settings {
    int spp; /* samples per pixel */
    uint64_t seed;
    int max_bounces;      /* surface events per path */
    int max_scatter;      /* volume scattering events per path */
    double time_limit;    /* seconds, 0: none (stops at spp) */
    int boundary_model;   /* a lucent_boundary_model (lucent/trace.h) */
    int light_paths;      /* a lucent_light_paths (lucent/trace.h) */
    double photons;       /* light paths per pixel and pass */
    bool interreflection; /* false: a path ends where it meets a surface from outside after its first
                             (no light between surfaces: what the real-time methods model) */
} lucent_trace_settings;

typedef struct lucent_render_settings {
    lucent_view_settings view;
    lucent_ssss_settings ssss;
    lucent_translucency_settings translucency;
    lucent_cdrf_settings cdrf;
    lucent_points_settings points;
    lucent_tsd_settings tsd;
    lucent_trace_settings trace;
    lucent_burley_settings burley;
} lucent_render_settings;

/* Returns every setting at its default. */
lucent_render_settings lucent_render_settings_defaults(void);

/* ---- The table ------------------------------------------------------------------------------ */

typedef enum lucent_setting_type {
    LUCENT_SETTING_BOOL = 0, /* bool */
    LUCENT_SETTING_INT,      /* int in [lo, hi] (optionally odd) */
    LUCENT_SETTING_REAL,     /* double in [lo, hi] */
    LUCENT_SETTING_COLOR,    /* double[3], each in [lo, hi]; one number in a file stands for all three */
    LUCENT_SETTING_CHOICE,   /* an enum stored as int: one of the names choice(0), choice(1), ... */
    LUCENT_SETTING_TEXT,     /* char[size]: one of choice's names when choice is set */
    LUCENT_SETTING_SEED      /* uint64_t in [lo, hi] (hi at most 2^53: exact in JSON numbers) */
} lucent_setting_type;

enum {
    LUCENT_SETTING_ODD = 1u << 0 /* INT: must be odd */
};

/* One setting: where it lives in lucent_render_settings and what values it takes. */
typedef struct lucent_setting {
    const char *key; /* in scene files, under "render" */
    lucent_setting_type type;
    size_t offset, size;  /* of the member in lucent_render_settings */
    double def, lo, hi;   /* numbers: default and inclusive range (COLOR: each channel) */
    const char *def_text; /* CHOICE, TEXT: the default's name */
    /* CHOICE, TEXT: the i-th name, NULL past the last. */
    const char *(*choice)(int index);
    /* Optional: reads text into the member (and related members, e.g. "ssss:svd3" sets the method,
     * the kernel and its rank); replaces the plain reader of the type. */
    lucent_status (*parse)(const char *text, lucent_render_settings *dest);
    unsigned flags;  /* LUCENT_SETTING_ODD */
    const char *doc; /* one line */
} lucent_setting;

typedef struct lucent_settings_group {
    const char *name; /* "ssss" */
    const char *doc;
    const lucent_setting *settings;
    int count;
} lucent_settings_group;

/* The groups, in the order they are read (a method given as "ssss:svd3" comes before "kernel"). */
int lucent_settings_group_count(void);
const lucent_settings_group *lucent_settings_group_get(int index);

/* Finds a setting by key ("taps"; "render.taps" also works); NULL when there is none. *group (may be
 * NULL) receives its group. */
const lucent_setting *lucent_setting_find(const char *key, const lucent_settings_group **group);

/* Sets one setting from text as a scene file or `--set` would give it ("17", "true", "follow",
 * "0.2,0.3,0.4" for a colour), checked against its range. Errors name the key. */
lucent_status lucent_setting_set(lucent_render_settings *s, const lucent_setting *setting, const char *text);

/* Writes the value of one setting as text (the form lucent_setting_set reads back). */
void lucent_setting_format(const lucent_render_settings *s, const lucent_setting *setting, char *dest, size_t size);

/* Checks every setting of s against the table; the message names the first bad one:
 * "render settings: taps: must be odd (a centre tap and pairs), got 16". */
lucent_status lucent_render_settings_check(const lucent_render_settings *s);

/* The settings of `group` as "key value, key value" text (compare's method descriptions); keys
 * listed in `skip` (NULL-terminated, may be NULL) are left out. */
void lucent_settings_describe(const lucent_render_settings *s, const char *group, const char *const *skip, char *dest,
                              size_t size);

/* A listing of every group and setting (key, default, range or names, doc) for `--help`;
 * markdown: a Markdown table per group instead of plain text. Free *dest with free(). */
lucent_status lucent_settings_help(bool markdown, char **dest);

/* Names of the enums above ("unknown" out of range). */
const char *lucent_render_method_name(lucent_render_method method);
const char *lucent_depth_filter_name(lucent_depth_filter filter);
const char *lucent_transmittance_name(lucent_transmittance_model model);
const char *lucent_sigma0_source_name(lucent_sigma0_source source);

/* The key of the index-th setting the method reads (its panel, its description); NULL past the last. */
const char *lucent_render_method_setting(lucent_render_method method, int index);

/* The settings that s->view.method reads, as "key value, key value" (compare's method column). */
void lucent_render_method_describe(const lucent_render_settings *s, char *dest, size_t size);

/* Parses a method: a name of lucent_render_method_name, or "<name>:<variant>" for methods that take
 * one (e.g. "ssss:svd3" for the svd kernel of rank 3, "ssss:preint"); the variant sets the method's
 * own settings in s (s may be NULL to check only). Fails with LUCENT_ERR_INVALID_ARGUMENT listing
 * the methods. */
lucent_status lucent_render_method_parse(const char *text, lucent_render_method *method, lucent_render_settings *s);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SETTINGS_H */
