/* glTF 2.0 scenes: a glTF document becomes the Lucent scene document it describes, which the JSON
 * reader then reads like any scene (overrides included), so that `lucent render`, `trace`, `compare`
 * and `view` take a glTF asset directly and record the scene they drew. docs/scenes.md#gltf-scenes.
 *
 *   nodes       the default scene's node trees, each node's world matrix = parent x (matrix or T R S)
 *   meshes      each primitive of triangles (strips, fans) is an object: {"mesh": {"gltf": FILE,
 *               "mesh": M, "primitive": P}, "mm_per_unit": 1000, "transform": {"matrix": world}}
 *               (glTF is in metres); points and lines are left out
 *   materials   extras.lucent's exact medium, else the inverse mapping of lucent/gltf.h
 *   cameras     the first perspective camera met (yfov, znear, zfar, aspectRatio); none: one on +z
 *               looking down -z at the bounds (from POSITION's min and max), fov_y 30
 *   lights      KHR_lights_punctual: directional (lux) as directional, point (candela) as point with
 *               intensity x 10^6 (Lucent's distances are mm), spot as point (no cone; logged); none:
 *               a key light over the camera's shoulder and a dim environment */
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "material/gltf.h"
#include "scene/internal.h"

enum { MAX_DEPTH = 256 };

typedef struct convert {
    const char *file_ref; /* what objects name as their "gltf" */
    lucent_json_node root;
    cJSON *objects, *lights, *camera;
    double lo[3], hi[3]; /* world mm, from POSITION's bounds */
    cJSON **materials;   /* per glTF material, then the default one: the Lucent material object */
    double *roughness;   /* the boundary's alpha, per material */
    int material_count;
    unsigned char *visited; /* per node */
    int node_count;
    int render_width, render_height;
} convert;

/* ---- the documents of one load ---- */

