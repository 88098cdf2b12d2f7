/* Internal helpers of the scene module (vectors: base/vec3.h). */
#ifndef LUCENT_SCENE_INTERNAL_H
#define LUCENT_SCENE_INTERNAL_H

#include <math.h>

#include "base/json.h"
#include "base/vec3.h"
#include "lucent/scene.h"
#include "mesh/gltf.h"

/* The glTF documents opened while one scene loads, by resolved path: a glTF scene's own (gltf.c), and
 * those whose meshes objects name ({"gltf": FILE, "mesh": M, "primitive": P}), each opened once. */
typedef struct scene_gltf_cache {
    int count;
    char **paths;
    gltf_doc **docs;
} scene_gltf_cache;

/* The document at path, opened (and kept) when not yet there. */
lucent_status scene_gltf_get(scene_gltf_cache *cache, const char *path, gltf_doc **dest);

/* Keeps doc under path (the cache owns it from now on, also when this fails). */
lucent_status scene_gltf_put(scene_gltf_cache *cache, const char *path, gltf_doc *doc);

void scene_gltf_cache_free(scene_gltf_cache *cache);

/* The Lucent scene document a glTF describes (docs/scenes.md#gltf-scenes); objects name file_ref as
 * their "gltf". */
lucent_status scene_gltf_document(gltf_doc *doc, const char *file_ref, cJSON **dest);

/* Applies "key=value" overrides to a parsed scene document; errors name the override. */
lucent_status scene_apply_overrides(cJSON *root, const char *file, const char *const *overrides, int count);

/* Reads the "render" object (absent: the defaults). */
lucent_status scene_read_render(const lucent_json_node *root, lucent_render_settings *dest);

/* Reads the "camera" object (required). */
lucent_status scene_read_camera(const lucent_json_node *root, lucent_camera *dest);

/* Reads the "lights" array (at least one light). Free *dest with free(). */
lucent_status scene_read_lights(const lucent_json_node *root, lucent_light **dest, int *count);

/* Reads object n: mesh (unless skip_meshes), transform, material, appearance; glTF meshes through
 * the cache. */
lucent_status scene_read_object(const lucent_json_node *n, const char *base_dir, bool skip_meshes,
                                scene_gltf_cache *cache, lucent_scene_object *dest);

/* Frees what an object owns (mesh, texture, texcoords). */
void scene_object_free(lucent_scene_object *o);

/* Reads an optional 3-vector of finite numbers with a default. */
lucent_status scene_read_vec3(const lucent_json_node *n, const char *key, const double def[3], double dest[3]);

/* Reads an optional number with a default, checked to lie in [lo, hi]. */
lucent_status scene_read_range(const lucent_json_node *n, const char *key, double def, double lo, double hi,
                               double *dest);

/* Reads an optional integer with a default, checked to lie in [lo, hi]. */
lucent_status scene_read_int(const lucent_json_node *n, const char *key, int def, int lo, int hi, int *dest);

#endif
