/* Lucent scenes: a camera, lights, objects (a mesh, where it stands, what it is made of) and the
 * render settings, read from one JSON file that the OpenGL renderer and the path tracer share.
 * The format is described in docs/scenes.md.
 *
 * Units: the world is in millimetres. Each object's mesh is scaled by its mm_per_unit and then
 * placed by its transform when the scene is loaded, so every mesh of a loaded scene is in world
 * millimetres, and curvatures computed on it are in mm^-1. Angles in files are in degrees.
 *
 * Image convention (both renderers): pixel (x, y) has x from the left, y from the TOP row, and its
 * centre at (x + 0.5, y + 0.5). */
#ifndef LUCENT_SCENE_H
#define LUCENT_SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/cdrf.h"
#include "lucent/image.h"
#include "lucent/kernel.h"
#include "lucent/material.h"
#include "lucent/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { LUCENT_SCENE_NAME_SIZE = 64, LUCENT_SCENE_PATH_SIZE = 1024 };

/* ---- Camera ------------------------------------------------------------------------------ */

typedef struct lucent_camera {
    double position[3]; /* mm */
    double target[3];   /* mm, the point looked at */
    double up[3];       /* default (0, 1, 0) */
    double fov_y;       /* vertical field of view, degrees, in (0, 180); default 30 */
    double near_plane;  /* mm; 0: fitted to the scene's bounds */
    double far_plane;   /* mm; 0: fitted to the scene's bounds */
} lucent_camera;

/* Column-major 4x4 view matrix (world mm to eye space, looking down -z), as OpenGL takes it. */
void lucent_camera_view(const lucent_camera *cam, double dest[16]);

/* Column-major 4x4 perspective projection for width / height = aspect (OpenGL clip space,
 * z in [-1, 1]); uses the camera's near and far planes, which must be resolved (> 0). */
void lucent_camera_projection(const lucent_camera *cam, double aspect, double dest[16]);

/* The primary ray through image point (px, py) of a width x height image (see the image convention
 * above; (x + 0.5, y + 0.5) is the centre of pixel (x, y)): origin is the camera position, dir is
 * unit. The same projection as lucent_camera_projection, so both renderers see the same image. */
void lucent_camera_ray(const lucent_camera *cam, int width, int height, double px, double py,
                       double origin[3], double dir[3]);

/* ---- Lights -------------------------------------------------------------------------------- */

typedef enum lucent_light_type {
    LUCENT_LIGHT_DIRECTIONAL = 0, /* the sun: parallel light, optionally a disc of angular radius */
    LUCENT_LIGHT_POINT,           /* an isotropic point */
    LUCENT_LIGHT_SPHERE,          /* an isotropic emitting sphere of radius > 0 */
    LUCENT_LIGHT_ENVIRONMENT      /* uniform radiance from every direction */
} lucent_light_type;

/* A light. The emitted quantity is color x intensity per channel:
 *   directional: irradiance on a surface facing the light (radiance x solid angle of the disc);
 *   point, sphere: radiant intensity (per steradian); irradiance at distance d (mm) is I / d^2;
 *   environment: radiance. */
typedef struct lucent_light {
    lucent_light_type type;
    double color[3];       /* linear RGB, default (1, 1, 1) */
    double intensity;      /* default 1 */
    double direction[3];   /* directional: unit direction the light travels (from the light) */
    double position[3];    /* point, sphere: mm */
    double radius;         /* sphere: mm, > 0 */
    double angular_radius; /* directional: radians of the sun's disc (0: a delta light) */
    bool shadows;          /* cast shadows in the GL renderer (default true); the tracer always does */
} lucent_light;

/* Returns the light's name in files ("directional", "point", "sphere", "environment"). */
const char *lucent_light_type_name(lucent_light_type type);

/* ---- Objects ------------------------------------------------------------------------------- */

typedef enum lucent_albedo_source {
    LUCENT_ALBEDO_FROM_MATERIAL = 0, /* the material's total diffuse reflectance (dipole Rd) */
    LUCENT_ALBEDO_COLOR,             /* the "albedo" colour of the object */
    LUCENT_ALBEDO_TEXTURE            /* the "albedo_texture" image (linear RGB once read) */
} lucent_albedo_source;

typedef struct lucent_scene_object {
    char name[LUCENT_SCENE_NAME_SIZE];
    char mesh_source[LUCENT_SCENE_PATH_SIZE]; /* the resolved file, or "primitive:<kind>" */
    lucent_mesh *mesh;                        /* in world mm (scaled and transformed when loaded) */
    double mm_per_unit;                       /* as in the file (default 1) */
    double to_world[16];                      /* column-major: mesh units to world mm (scale included) */
    lucent_material material;                 /* the medium inside the mesh */
    lucent_albedo_source albedo_source;
    double albedo[3];       /* the diffuse colour in use: the material's Rd or the file's colour */
    lucent_image *albedo_texture; /* LUCENT_ALBEDO_TEXTURE: linear RGB; else NULL */
    double *texcoords;      /* with a texture: 2 per vertex (u, v in [0, 1]), a latitude-longitude
                               projection about the mesh's bounding-box centre in mesh units
                               (scanned meshes carry no UVs); else NULL */
    double roughness;       /* specular roughness (microfacet alpha) of the boundary, default 0.3 */
    double specular_f0;     /* normal-incidence Fresnel reflectance, default ((eta-1)/(eta+1))^2 */
    bool sigma0_set;        /* the file gives sigma0 (CDRF) explicitly */
    double sigma0[3];       /* mm; meaningful when sigma0_set */
    double sss_strength;    /* ssss: this object's share of the blur, [0, 1], default 1 (per pixel) */
    bool visible;           /* default true */
} lucent_scene_object;

