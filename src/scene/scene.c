/* Scene files: one loader for the GL renderer and the path tracer. */
#include <libgen.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene/internal.h"

static const char *const k_scene_keys[] = {"name", "description", "camera", "lights", "objects", "render", NULL};

static lucent_status read_objects(const lucent_json_node *root, const char *base_dir, bool skip,
                                  scene_gltf_cache *cache, lucent_scene *sc)
{
    lucent_json_node list, e;
    int n = 0;
    lucent_status s = lucent_json_array(root, "objects", true, &list, &n);
    if (s == LUCENT_OK && n == 0) s = lucent_json_fail(&list, NULL, LUCENT_ERR_PARSE, "expected at least one object");
    if (s != LUCENT_OK) return s;
    sc->objects = calloc((size_t)n, sizeof *sc->objects);
    if (!sc->objects) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < n && s == LUCENT_OK; i++) {
        s = lucent_json_element(&list, i, &e);
        if (s == LUCENT_OK) s = scene_read_object(&e, base_dir, skip, cache, &sc->objects[i]);
        if (s == LUCENT_OK) sc->object_count = i + 1;
    }
    return s;
}

void lucent_scene_bounds(const lucent_scene *scene, double min[3], double max[3])
{
    for (int i = 0; i < 3; i++) min[i] = INFINITY, max[i] = -INFINITY;
    for (int o = 0; o < scene->object_count; o++) {
        const lucent_mesh *m = scene->objects[o].mesh;
        for (size_t v = 0; m && scene->objects[o].visible && v < m->vertex_count; v++)
            for (int i = 0; i < 3; i++)
                min[i] = fmin(min[i], m->positions[3 * v + i]), max[i] = fmax(max[i], m->positions[3 * v + i]);
    }
}

/* Near and far planes not given in the file enclose the scene's bounding sphere, with a margin;
 * near is kept at least far / 10^4 for depth precision. */
static void resolve_planes(lucent_scene *sc)
{
    lucent_camera *c = &sc->camera;
    double lo[3], hi[3], centre[3];
    lucent_scene_bounds(sc, lo, hi);
    double radius = 0;
    for (int i = 0; i < 3; i++) {
        centre[i] = lo[i] <= hi[i] ? 0.5 * (lo[i] + hi[i]) : c->target[i];
        radius += lo[i] <= hi[i] ? 0.25 * (hi[i] - lo[i]) * (hi[i] - lo[i]) : 0;
    }
    radius = fmax(sqrt(radius), 1e-3);
    double dist = v3_length(v3_sub(v3_load(centre), v3_load(c->position)));
    double far = c->far_plane > 0 ? c->far_plane : 1.05 * (dist + radius);
    double near = c->near_plane > 0 ? c->near_plane : fmax(0.95 * (dist - radius), far * 1e-4);
    c->near_plane = fmin(near, 0.5 * far), c->far_plane = far;
}

static lucent_status read_scene(const lucent_json_node *root, const char *base_dir, bool skip, scene_gltf_cache *cache,
                                lucent_scene *sc)
{
    const char *name, *description;
    if (!cJSON_IsObject(root->json))
        return lucent_json_fail(root, NULL, LUCENT_ERR_PARSE, "expected a scene object {\"camera\", \"lights\", ...}");
    lucent_status s = lucent_json_check_keys(root, k_scene_keys);
    if (s == LUCENT_OK) s = lucent_json_string_or(root, "name", "", &name);
    if (s == LUCENT_OK) s = lucent_json_string_or(root, "description", "", &description);
    if (s == LUCENT_OK) snprintf(sc->name, sizeof sc->name, "%s", name);
    if (s == LUCENT_OK) snprintf(sc->description, sizeof sc->description, "%s", description);
    if (s == LUCENT_OK) s = scene_read_camera(root, &sc->camera);
    if (s == LUCENT_OK) s = scene_read_lights(root, &sc->lights, &sc->light_count);
    if (s == LUCENT_OK) s = scene_read_render(root, &sc->render);
    if (s == LUCENT_OK) s = read_objects(root, base_dir, skip, cache, sc);
    if (s == LUCENT_OK) resolve_planes(sc);
    return s;
}

/* The file's base name without its extension: the default scene name. */
static void stem(const char *path, char *dest, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t len = strcspn(base, ".");
    snprintf(dest, size, "%.*s", (int)len, base);
}

/* Reads a scene document; cache holds the glTF documents already open (a glTF scene's own) and is
 * freed. */