lucent_status scene_gltf_put(scene_gltf_cache *c, const char *path, gltf_doc *doc)
{
    char **paths = realloc(c->paths, ((size_t)c->count + 1) * sizeof *paths);
    if (paths) c->paths = paths;
    gltf_doc **docs = paths ? realloc(c->docs, ((size_t)c->count + 1) * sizeof *docs) : NULL;
    if (docs) c->docs = docs;
    char *copy = docs ? strdup(path) : NULL;
    if (!copy) {
        gltf_close(doc);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    c->paths[c->count] = copy, c->docs[c->count++] = doc;
    return LUCENT_OK;
}

lucent_status scene_gltf_get(scene_gltf_cache *c, const char *path, gltf_doc **dest)
{
    for (int i = 0; i < c->count; i++)
        if (!strcmp(c->paths[i], path)) return *dest = c->docs[i], LUCENT_OK;
    lucent_status s = gltf_open(path, dest);
    if (s == LUCENT_OK) s = scene_gltf_put(c, path, *dest);
    return s;
}

void scene_gltf_cache_free(scene_gltf_cache *c)
{
    for (int i = 0; i < c->count; i++) free(c->paths[i]), gltf_close(c->docs[i]);
    free(c->paths), free(c->docs);
    *c = (scene_gltf_cache){0};
}

/* ---- matrices ---- */

static lucent_status node_matrix(const lucent_json_node *n, double dest[16])
{
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(dest, identity, sizeof identity);
    if (lucent_json_has(n, "matrix")) { /* column-major, as Lucent's */
        lucent_status s = lucent_json_numbers(n, "matrix", 16, false, dest);
        if (s == LUCENT_OK && (dest[3] != 0 || dest[7] != 0 || dest[11] != 0 || dest[15] != 1))
            s = lucent_json_fail(n, "matrix", LUCENT_ERR_PARSE, "not affine: the last row must be 0 0 0 1");
        return s;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, sc[3] = {1, 1, 1};
    lucent_status s =
        lucent_json_has(n, "translation") ? lucent_json_numbers(n, "translation", 3, false, t) : LUCENT_OK;
    if (s == LUCENT_OK && lucent_json_has(n, "rotation")) s = lucent_json_numbers(n, "rotation", 4, false, q);
    if (s == LUCENT_OK && lucent_json_has(n, "scale")) s = lucent_json_numbers(n, "scale", 3, false, sc);
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (s == LUCENT_OK && !(len > 1e-6))
        s = lucent_json_fail(n, "rotation", LUCENT_ERR_PARSE, "not a unit quaternion (length %g)", len);
    if (s != LUCENT_OK) return s;
    double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
    const double r[9] = {/* columns of the rotation of unit quaternion (x, y, z, w) */
                         1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                         2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                         2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++) dest[4 * c + row] = r[3 * c + row] * sc[c]; /* T R S */
    dest[12] = t[0], dest[13] = t[1], dest[14] = t[2];
    return LUCENT_OK;
}

static v3 apply(const double m[16], double x, double y, double z, double w)
{
    return v3_make(m[0] * x + m[4] * y + m[8] * z + m[12] * w, m[1] * x + m[5] * y + m[9] * z + m[13] * w,
                   m[2] * x + m[6] * y + m[10] * z + m[14] * w);
}

/* Numbers as cJSON numbers (the document is read in memory: lucent_json_add_number's raw text would
 * not read as a number). */
static bool add_numbers(cJSON *o, const char *key, const double *v, int n)
{
    cJSON *a = cJSON_CreateDoubleArray(v, n);
    if (a && !cJSON_AddItemToObject(o, key, a)) cJSON_Delete(a), a = NULL;
    return a != NULL;
}

static bool add_v3(cJSON *o, const char *key, v3 v)
{
    double a[3];
    v3_store(v, a);
    return add_numbers(o, key, a, 3);
}

static lucent_status oom(const convert *cv)
{
    return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", cv->root.file);
}

/* ---- materials ---- */

static lucent_status material(convert *cv, int index, const lucent_json_node *ref, cJSON **dest, double *roughness)
{
    int slot = index < 0 ? cv->material_count : index;
    if (index >= cv->material_count)
        return lucent_json_fail(ref, "material", LUCENT_ERR_PARSE, "%d: no such material (%d in the file)", index,
                                cv->material_count);
    if (!cv->materials[slot]) {
        lucent_json_node list, n = {0};
        int count;
        lucent_gltf_material g;
        lucent_material m;
        bool exact = false;
        double alpha = 1;
        lucent_status s = LUCENT_OK;
        if (index >= 0) {
            s = lucent_json_array(&cv->root, "materials", true, &list, &count);
            if (s == LUCENT_OK) s = lucent_json_element(&list, index, &n);
            if (s == LUCENT_OK && !cJSON_IsObject(n.json))
                s = lucent_json_fail(&n, NULL, LUCENT_ERR_PARSE, "expected a material object");
            if (s == LUCENT_OK) s = material_gltf_read(&n, &g, &exact, &m, &alpha);
        } else {
            memset(&g, 0, sizeof g); /* glTF's default material: white, rough, metallic 1, ior 1.5 */
            g.base_color[0] = g.base_color[1] = g.base_color[2] = 1, g.roughness = 1, g.ior = 1.5;
        }
        if (s == LUCENT_OK && !g.name[0])
            snprintf(g.name, sizeof g.name, index < 0 ? "gltf-default" : "gltf-%d", index);
        if (s == LUCENT_OK && exact) snprintf(m.name, sizeof m.name, "%s", g.name);
        if (s == LUCENT_OK && !exact && (s = lucent_gltf_material_to_lucent(&g, &m, &alpha)) != LUCENT_OK)
            s = index >= 0 ? lucent_json_fail(&n, NULL, s, "%s", lucent_last_error())
                           : lucent_error(s, "%s: the default material: %s", cv->root.file, lucent_last_error());
        if (s == LUCENT_OK && !exact && !(g.has_volume && g.thickness > 0))
            lucent_log(LUCENT_LOG_INFO,
                       "%s: material \"%s\" has no volume: read as a dense medium whose multiple-scattering albedo is "
                       "its base colour (at most %g), mean free path %g mm (docs/scenes.md)",
                       cv->root.file, g.name, LUCENT_GLTF_SURFACE_MAX_ALBEDO, LUCENT_GLTF_SURFACE_MFP_MM);
        if (s != LUCENT_OK) return s;
        cJSON *o = cJSON_CreateObject();
        if (!o || !cJSON_AddStringToObject(o, "name", m.name) || !cJSON_AddStringToObject(o, "units", "mm^-1") ||
            !add_numbers(o, "sigma_a", m.sigma_a, 3) || !add_numbers(o, "sigma_s", m.sigma_s, 3) ||
            !add_numbers(o, "g", m.g, 3) || !cJSON_AddNumberToObject(o, "eta", m.eta))
            return cJSON_Delete(o), oom(cv);
        cv->materials[slot] = o, cv->roughness[slot] = alpha;
    }
    *dest = cJSON_Duplicate(cv->materials[slot], true);
    *roughness = cv->roughness[slot];
    return *dest ? LUCENT_OK : oom(cv);
}

/* ---- objects ---- */

/* Grows the bounds by the primitive's POSITION box (its 8 corners through the world matrix, in mm). */
static lucent_status bounds(convert *cv, const lucent_json_node *attrs, const double world[16])
{
    lucent_json_node list, a;
    double idx, lo[3], hi[3];
    int count;
    lucent_status s = lucent_json_number(attrs, "POSITION", &idx);
    if (s == LUCENT_OK) s = lucent_json_array(&cv->root, "accessors", true, &list, &count);
    if (s == LUCENT_OK && !(idx >= 0 && idx < count && idx == (int)idx))
        s = lucent_json_fail(attrs, "POSITION", LUCENT_ERR_PARSE, "%g: no such accessor (%d in the file)", idx, count);
    if (s == LUCENT_OK) s = lucent_json_element(&list, (int)idx, &a);
    if (s == LUCENT_OK) s = lucent_json_numbers(&a, "min", 3, false, lo);
    if (s == LUCENT_OK) s = lucent_json_numbers(&a, "max", 3, false, hi);
    for (int c = 0; s == LUCENT_OK && c < 8; c++) {
        v3 p = apply(world, c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2], 1);
        double q[3];
        v3_store(v3_scale(p, 1000), q);
        for (int k = 0; k < 3; k++) cv->lo[k] = fmin(cv->lo[k], q[k]), cv->hi[k] = fmax(cv->hi[k], q[k]);
    }
    return s;
}

static cJSON *transform(const double world[16])
{
    double rows[16]; /* the scene file's matrix is row-major, translations in mm */
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) rows[4 * r + c] = world[4 * c + r] * (r < 3 && c == 3 ? 1000 : 1);
    rows[12] = rows[13] = rows[14] = 0, rows[15] = 1;
    cJSON *t = cJSON_CreateObject();
    if (t && !add_numbers(t, "matrix", rows, 16)) cJSON_Delete(t), t = NULL;
    return t;
}

