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
#include <stddef.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/image.h"
#include "lucent/material.h"
#include "lucent/mesh.h"
#include "lucent/settings.h"
#include "lucent/surfels.h"

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
void lucent_camera_ray(const lucent_camera *cam, int width, int height, double px, double py, double origin[3],
                       double dir[3]);

/* The inverse of lucent_camera_ray: the image point (px, py) where point (mm) appears, and the cosine
 * between the camera's axis and the direction to it. False when it is behind the camera or outside
 * the image. */
bool lucent_camera_project(const lucent_camera *cam, int width, int height, const double point[3], double *px,
                           double *py, double *cos_axis);

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
    LUCENT_ALBEDO_FROM_MATERIAL = 0, /* the material's total diffuse reflectance: albedo holds the dipole's
                                        closed form, the GL renderer shades with the Monte Carlo Rd
                                        (lucent/bake.h, LUCENT_BAKE_RD) */
    LUCENT_ALBEDO_COLOR,             /* the "albedo" colour of the object */
    LUCENT_ALBEDO_TEXTURE            /* the "albedo_texture" image (linear RGB once read) */
} lucent_albedo_source;

typedef struct lucent_scene_object {
    char name[LUCENT_SCENE_NAME_SIZE];
    char mesh_source[LUCENT_SCENE_PATH_SIZE]; /* the resolved file (mesh or point cloud), or "primitive:<kind>" */
    lucent_mesh *mesh;                        /* in world mm (scaled and transformed when loaded); for a
                                                 point cloud its points without faces */
    lucent_surfels *points;                   /* "points": the cloud's surfels (level 0 only, world mm),
                                                 lucent_surfels_load; NULL for a mesh */
    double mm_per_unit;                       /* as in the file (default 1) */
    double to_world[16];                      /* column-major: mesh units to world mm (scale included) */
    lucent_material material;                 /* the medium inside the mesh */
    lucent_albedo_source albedo_source;
    double albedo[3];             /* the diffuse colour in use: the material's Rd or the file's colour */
    lucent_image *albedo_texture; /* LUCENT_ALBEDO_TEXTURE: linear RGB; else NULL */
    double *texcoords;            /* with a texture: 2 per vertex (u, v in [0, 1]), a latitude-longitude
                               projection about the mesh's bounding-box centre in mesh units
                               (scanned meshes carry no UVs); else NULL */
    double roughness;             /* specular roughness (microfacet alpha) of the boundary, default 0.3 */
    double specular_f0;           /* normal-incidence Fresnel reflectance, default ((eta-1)/(eta+1))^2 */
    bool sigma0_set;              /* the file gives sigma0 (CDRF) explicitly */
    double sigma0[3];             /* mm; meaningful when sigma0_set */
    double sss_strength;          /* ssss: this object's share of the blur, [0, 1], default 1 (per pixel) */
    bool visible;                 /* default true */
    bool as_points;               /* the points method splats it as surfels (one per vertex,
                                     lucent/surfels.h); the other methods and the tracer see the mesh.
                                     Always true for a point cloud, which only the points method draws */
} lucent_scene_object;

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
    lucent_render_settings render; /* the "render" object (lucent/settings.h) */
    char *json;                    /* the scene after overrides, as JSON text: what made an image */
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

/* Loads a scene file: Lucent's JSON, or a glTF 2.0 asset (.gltf with external or data-URI buffers,
 * .glb), read as the Lucent scene it describes (docs/scenes.md#gltf-scenes: meshes with their node
 * transforms, the first perspective camera, KHR_lights_punctual, the materials' extensions or their
 * extras.lucent; overrides apply to that scene, and scene->json records it).
 * Relative mesh and texture paths are relative to the scene file's folder.
 * Errors name the file and the JSON path: "dragon.json: objects[0].material: unknown material
 * \"marbel\" ...", "dragon.json: objects[0].mesh: cannot open ../meshes/x.ply: No such file".
 * Free with lucent_scene_destroy. */
lucent_status lucent_scene_load(const char *path, const lucent_scene_load_desc *desc, lucent_scene **dest);

/* The same from JSON text; name stands for the file in messages, base_dir resolves relative paths
 * (NULL: the current directory). */
lucent_status lucent_scene_parse(const char *text, const char *name, const char *base_dir,
                                 const lucent_scene_load_desc *desc, lucent_scene **dest);

/* A glTF asset from memory (.gltf text or .glb bytes, copied); name stands for the file in messages
 * and in the objects' mesh references, base_dir resolves external buffers (NULL: they are refused
 * and the current directory stands for the folder). */
lucent_status lucent_scene_parse_gltf(const void *data, size_t size, const char *name, const char *base_dir,
                                      const lucent_scene_load_desc *desc, lucent_scene **dest);

void lucent_scene_destroy(lucent_scene *scene);

/* World-space bounds of the visible objects' meshes (min > max when there are none). */
void lucent_scene_bounds(const lucent_scene *scene, double min[3], double max[3]);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_SCENE_H */