static lucent_status parse_doc_with(cJSON *json, const char *name, const char *base_dir,
                                    const lucent_scene_load_desc *desc, scene_gltf_cache *cache, lucent_scene **dest)
{
    static const lucent_scene_load_desc none = {0};
    const lucent_scene_load_desc *d = desc ? desc : &none;
    lucent_status s = scene_apply_overrides(json, name, d->overrides, d->override_count);
    lucent_scene *sc = calloc(1, sizeof *sc);
    if (s == LUCENT_OK && !sc) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) {
        lucent_json_node root = lucent_json_root(json, name, "");
        s = read_scene(&root, base_dir, d->skip_meshes, cache, sc);
    }
    scene_gltf_cache_free(cache);
    if (s == LUCENT_OK && !sc->name[0]) stem(name, sc->name, sizeof sc->name);
    if (s == LUCENT_OK && !(sc->json = cJSON_Print(json))) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s != LUCENT_OK) {
        lucent_scene_destroy(sc);
        return s;
    }
    *dest = sc;
    return LUCENT_OK;
}

static lucent_status parse_doc(cJSON *json, const char *name, const char *base_dir, const lucent_scene_load_desc *desc,
                               lucent_scene **dest)
{
    scene_gltf_cache cache = {0};
    return parse_doc_with(json, name, base_dir, desc, &cache, dest);
}

/* ---- glTF scenes: the document they describe, read as any (gltf.c) ---- */

static bool has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

/* doc becomes the cache's first entry, under base_dir/<its base name>, what its objects name. */
static lucent_status parse_gltf(gltf_doc *doc, const char *name, const char *base_dir,
                                const lucent_scene_load_desc *desc, lucent_scene **dest)
{
    const char *base = strrchr(name, '/');
    base = base ? base + 1 : name;
    char key[LUCENT_SCENE_PATH_SIZE];
    snprintf(key, sizeof key, "%s/%s", base_dir, base);
    scene_gltf_cache cache = {0};
    cJSON *json = NULL;
    lucent_status s = scene_gltf_put(&cache, key, doc);
    if (s == LUCENT_OK) s = scene_gltf_document(doc, base, &json);
    if (s != LUCENT_OK) {
        scene_gltf_cache_free(&cache);
        return s;
    }
    s = parse_doc_with(json, name, base_dir, desc, &cache, dest);
    cJSON_Delete(json);
    return s;
}

lucent_status lucent_scene_parse_gltf(const void *data, size_t size, const char *name, const char *base_dir,
                                      const lucent_scene_load_desc *desc, lucent_scene **dest)
{
    *dest = NULL;
    if (!name) name = "<scene>.gltf";
    gltf_doc *doc;
    lucent_status s = gltf_open_memory(data, size, name, base_dir, &doc);
    if (s == LUCENT_OK) s = parse_gltf(doc, name, base_dir ? base_dir : ".", desc, dest);
    return s;
}

static lucent_status load_gltf(const char *path, const char *dir, const lucent_scene_load_desc *desc,
                               lucent_scene **dest)
{
    gltf_doc *doc;
    lucent_status s = gltf_open(path, &doc);
    if (s == LUCENT_OK) s = parse_gltf(doc, path, dir, desc, dest);
    return s;
}

lucent_status lucent_scene_parse(const char *text, const char *name, const char *base_dir,
                                 const lucent_scene_load_desc *desc, lucent_scene **dest)
{
    cJSON *json;
    *dest = NULL;
    if (!name) name = "<scene>";
    lucent_status s = lucent_json_parse_text(text, name, &json);
    if (s != LUCENT_OK) return s;
    s = parse_doc(json, name, base_dir ? base_dir : ".", desc, dest);
    cJSON_Delete(json);
    return s;
}

lucent_status lucent_scene_load(const char *path, const lucent_scene_load_desc *desc, lucent_scene **dest)
{
    cJSON *json;
    *dest = NULL;
    if (!path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "scene: no file given (NULL path)");
    if (strlen(path) >= LUCENT_SCENE_PATH_SIZE)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%.64s...: path too long", path);
    char dir[LUCENT_SCENE_PATH_SIZE];
    snprintf(dir, sizeof dir, "%s", path);
    lucent_status s;
    if (has_suffix(path, ".gltf") || has_suffix(path, ".glb")) {
        s = load_gltf(path, dirname(dir), desc, dest);
    } else if ((s = lucent_json_parse_file(path, &json)) == LUCENT_OK) {
        s = parse_doc(json, path, dirname(dir), desc, dest);
        cJSON_Delete(json);
    }
    if (s == LUCENT_OK) snprintf((*dest)->path, sizeof(*dest)->path, "%s", path);
    return s;
}

void lucent_scene_destroy(lucent_scene *scene)
{
    if (!scene) return;
    for (int i = 0; i < scene->object_count; i++) scene_object_free(&scene->objects[i]);
    free(scene->objects);
    free(scene->lights);
    cJSON_free(scene->json);
    free(scene);
}