static lucent_status primitive_object(convert *cv, int mesh, int p, const lucent_json_node *prim,
                                      const double world[16], const char *name)
{
    lucent_json_node attrs;
    double mode = 4, mat = -1, alpha = 0;
    lucent_status s = lucent_json_number_or(prim, "mode", 4, &mode);
    if (s == LUCENT_OK && !(mode >= 0 && mode <= 6 && mode == (int)mode))
        s = lucent_json_fail(prim, "mode", LUCENT_ERR_PARSE, "must be 0 to 6, got %g", mode);
    if (s == LUCENT_OK && !gltf_mode_is_surface((int)mode)) return LUCENT_OK; /* points, lines: no surface */
    if (s == LUCENT_OK) s = lucent_json_object(prim, "attributes", true, &attrs);
    if (s == LUCENT_OK) s = bounds(cv, &attrs, world);
    if (s == LUCENT_OK) s = lucent_json_number_or(prim, "material", -1, &mat);
    if (s == LUCENT_OK && !(mat >= -1 && mat <= 2147483647.0 && mat == (int)mat))
        s = lucent_json_fail(prim, "material", LUCENT_ERR_PARSE, "must be a material index, got %g", mat);
    cJSON *m = NULL, *o = cJSON_CreateObject(), *ref = NULL, *t = NULL;
    if (s == LUCENT_OK && (!o || !cJSON_AddItemToArray(cv->objects, o)))
        cJSON_Delete(o), s = oom(cv);
    else if (s != LUCENT_OK)
        cJSON_Delete(o);
    if (s == LUCENT_OK) s = material(cv, (int)mat, prim, &m, &alpha);
    if (s != LUCENT_OK) return s;
    if (!cJSON_AddItemToObject(o, "material", m)) return cJSON_Delete(m), oom(cv);
    if (!(t = transform(world)) || !cJSON_AddItemToObject(o, "transform", t)) return cJSON_Delete(t), oom(cv);
    char label[LUCENT_SCENE_NAME_SIZE];
    if (p)
        snprintf(label, sizeof label, "%.40s#%d", name, p);
    else
        snprintf(label, sizeof label, "%.60s", name);
    bool ok = (ref = cJSON_AddObjectToObject(o, "mesh")) && cJSON_AddStringToObject(ref, "gltf", cv->file_ref) &&
              cJSON_AddNumberToObject(ref, "mesh", mesh) && cJSON_AddNumberToObject(ref, "primitive", p) &&
              cJSON_AddNumberToObject(o, "mm_per_unit", 1000) && cJSON_AddNumberToObject(o, "roughness", alpha) &&
              (!label[0] || cJSON_AddStringToObject(o, "name", label));
    return ok ? LUCENT_OK : oom(cv);
}

