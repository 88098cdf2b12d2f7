/* The pack's glTF (material.gltf): a small scene that other tools read as what it is, a mesh that uses
 * the material (lucent/gltf.h's mapping, Lucent's exact medium under extras.lucent), the pack's camera
 * (the screen's field of view and aspect, at the depth of the printed kernel width) and a directional
 * key light (KHR_lights_punctual), in metres. Lucent reads it back as a scene (docs/scenes.md). */
#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "engine/internal.h"
#include "material/gltf.h"
#include "mesh/gltf.h"

/* The key light travels along this direction (from the upper left, in front), as in
 * data/scenes/dragon-marble.json. */
static const double k_light_direction[3] = {0.55, -0.45, -0.7};
static const double k_light_lux = 3;

static bool add_node(cJSON *nodes, const char *name, cJSON **dest)
{
    cJSON *n = cJSON_CreateObject();
    if (!n || !cJSON_AddItemToArray(nodes, n)) return cJSON_Delete(n), false;
    *dest = n;
    return cJSON_AddStringToObject(n, "name", name) != NULL;
}

/* The unit quaternion (x, y, z, w) turning glTF's light direction -z into d. */
static void rotation_to(const double d[3], double q[4])
{
    v3 a = v3_make(0, 0, -1), b = v3_normalize(v3_load(d)), axis = v3_cross(a, b);
    double w = 1 + v3_dot(a, b), len = sqrt(v3_dot(axis, axis) + w * w);
    q[0] = axis.x / len, q[1] = axis.y / len, q[2] = axis.z / len, q[3] = w / len;
}

static bool add_camera(cJSON *root, cJSON *nodes, const pack_ctx *p)
{
    cJSON *cams = cJSON_AddArrayToObject(root, "cameras"), *c = cJSON_CreateObject(), *persp, *node;
    if (!c || !cams || !cJSON_AddItemToArray(cams, c)) return cJSON_Delete(c), false;
    double depth = p->r.depth_mm / 1000, t[3] = {0, 0, depth};
    return cJSON_AddStringToObject(c, "type", "perspective") && (persp = cJSON_AddObjectToObject(c, "perspective")) &&
           lucent_json_add_number(persp, "yfov", p->d.fov_y * M_PI / 180) &&
           lucent_json_add_number(persp, "aspectRatio", (double)p->d.screen_width / p->d.screen_height) &&
           lucent_json_add_number(persp, "znear", depth / 100) && add_node(nodes, "camera", &node) &&
           cJSON_AddNumberToObject(node, "camera", 0) && lucent_json_add_numbers(node, "translation", t, 3);
}

static bool add_light(cJSON *root, cJSON *nodes)
{
    static const double white[3] = {1, 1, 1};
    double q[4];
    rotation_to(k_light_direction, q);
    cJSON *ext = cJSON_AddObjectToObject(root, "extensions"),
          *lp = ext ? cJSON_AddObjectToObject(ext, "KHR_lights_punctual") : NULL;
    cJSON *lights = lp ? cJSON_AddArrayToObject(lp, "lights") : NULL, *l = cJSON_CreateObject(), *node, *nx, *nl;
    if (!l || !lights || !cJSON_AddItemToArray(lights, l)) return cJSON_Delete(l), false;
    return cJSON_AddStringToObject(l, "name", "key light") && cJSON_AddStringToObject(l, "type", "directional") &&
           lucent_json_add_numbers(l, "color", white, 3) && lucent_json_add_number(l, "intensity", k_light_lux) &&
           add_node(nodes, "key light", &node) && lucent_json_add_numbers(node, "rotation", q, 4) &&
           (nx = cJSON_AddObjectToObject(node, "extensions")) &&
           (nl = cJSON_AddObjectToObject(nx, "KHR_lights_punctual")) && cJSON_AddNumberToObject(nl, "light", 0);
}

static bool add_extensions_used(cJSON *root)
{
    static const char *const used[] = {LUCENT_GLTF_EXT_IOR,
                                       LUCENT_GLTF_EXT_TRANSMISSION,
                                       LUCENT_GLTF_EXT_VOLUME,
                                       LUCENT_GLTF_EXT_DIFFUSE_TRANSMISSION,
                                       LUCENT_GLTF_EXT_VOLUME_SCATTER,
                                       "KHR_lights_punctual"};
    cJSON *list = cJSON_CreateStringArray(used, (int)(sizeof used / sizeof used[0]));
    if (list && !cJSON_AddItemToObject(root, "extensionsUsed", list)) cJSON_Delete(list), list = NULL;
    return list != NULL;
}

lucent_status pack_gltf(const pack_ctx *p, const lucent_mesh *mesh_mm, const char *path)
{
    lucent_gltf_material g;
    lucent_status s = lucent_gltf_material_from_lucent(p->m, p->d.roughness, p->r.thickness_m, &g);
    if (s != LUCENT_OK) return s;
    char generator[64];
    snprintf(generator, sizeof generator, "lucent pack %s", LUCENT_VERSION_STRING);
    cJSON *root = cJSON_CreateObject(), *asset, *scene, *nodes, *list,
          *mat = material_gltf_object(&g, p->m, p->d.roughness);
    cJSON *materials = root ? cJSON_AddArrayToObject(root, "materials") : NULL, *node;
    if (!mat || !materials || !cJSON_AddItemToArray(materials, mat)) cJSON_Delete(mat), materials = NULL;
    bool ok = materials && (asset = cJSON_AddObjectToObject(root, "asset")) &&
              cJSON_AddStringToObject(asset, "version", "2.0") &&
              cJSON_AddStringToObject(asset, "generator", generator) && add_extensions_used(root) &&
              cJSON_AddNumberToObject(root, "scene", 0) && (list = cJSON_AddArrayToObject(root, "scenes")) &&
              (scene = cJSON_CreateObject()) && cJSON_AddItemToArray(list, scene) &&
              cJSON_AddStringToObject(scene, "name", p->m->name);
    int idx[3] = {0, 1, 2};
    cJSON *roots = ok ? cJSON_CreateIntArray(idx, 3) : NULL;
    if (roots && !cJSON_AddItemToObject(scene, "nodes", roots)) cJSON_Delete(roots), roots = NULL;
    ok = ok && roots && (nodes = cJSON_AddArrayToObject(root, "nodes")) && add_node(nodes, p->m->name, &node) &&
         cJSON_AddNumberToObject(node, "mesh", 0) && add_camera(root, nodes, p) && add_light(root, nodes);
    int mesh = -1;
    s = ok ? gltf_add_mesh(root, mesh_mm, 0.001, 0, &mesh)
           : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (s == LUCENT_OK) s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}