/* ---- Render settings -------------------------------------------------------------------------- */

typedef enum lucent_render_method {
    LUCENT_METHOD_LAMBERT = 0,       /* Lambert diffuse + a specular lobe */
    LUCENT_METHOD_CDRF,              /* Kubo's curvature-dependent reflectance */
    LUCENT_METHOD_CDRF_TRANSLUCENCY, /* the CDRF with depth-based transmission (the blog) */
    LUCENT_METHOD_SSSS,              /* screen-space separable subsurface scattering */
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

typedef struct lucent_render_settings {
    int width, height;                /* pixels; default 512 x 512 */
    lucent_render_method method;      /* default ssss */
    /* ssss */
    lucent_kernel_model kernel_model; /* default preint */
    int kernel_rank;                  /* default 1 */
    int taps;                         /* per 1-D pass, odd; default 17 */
    char profile[32];                 /* the profile kernels are built from, default "dipole" */
    double strength;                  /* blend of blurred and unblurred diffuse, [0, 1], times each
                                         object's sss_strength; default 1 */
    double width_scale;               /* an artist's multiplier on the physical kernel width; default 1 */
    lucent_depth_filter depth_filter; /* default follow */
    bool translucency;                /* light through thin parts (shadow-map thickness); default true */
    lucent_transmittance_model transmittance; /* how much passes a thickness; default slab */
    double translucency_curvature;    /* cdrf+translucency: the transmitted light times
                                         1 + this x sigma0 x curvature (the CDRF blog); default 1 */
    /* cdrf */
    lucent_cdrf_variant cdrf_variant; /* default kubo */
    bool cdrf_lut;                    /* true (default): the LUT texture; false: the closed form */
    lucent_sigma0_source sigma0_source;
    int curvature_smooth;             /* n-ring smoothing of the per-vertex curvature; default 1 */
    /* shared */
    int shadow_map_size;              /* default 2048 */
    double background[3];             /* linear RGB, default black (an environment light shows through) */
    lucent_tonemap_op tonemap;        /* for PNG output; default filmic */
    double exposure;                  /* stops; default 0 */
    /* path tracer */
    int spp;                          /* samples per pixel; default 64 */
    uint64_t seed;                    /* default 1 */
    int max_bounces;                  /* surface events per path; default 64 */
    int max_scatter;                  /* volume scattering events per path; default 100000 */
    double time_limit;                /* seconds, 0: none (stops at spp) */
} lucent_render_settings;

/* Returns the defaults stated above. */
lucent_render_settings lucent_render_settings_defaults(void);

/* Returns the method's name: "lambert", "cdrf", "cdrf+translucency", "ssss". */
const char *lucent_render_method_name(lucent_render_method method);

/* The names the scene file uses: "follow", "gaussian", "none"; "slab", "profile"; "fit", "diffuse"
 * ("unknown" out of range). */
const char *lucent_depth_filter_name(lucent_depth_filter filter);
const char *lucent_transmittance_name(lucent_transmittance_model model);
const char *lucent_sigma0_source_name(lucent_sigma0_source source);

/* Parses a method: one of the names above, or "ssss:<kernel model>" (e.g. "ssss:svd3" for rank 3,
 * "ssss:preint"), which also sets *model and *rank when they are not NULL. Fails with
 * LUCENT_ERR_INVALID_ARGUMENT listing the methods and models. */
lucent_status lucent_render_method_parse(const char *text, lucent_render_method *method,
                                         lucent_kernel_model *model, int *rank);

/* ---- The scene --------------------------------------------------------------------------------- */

typedef struct lucent_scene {
    char path[LUCENT_SCENE_PATH_SIZE]; /* the file it came from ("" from memory) */
    char name[LUCENT_SCENE_NAME_SIZE];
    char description[512];
    lucent_camera camera; /* near and far resolved */
    int light_count;
    lucent_light *lights;
    int object_count;
    lucent_scene_object *objects;
    lucent_render_settings render;
    char *json; /* the scene after overrides, as JSON text: what made an image */
} lucent_scene;

/* How to load a scene; a zero field means the default. */
typedef struct lucent_scene_load_desc {
    /* "key=value" overrides applied to the JSON before it is read: key is a path such as
     * "render.method", "camera.fov_y", "objects[0].material", "lights[1].intensity"; value is JSON
     * when it parses as JSON (numbers, arrays, true), else a string. */
    const char *const *overrides;
    int override_count;
    bool skip_meshes; /* read and check everything but do not load meshes (mesh is NULL) */
} lucent_scene_load_desc;

/* Loads a scene file. Relative mesh and texture paths are relative to the scene file's folder.
 * Errors name the file and the JSON path: "dragon.json: objects[0].material: unknown material
 * \"marbel\" ...", "dragon.json: objects[0].mesh: cannot open ../meshes/x.ply: No such file".
 * Free with lucent_scene_destroy. */
lucent_status lucent_scene_load(const char *path, const lucent_scene_load_desc *desc, lucent_scene **dest);

/* The same from JSON text; name stands for the file in messages, base_dir resolves relative paths
 * (NULL: the current directory). */
lucent_status lucent_scene_parse(const char *text, const char *name, const char *base_dir,
                                 const lucent_scene_load_desc *desc, lucent_scene **dest);

void lucent_scene_destroy(lucent_scene *scene);

/* World-space bounds of the visible objects' meshes (min > max when there are none). */
void lucent_scene_bounds(const lucent_scene *scene, double min[3], double max[3]);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SCENE_H */