static lucent_status mesh_objects(convert *cv, const lucent_json_node *node, const double world[16])
{
    lucent_json_node meshes, me, prims, p;
    double index;
    int count, pcount;
    const char *name;
    lucent_status s = lucent_json_number(node, "mesh", &index);
    if (s == LUCENT_OK) s = lucent_json_array(&cv->root, "meshes", true, &meshes, &count);
    if (s == LUCENT_OK && !(index >= 0 && index < count && index == (int)index))
        s = lucent_json_fail(node, "mesh", LUCENT_ERR_PARSE, "%g: no such mesh (%d in the file)", index, count);
    if (s == LUCENT_OK) s = lucent_json_element(&meshes, (int)index, &me);
    if (s == LUCENT_OK) s = lucent_json_array(&me, "primitives", true, &prims, &pcount);
    if (s == LUCENT_OK) s = lucent_json_string_or(node, "name", "", &name);
    if (s == LUCENT_OK && !name[0]) s = lucent_json_string_or(&me, "name", "", &name);
    for (int i = 0; s == LUCENT_OK && i < pcount; i++) {
        s = lucent_json_element(&prims, i, &p);
        if (s == LUCENT_OK) s = primitive_object(cv, (int)index, i, &p, world, name);
    }
    return s;
}

/* ---- cameras and lights ---- */

static lucent_status camera(convert *cv, const lucent_json_node *node, const double world[16])
{
    lucent_json_node list, c, persp;
    double index, yfov, znear, zfar = 0, aspect = 0;
    int count;
    const char *type;
    lucent_status s = lucent_json_number(node, "camera", &index);
    if (s == LUCENT_OK) s = lucent_json_array(&cv->root, "cameras", true, &list, &count);
    if (s == LUCENT_OK && !(index >= 0 && index < count && index == (int)index))
        s = lucent_json_fail(node, "camera", LUCENT_ERR_PARSE, "%g: no such camera (%d in the file)", index, count);
    if (s == LUCENT_OK) s = lucent_json_element(&list, (int)index, &c);
    if (s == LUCENT_OK) s = lucent_json_string(&c, "type", &type);
    if (s != LUCENT_OK || strcmp(type, "perspective") != 0) {
        if (s == LUCENT_OK) lucent_log(LUCENT_LOG_WARN, "%s: %s: a %s camera is not read", c.file, c.path, type);
        return s;
    }
    s = lucent_json_object(&c, "perspective", true, &persp);
    if (s == LUCENT_OK) s = lucent_json_number(&persp, "yfov", &yfov);
    if (s == LUCENT_OK && !(yfov * 180 / M_PI >= 0.01 && yfov * 180 / M_PI <= 179))
        s = lucent_json_fail(&persp, "yfov", LUCENT_ERR_PARSE, "%g rad: must be in [0.01, 179] degrees", yfov);
    if (s == LUCENT_OK) s = lucent_json_number(&persp, "znear", &znear);
    if (s == LUCENT_OK && !(znear > 0 && znear <= 1e9))
        s = lucent_json_fail(&persp, "znear", LUCENT_ERR_PARSE, "must be in (0, 1e9] m, got %g", znear);
    if (s == LUCENT_OK) s = lucent_json_number_or(&persp, "zfar", 0, &zfar);
    if (s == LUCENT_OK && lucent_json_has(&persp, "zfar") && !(zfar > znear && zfar <= 1e9))
        s = lucent_json_fail(&persp, "zfar", LUCENT_ERR_PARSE, "must be in (znear, 1e9] m, got %g", zfar);
    if (s == LUCENT_OK) s = lucent_json_number_or(&persp, "aspectRatio", 0, &aspect);
    if (s == LUCENT_OK && lucent_json_has(&persp, "aspectRatio") && !(aspect >= 1.0 / 16384 && aspect <= 16384))
        s = lucent_json_fail(&persp, "aspectRatio", LUCENT_ERR_PARSE, "must be in [1/16384, 16384], got %g", aspect);
    v3 eye = v3_scale(apply(world, 0, 0, 0, 1), 1000), fwd = v3_normalize(apply(world, 0, 0, -1, 0));
    v3 up = v3_normalize(apply(world, 0, 1, 0, 0));
    if (s == LUCENT_OK && (v3_dot(fwd, fwd) == 0 || v3_dot(up, up) == 0 || v3_length(v3_cross(fwd, up)) < 1e-9))
        s = lucent_json_fail(node, NULL, LUCENT_ERR_PARSE, "the camera's matrix is singular");
    if (s != LUCENT_OK) return s;
    cJSON *cam = cJSON_CreateObject();
    bool ok = cam && add_v3(cam, "position", eye) && add_v3(cam, "target", v3_add(eye, v3_scale(fwd, 1000))) &&
              add_v3(cam, "up", up) && cJSON_AddNumberToObject(cam, "fov_y", yfov * 180 / M_PI) &&
              cJSON_AddNumberToObject(cam, "near", znear * 1000) && cJSON_AddNumberToObject(cam, "far", zfar * 1000);
    if (!ok) return cJSON_Delete(cam), oom(cv);
    cv->camera = cam;
    if (aspect > 0) cv->render_height = 512, cv->render_width = (int)fmax(1, fmin(16384, round(512 * aspect)));
    return LUCENT_OK;
}

static lucent_status light(convert *cv, const lucent_json_node *ext, const double world[16])
{
    lucent_json_node rext, lp, list, l;
    double index, intensity, color[3] = {1, 1, 1};
    int count;
    const char *type;
    lucent_status s = lucent_json_number(ext, "light", &index);
    if (s == LUCENT_OK) s = lucent_json_object(&cv->root, "extensions", true, &rext);
    if (s == LUCENT_OK) s = lucent_json_object(&rext, "KHR_lights_punctual", true, &lp);
    if (s == LUCENT_OK) s = lucent_json_array(&lp, "lights", true, &list, &count);
    if (s == LUCENT_OK && !(index >= 0 && index < count && index == (int)index))
        s = lucent_json_fail(ext, "light", LUCENT_ERR_PARSE, "%g: no such light (%d in the file)", index, count);
    if (s == LUCENT_OK) s = lucent_json_element(&list, (int)index, &l);
    if (s == LUCENT_OK) s = lucent_json_string(&l, "type", &type);
    if (s == LUCENT_OK) s = lucent_json_number_or(&l, "intensity", 1, &intensity);
    if (s == LUCENT_OK && !(intensity >= 0 && intensity <= 1e12))
        s = lucent_json_fail(&l, "intensity", LUCENT_ERR_PARSE, "must be in [0, 1e12], got %g", intensity);
    if (s == LUCENT_OK && lucent_json_has(&l, "color")) s = lucent_json_numbers(&l, "color", 3, false, color);
    for (int c = 0; s == LUCENT_OK && c < 3; c++)
        if (!(color[c] >= 0)) s = lucent_json_fail(&l, "color", LUCENT_ERR_PARSE, "must be >= 0, got %g", color[c]);
    bool sun = s == LUCENT_OK && !strcmp(type, "directional"), spot = s == LUCENT_OK && !strcmp(type, "spot");
    if (s == LUCENT_OK && !sun && !spot && strcmp(type, "point") != 0)
        s = lucent_json_fail(&l, "type", LUCENT_ERR_PARSE, "\"%s\": expected directional, point or spot", type);
    if (s == LUCENT_OK && spot)
        lucent_log(LUCENT_LOG_WARN, "%s: %s: a spot light is read as a point light (Lucent has no cones)", l.file,
                   l.path);
    v3 dir = v3_normalize(apply(world, 0, 0, -1, 0));
    if (s == LUCENT_OK && sun && v3_dot(dir, dir) == 0)
        s = lucent_json_fail(ext, NULL, LUCENT_ERR_PARSE, "the light's matrix is singular");
    if (s != LUCENT_OK) return s;
    cJSON *o = cJSON_CreateObject();
    bool ok = o && cJSON_AddItemToArray(cv->lights, o) &&
              cJSON_AddStringToObject(o, "type", sun ? "directional" : "point") && add_numbers(o, "color", color, 3) &&
              cJSON_AddNumberToObject(o, "intensity", sun ? intensity : intensity * 1e6) &&
              (sun ? add_v3(o, "direction", dir) : add_v3(o, "position", v3_scale(apply(world, 0, 0, 0, 1), 1000)));
    return ok ? LUCENT_OK : oom(cv);
}

/* ---- the node trees ---- */

/* An array element that must be a whole number (a node index). */
static lucent_status element_index(const lucent_json_node *list, int i, lucent_json_node *e, double *dest)
{
    lucent_status s = lucent_json_element(list, i, e);
    if (s == LUCENT_OK && !(cJSON_IsNumber(e->json) && isfinite(e->json->valuedouble)))
        s = lucent_json_fail(e, NULL, LUCENT_ERR_PARSE, "expected a node index");
    if (s == LUCENT_OK) *dest = e->json->valuedouble;
    return s;
}

static lucent_status visit(convert *cv, const lucent_json_node *nodes, double index, const lucent_json_node *ref,
                           const double parent[16], int depth)
{
    lucent_json_node n, kids, k, ext, lp;
    if (!(index >= 0 && index < cv->node_count && index == (int)index))
        return lucent_json_fail(ref, NULL, LUCENT_ERR_PARSE, "%g: no such node (%d in the file)", index,
                                cv->node_count);
    if (cv->visited[(int)index]++)
        return lucent_json_fail(ref, NULL, LUCENT_ERR_PARSE, "nodes[%d] is reached twice: glTF nodes form trees",
                                (int)index);
    if (depth > MAX_DEPTH)
        return lucent_json_fail(ref, NULL, LUCENT_ERR_UNSUPPORTED, "nodes nested deeper than %d", MAX_DEPTH);
    double local[16], world[16], child;
    int count = 0;
    lucent_status s = lucent_json_element(nodes, (int)index, &n);
    if (s == LUCENT_OK && !cJSON_IsObject(n.json))
        s = lucent_json_fail(&n, NULL, LUCENT_ERR_PARSE, "expected a node object");
    if (s == LUCENT_OK) s = node_matrix(&n, local);
    if (s == LUCENT_OK) lucent_mat4_mul(parent, local, world);
    if (s == LUCENT_OK && lucent_json_has(&n, "mesh")) s = mesh_objects(cv, &n, world);
    if (s == LUCENT_OK && lucent_json_has(&n, "camera") && !cv->camera) s = camera(cv, &n, world);
    if (s == LUCENT_OK && lucent_json_has(&n, "extensions") &&
        (s = lucent_json_object(&n, "extensions", false, &ext)) == LUCENT_OK &&
        (s = lucent_json_object(&ext, "KHR_lights_punctual", false, &lp)) == LUCENT_OK && lp.json)
        s = light(cv, &lp, world);
    if (s == LUCENT_OK) s = lucent_json_array(&n, "children", false, &kids, &count);
    for (int i = 0; s == LUCENT_OK && i < count; i++) {
        s = element_index(&kids, i, &k, &child);
        if (s == LUCENT_OK) s = visit(cv, nodes, child, &k, world, depth + 1);
    }
    return s;
}

/* The roots: the default scene's nodes (scene, else scenes[0]), else every node no other names as a
 * child. */
static lucent_status visit_roots(convert *cv)
{
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    lucent_json_node nodes, scenes, sc, list, e;
    int count = 0, scene_count = 0;
    double which = 0, index;
    lucent_status s = lucent_json_array(&cv->root, "nodes", false, &nodes, &cv->node_count);
    if (s == LUCENT_OK && cv->node_count > 0 && !(cv->visited = calloc((size_t)cv->node_count, 1))) return oom(cv);
    if (s == LUCENT_OK) s = lucent_json_array(&cv->root, "scenes", false, &scenes, &scene_count);
    if (s == LUCENT_OK) s = lucent_json_number_or(&cv->root, "scene", 0, &which);
    if (s == LUCENT_OK && scene_count > 0 && !(which >= 0 && which < scene_count && which == (int)which))
        s = lucent_json_fail(&cv->root, "scene", LUCENT_ERR_PARSE, "%g: no such scene (%d in the file)", which,
                             scene_count);
    if (s == LUCENT_OK && scene_count > 0) {
        s = lucent_json_element(&scenes, (int)which, &sc);
        if (s == LUCENT_OK) s = lucent_json_array(&sc, "nodes", false, &list, &count);
        for (int i = 0; s == LUCENT_OK && i < count; i++) {
            s = element_index(&list, i, &e, &index);
            if (s == LUCENT_OK) s = visit(cv, &nodes, index, &e, identity, 0);
        }
        return s;
    }
    /* no scenes: a node nobody names as a child is a root (those named are marked first) */
    unsigned char *child = s == LUCENT_OK && cv->node_count > 0 ? calloc((size_t)cv->node_count, 1) : NULL;
    if (s == LUCENT_OK && cv->node_count > 0 && !child) return oom(cv);
    for (int i = 0; s == LUCENT_OK && i < cv->node_count; i++) {
        lucent_json_node n, kids, k;
        int kc = 0;
        s = lucent_json_element(&nodes, i, &n);
        if (s == LUCENT_OK && cJSON_IsObject(n.json)) s = lucent_json_array(&n, "children", false, &kids, &kc);
        for (int j = 0; s == LUCENT_OK && j < kc; j++) {
            s = element_index(&kids, j, &k, &index);
            if (s == LUCENT_OK && index >= 0 && index < cv->node_count && index == (int)index) child[(int)index] = 1;
        }
    }
    for (int i = 0; s == LUCENT_OK && i < cv->node_count; i++)
        if (!child[i]) {
            lucent_json_node n;
            s = lucent_json_element(&nodes, i, &n);
            if (s == LUCENT_OK) s = visit(cv, &nodes, i, &n, identity, 0);
        }
    free(child);
    return s;
}

/* ---- defaults and the document ---- */

/* No camera: on +z of the bounds' centre looking down -z (glTF's view direction), the bounding sphere
 * filling fov_y 30 with 5% to spare. */
static lucent_status default_camera(convert *cv)
{
    v3 lo = v3_load(cv->lo), hi = v3_load(cv->hi), c = v3_scale(v3_add(lo, hi), 0.5);
    double r = fmax(0.5 * v3_length(v3_sub(hi, lo)), 1e-3), dist = 1.05 * r / sin(15 * M_PI / 180);
    cJSON *cam = cJSON_CreateObject();
    bool ok = cam && add_v3(cam, "position", v3_add(c, v3_make(0, 0, dist))) && add_v3(cam, "target", c) &&
              add_v3(cam, "up", v3_make(0, 1, 0)) && cJSON_AddNumberToObject(cam, "fov_y", 30);
    if (!ok) return cJSON_Delete(cam), oom(cv);
    cv->camera = cam;
    return LUCENT_OK;
}

/* No lights: a key light travelling from over the camera's left shoulder, and a dim environment. */
static lucent_status default_lights(convert *cv)
{
    double p[3], t[3], u[3];
    lucent_json_node cam = lucent_json_root(cv->camera, cv->root.file, "camera");
    lucent_json_numbers(&cam, "position", 3, false, p);
    lucent_json_numbers(&cam, "target", 3, false, t);
    lucent_json_numbers(&cam, "up", 3, false, u);
    v3 fwd = v3_normalize(v3_sub(v3_load(t), v3_load(p))), right = v3_normalize(v3_cross(fwd, v3_load(u)));
    v3 up = v3_cross(right, fwd), dir = v3_normalize(v3_add(v3_add(fwd, v3_scale(up, -0.6)), v3_scale(right, 0.4)));
    cJSON *key = cJSON_CreateObject(), *env = NULL;
    if (!key || !cJSON_AddItemToArray(cv->lights, key)) return cJSON_Delete(key), oom(cv);
    if (!(env = cJSON_CreateObject()) || !cJSON_AddItemToArray(cv->lights, env)) return cJSON_Delete(env), oom(cv);
    bool ok = cJSON_AddStringToObject(key, "type", "directional") && add_v3(key, "direction", dir) &&
              cJSON_AddNumberToObject(key, "intensity", 3) && cJSON_AddStringToObject(env, "type", "environment") &&
              cJSON_AddNumberToObject(env, "intensity", 0.08);
    return ok ? LUCENT_OK : oom(cv);
}

/* The file's base name without its extension. */
static void stem(const char *path, char *dest, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(dest, size, "%.*s", (int)strcspn(base, "."), base);
}

static lucent_status document(convert *cv, cJSON **dest)
{
    char name[LUCENT_SCENE_NAME_SIZE], desc[300];
    stem(cv->root.file, name, sizeof name);
    snprintf(desc, sizeof desc, "the glTF asset %.200s", cv->root.file);
    cJSON *doc = cJSON_CreateObject();
    bool ok = doc && cJSON_AddStringToObject(doc, "name", name) && cJSON_AddStringToObject(doc, "description", desc) &&
              cJSON_AddItemToObject(doc, "camera", cv->camera);
    if (ok) cv->camera = NULL;
    ok = ok && cJSON_AddItemToObject(doc, "lights", cv->lights);
    if (ok) cv->lights = NULL;
    ok = ok && cJSON_AddItemToObject(doc, "objects", cv->objects);
    if (ok) cv->objects = NULL;
    cJSON *render = ok && cv->render_width ? cJSON_AddObjectToObject(doc, "render") : NULL;
    if (cv->render_width)
        ok = ok && render && cJSON_AddNumberToObject(render, "width", cv->render_width) &&
             cJSON_AddNumberToObject(render, "height", cv->render_height);
    if (!ok) return cJSON_Delete(doc), oom(cv);
    *dest = doc;
    return LUCENT_OK;
}

lucent_status scene_gltf_document(gltf_doc *doc, const char *file_ref, cJSON **dest)
{
    *dest = NULL;
    convert cv = {.file_ref = file_ref, .root = gltf_root(doc)};
    for (int k = 0; k < 3; k++) cv.lo[k] = INFINITY, cv.hi[k] = -INFINITY;
    lucent_json_node list;
    lucent_status s = lucent_json_array(&cv.root, "materials", false, &list, &cv.material_count);
    cv.materials = calloc((size_t)cv.material_count + 1, sizeof *cv.materials);
    cv.roughness = calloc((size_t)cv.material_count + 1, sizeof *cv.roughness);
    cv.objects = cJSON_CreateArray(), cv.lights = cJSON_CreateArray();
    if (s == LUCENT_OK && (!cv.materials || !cv.roughness || !cv.objects || !cv.lights)) s = oom(&cv);
    if (s == LUCENT_OK) s = visit_roots(&cv);
    if (s == LUCENT_OK && cJSON_GetArraySize(cv.objects) == 0)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: no mesh of triangles in the scene", cv.root.file);
    if (s == LUCENT_OK && !cv.camera) s = default_camera(&cv);
    if (s == LUCENT_OK && cJSON_GetArraySize(cv.lights) == 0) s = default_lights(&cv);
    if (s == LUCENT_OK) s = document(&cv, dest);
    for (int i = 0; cv.materials && i <= cv.material_count; i++) cJSON_Delete(cv.materials[i]);
    free(cv.materials), free(cv.roughness), free(cv.visited);
    cJSON_Delete(cv.objects), cJSON_Delete(cv.lights), cJSON_Delete(cv.camera);
    return s;
}
