/* Scene objects: the mesh (a file or a primitive), its placement in world millimetres, the material
 * inside it and how its surface looks. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "base/mat4.h"
#include "base/optics.h"
#include "lucent/skin.h"
#include "material/internal.h"
#include "scene/internal.h"

static const char *const k_object_keys[] = {
    "name",        "mesh",   "mm_per_unit",  "transform", "material",  "albedo",    "albedo_texture", "roughness",
    "specular_f0", "sigma0", "sss_strength", "visible",   "subdivide", "as_points", "points",         NULL};

/* ---- paths ---- */

static void join_path(const char *base_dir, const char *path, char *dest, size_t size)
{
    if (path[0] == '/' || !base_dir || !base_dir[0])
        snprintf(dest, size, "%s", path);
    else
        snprintf(dest, size, "%s/%s", base_dir, path);
}

/* ---- the mesh ---- */

static const char *const k_primitive_names[] = {"uv_sphere", "icosphere", "torus", "ellipsoid", NULL};
static const char *const k_primitive_keys[] = {"primitive", "radius",  "major_radius", "axes",
                                               "u_count",   "v_count", "subdivisions", NULL};

/* An optional length > 0 (0 when absent: the primitive's default). */
static lucent_status read_positive(const lucent_json_node *n, const char *key, double *dest)
{
    lucent_status s = lucent_json_number_or(n, key, 0, dest);
    if (s == LUCENT_OK && lucent_json_has(n, key) && !(*dest > 0 && *dest <= 1e12))
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be > 0 and at most 1e12, got %g", *dest);
    return s;
}

static lucent_status read_primitive(const lucent_json_node *n, lucent_primitive_desc *d, const char **kind)
{
    memset(d, 0, sizeof *d);
    *kind = ""; /* named in the mesh source even when a key is refused before "primitive" is read */
    lucent_status s = lucent_json_check_keys(n, k_primitive_keys);
    if (s == LUCENT_OK) s = lucent_json_string(n, "primitive", kind);
    int k = -1;
    for (int i = 0; s == LUCENT_OK && k_primitive_names[i]; i++)
        if (!strcasecmp(*kind, k_primitive_names[i])) k = i;
    if (s == LUCENT_OK && k < 0)
        s = lucent_json_fail(n, "primitive", LUCENT_ERR_PARSE,
                             "unknown primitive \"%s\" (uv_sphere, icosphere, torus, ellipsoid)", *kind);
    d->kind = (lucent_primitive_kind)(k < 0 ? 0 : k);
    /* Each key that the primitive reads (a key it does not read is refused, not ignored); a value given is
     * used as given: lucent_primitive_desc's zero means the default, so 0 is refused, never a unit sphere. */
    /* per kind, the keys it reads (bit i: k_primitive_keys[i]): uv_sphere, icosphere, torus, ellipsoid */
    static const unsigned reads[4] = {1u << 1 | 1u << 4 | 1u << 5, 1u << 1 | 1u << 6,
                                      1u << 1 | 1u << 2 | 1u << 4 | 1u << 5, 1u << 3 | 1u << 4 | 1u << 5};
    for (int i = 1; s == LUCENT_OK && k_primitive_keys[i]; i++)
        if (!(reads[d->kind] >> i & 1) && lucent_json_has(n, k_primitive_keys[i]))
            s = lucent_json_fail(n, k_primitive_keys[i], LUCENT_ERR_PARSE, "the primitive %s has no %s",
                                 k_primitive_names[d->kind], k_primitive_keys[i]);
    static const double no_axes[3] = {0, 0, 0};
    if (s == LUCENT_OK) s = read_positive(n, "radius", &d->radius);
    if (s == LUCENT_OK) s = read_positive(n, "major_radius", &d->major_radius);
    if (s == LUCENT_OK) s = scene_read_vec3(n, "axes", no_axes, d->axes);
    for (int a = 0; s == LUCENT_OK && lucent_json_has(n, "axes") && a < 3; a++)
        if (!(d->axes[a] > 0 && d->axes[a] <= 1e12))
            s = lucent_json_fail(n, "axes", LUCENT_ERR_PARSE, "each axis must be > 0 and at most 1e12, got %g",
                                 d->axes[a]);
    int min_v = d->kind == LUCENT_PRIMITIVE_TORUS ? 3 : 2;
    if (s == LUCENT_OK && lucent_json_has(n, "u_count")) s = scene_read_int(n, "u_count", 0, 3, 1 << 14, &d->u_count);
    if (s == LUCENT_OK && lucent_json_has(n, "v_count"))
        s = scene_read_int(n, "v_count", 0, min_v, 1 << 14, &d->v_count);
    if (s == LUCENT_OK && lucent_json_has(n, "subdivisions"))
        s = scene_read_int(n, "subdivisions", 0, 1, 9, &d->subdivisions);
    return s;
}

/* {"gltf": FILE, "mesh": M, "primitive": P}: one primitive of a glTF file's mesh, in its units. */
static const char *const k_gltf_mesh_keys[] = {"gltf", "mesh", "primitive", NULL};

static lucent_status load_gltf_mesh(const lucent_json_node *m, const char *base_dir, bool skip, scene_gltf_cache *cache,
                                    lucent_scene_object *o)
{
    const char *file;
    int mesh = 0, prim = 0;
    char path[LUCENT_SCENE_PATH_SIZE];
    lucent_status s = lucent_json_check_keys(m, k_gltf_mesh_keys);
    if (s == LUCENT_OK) s = lucent_json_string(m, "gltf", &file);
    if (s == LUCENT_OK) s = scene_read_int(m, "mesh", 0, 0, 1 << 30, &mesh);
    if (s == LUCENT_OK) s = scene_read_int(m, "primitive", 0, 0, 1 << 30, &prim);
    if (s != LUCENT_OK) return s;
    join_path(base_dir, file, path, sizeof path);
    snprintf(o->mesh_source, sizeof o->mesh_source, "%.900s#meshes[%d].primitives[%d]", path, mesh, prim);
    gltf_doc *doc;
    if (skip) return LUCENT_OK;
    if ((s = scene_gltf_get(cache, path, &doc)) == LUCENT_OK) s = gltf_read_primitive(doc, mesh, prim, &o->mesh);
    return s == LUCENT_OK ? s : lucent_json_fail(m, NULL, s, "%s", lucent_last_error());
}

static lucent_status load_mesh(const lucent_json_node *n, const char *base_dir, bool skip, scene_gltf_cache *cache,
                               lucent_scene_object *o)
{
    lucent_json_node m;
    lucent_status s = lucent_json_member(n, "mesh", true, &m);
    if (s != LUCENT_OK) return s;
    if (cJSON_IsObject(m.json) && lucent_json_has(&m, "gltf")) return load_gltf_mesh(&m, base_dir, skip, cache, o);
    if (cJSON_IsObject(m.json)) {
        lucent_primitive_desc d;
        const char *kind;
        s = read_primitive(&m, &d, &kind);
        snprintf(o->mesh_source, sizeof o->mesh_source, "primitive:%s", kind);
        if (s == LUCENT_OK && !skip && (s = lucent_mesh_primitive(&d, &o->mesh)) != LUCENT_OK)
            s = lucent_json_fail(&m, NULL, s, "%s", lucent_last_error());
        return s;
    }
    const char *file;
    if (!cJSON_IsString(m.json))
        return lucent_json_fail(&m, NULL, LUCENT_ERR_PARSE, "expected a file name or {\"primitive\": ...}");
    if ((s = lucent_json_string(n, "mesh", &file)) != LUCENT_OK) return s; /* e.g. not UTF-8: no name */
    join_path(base_dir, file, o->mesh_source, sizeof o->mesh_source);
    if (skip) return s;
    if (access(o->mesh_source, R_OK) != 0)
        return lucent_json_fail(&m, NULL, LUCENT_ERR_NOT_FOUND, "cannot open %s: %s%s", o->mesh_source, strerror(errno),
                                strstr(o->mesh_source, "meshes/") ? " (run `make setup` to fetch the sample meshes)"
                                                                  : "");
    if ((s = lucent_mesh_load(o->mesh_source, NULL, &o->mesh)) != LUCENT_OK)
        s = lucent_json_fail(&m, NULL, s, "%s", lucent_last_error());
    return s;
}

/* "points": a point cloud (lucent_surfels_load) in place of a mesh; its surfels at level 0 only
 * (the points method builds the levels with its own settings), its mesh the points without faces. */
static lucent_status load_points(const lucent_json_node *n, const char *base_dir, bool skip, lucent_scene_object *o)
{
    if (lucent_json_has(n, "mesh"))
        return lucent_json_fail(n, "points", LUCENT_ERR_PARSE, "give mesh or points, not both");
    const char *file;
    lucent_status s = lucent_json_string(n, "points", &file);
    if (s != LUCENT_OK) return s;
    join_path(base_dir, file, o->mesh_source, sizeof o->mesh_source);
    o->as_points = true;
    if (skip) return LUCENT_OK;
    if (access(o->mesh_source, R_OK) != 0)
        return lucent_json_fail(n, "points", LUCENT_ERR_NOT_FOUND, "cannot open %s: %s", o->mesh_source,
                                strerror(errno));
    s = lucent_surfels_load(o->mesh_source, &(lucent_surfels_desc){.max_levels = 1}, &o->points);
    if (s != LUCENT_OK) return lucent_json_fail(n, "points", s, "%s", lucent_last_error());
    size_t count = o->points->count;
    if ((s = lucent_mesh_create(count, 0, &o->mesh)) != LUCENT_OK) return s;
    for (size_t i = 0; i < 3 * count; i++) o->mesh->positions[i] = o->points->positions[i];
    return LUCENT_OK;
}

/* The cloud moved into world mm, and its mesh with it (positions and the surfels' normals). */
static void place_points(lucent_scene_object *o)
{
    lucent_surfels_transform(o->points, o->to_world);
    for (size_t i = 0; i < 3 * o->points->count; i++)
        o->mesh->positions[i] = o->points->positions[i], o->mesh->normals[i] = o->points->normals[i];
}

/* "subdivide": Loop subdivision levels, for coarse meshes whose facets would show (the path tracer
 * sees the true facets; the GL renderer interpolates normals across them). */
static lucent_status subdivide(const lucent_json_node *n, lucent_scene_object *o)
{
    int levels = 0;
    lucent_status s = scene_read_int(n, "subdivide", 0, 0, 4, &levels);
    if (s == LUCENT_OK && levels > 0 && lucent_json_has(n, "points"))
        return lucent_json_fail(n, "subdivide", LUCENT_ERR_PARSE, "a point cloud has no faces to subdivide");
    if (s == LUCENT_OK && o->mesh && levels > 0 && (s = lucent_mesh_subdivide(o->mesh, levels)) != LUCENT_OK)
        s = lucent_json_fail(n, "subdivide", s, "%s", lucent_last_error());
    return s;
}

/* ---- the transform: world = T Rz Ry Rx S (mm_per_unit p) ---- */

static void mat_rotation(int axis, double degrees, double dest[16])
{
    double c = cos(degrees * M_PI / 180), s = sin(degrees * M_PI / 180);
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    memset(dest, 0, 16 * sizeof *dest);
    dest[0] = dest[5] = dest[10] = dest[15] = 1;
    dest[4 * i + i] = c, dest[4 * j + j] = c;
    dest[4 * i + j] = s, dest[4 * j + i] = -s; /* column i gets +s in row j */
}

static lucent_status read_matrix(const lucent_json_node *t, double dest[16])
{
    double rows[16];
    lucent_status s = lucent_json_numbers(t, "matrix", 16, false, rows);
    for (int r = 0; s == LUCENT_OK && r < 4; r++)
        for (int c = 0; c < 4; c++) dest[4 * c + r] = rows[4 * r + c]; /* the file is row-major */
    if (s == LUCENT_OK && (dest[3] != 0 || dest[7] != 0 || dest[11] != 0 || dest[15] != 1))
        s = lucent_json_fail(t, "matrix", LUCENT_ERR_PARSE, "the last row must be 0 0 0 1 (an affine map)");
    return s;
}

static const char *const k_transform_keys[] = {"translate", "rotate", "scale", "matrix", NULL};

static lucent_status read_transform(const lucent_json_node *n, double mm_per_unit, double dest[16])
{
    lucent_json_node t;
    double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, r[16];
    lucent_status s = lucent_json_object(n, "transform", false, &t);
    if (s == LUCENT_OK && t.json) s = lucent_json_check_keys(&t, k_transform_keys);
    if (s == LUCENT_OK && t.json && lucent_json_has(&t, "matrix")) {
        if (lucent_json_has(&t, "translate") || lucent_json_has(&t, "rotate") || lucent_json_has(&t, "scale"))
            return lucent_json_fail(&t, "matrix", LUCENT_ERR_PARSE,
                                    "give a matrix or translate/rotate/scale, not both");
        s = read_matrix(&t, m);
    } else if (s == LUCENT_OK && t.json) {
        static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
        double tr[3], rot[3], sc[3];
        s = scene_read_vec3(&t, "translate", zero, tr);
        if (s == LUCENT_OK) s = scene_read_vec3(&t, "rotate", zero, rot);
        if (s == LUCENT_OK && lucent_json_has(&t, "scale"))
            s = lucent_json_numbers(&t, "scale", 3, true, sc);
        else
            memcpy(sc, one, sizeof sc);
        for (int i = 0; s == LUCENT_OK && i < 3; i++)
            if (!(fabs(sc[i]) >= 1e-12 && fabs(sc[i]) <= 1e12))
                s = lucent_json_fail(&t, "scale", LUCENT_ERR_PARSE, "must be within +-[1e-12, 1e12], got %g", sc[i]);
        for (int a = 2; s == LUCENT_OK && a >= 0; a--) mat_rotation(a, rot[a], r), lucent_mat4_mul(m, r, m);
        for (int c = 0; c < 3; c++)
            for (int row = 0; row < 3; row++) m[4 * c + row] *= sc[c];
        m[12] = tr[0], m[13] = tr[1], m[14] = tr[2];
    }
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++) m[4 * c + row] *= mm_per_unit;
    memcpy(dest, m, sizeof m);
    return s;
}

/* The farthest a vertex may stand from the origin in world mm (1000 km): the renderers work in single
 * precision, where a scale of 1e300 made every vertex infinite and the object vanished. */
#define WORLD_MAX_MM 1e9

/* After the transform: every vertex finite and within WORLD_MAX_MM, naming the transform and its scale. */
static lucent_status check_placed(const lucent_json_node *n, const lucent_mesh *mesh)
{
    for (size_t i = 0; i < 3 * mesh->vertex_count; i++)
        if (!(fabs(mesh->positions[i]) <= WORLD_MAX_MM))
            return lucent_json_fail(n, lucent_json_has(n, "transform") ? "transform" : "mm_per_unit", LUCENT_ERR_PARSE,
                                    "places vertex %zu at %g mm from the origin, beyond the %g mm the renderers "
                                    "represent (check the scale, the translation and mm_per_unit)",
                                    i / 3, mesh->positions[i], WORLD_MAX_MM);
    return LUCENT_OK;
}

/* Moves the mesh into world mm; a mirroring map reverses the faces so normals stay outward. */
static void transform_mesh(lucent_mesh *mesh, const double m[16])
{
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        double *p = mesh->positions + 3 * v, q[3];
        for (int r = 0; r < 3; r++) q[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        memcpy(p, q, sizeof q);
    }
    double det =
        m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
    for (size_t f = 0; det < 0 && f < mesh->face_count; f++) {
        uint32_t t = mesh->faces[3 * f + 1];
        mesh->faces[3 * f + 1] = mesh->faces[3 * f + 2], mesh->faces[3 * f + 2] = t;
    }
    lucent_mesh_compute_normals(mesh);
}

/* ---- the material and the surface ---- */

static lucent_status read_material(const lucent_json_node *n, lucent_material *m)
{
    lucent_json_node mat;
    lucent_status s = lucent_json_member(n, "material", true, &mat);
    if (s != LUCENT_OK) return s;
    if (cJSON_IsObject(mat.json)) {
        s = material_read_json(&mat, "material", m);
    } else if (!cJSON_IsString(mat.json)) {
        return lucent_json_fail(&mat, NULL, LUCENT_ERR_PARSE, "expected a preset name, a file or a material object");
    } else if (lucent_material_resolve(mat.json->valuestring, m) != LUCENT_OK) {
        return lucent_json_fail(&mat, NULL, LUCENT_ERR_PARSE, "%s", lucent_last_error());
    }
    /* a spectral skin: its equivalent medium for the tracer and the coefficient readers (lucent/skin.h) */
    if (s == LUCENT_OK && lucent_skin_resolve(m) != LUCENT_OK)
        return lucent_json_fail(&mat, NULL, LUCENT_ERR_PARSE, "%s", lucent_last_error());
    return s;
}

/* Latitude-longitude coordinates about the bounding-box centre of the mesh as loaded. */
static lucent_status make_texcoords(lucent_scene_object *o)
{
    const lucent_mesh *m = o->mesh;
    o->texcoords = malloc(2 * m->vertex_count * sizeof *o->texcoords);
    if (!o->texcoords) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, c[3];
    for (size_t v = 0; v < m->vertex_count; v++)
        for (int i = 0; i < 3; i++)
            lo[i] = fmin(lo[i], m->positions[3 * v + i]), hi[i] = fmax(hi[i], m->positions[3 * v + i]);
    for (int i = 0; i < 3; i++) c[i] = 0.5 * (lo[i] + hi[i]);
    for (size_t v = 0; v < m->vertex_count; v++) {
        v3 d = v3_normalize(v3_sub(v3_load(m->positions + 3 * v), v3_load(c)));
        o->texcoords[2 * v] = 0.5 + atan2(d.z, d.x) / (2 * M_PI);
        o->texcoords[2 * v + 1] = acos(fmax(-1, fmin(1, d.y))) / M_PI;
    }
    return LUCENT_OK;
}

static lucent_status read_albedo(const lucent_json_node *n, const char *base_dir, bool skip, lucent_scene_object *o)
{
    lucent_material_derived d;
    lucent_material_derive(&o->material, &d);
    memcpy(o->albedo, d.rd, sizeof o->albedo);
    lucent_status s = LUCENT_OK;
    if (lucent_json_has(n, "albedo") && lucent_json_has(n, "albedo_texture"))
        return lucent_json_fail(n, "albedo", LUCENT_ERR_PARSE, "give albedo or albedo_texture, not both");
    if (lucent_json_has(n, "albedo")) {
        o->albedo_source = LUCENT_ALBEDO_COLOR;
        s = lucent_json_numbers(n, "albedo", 3, true, o->albedo);
        for (int c = 0; c < 3 && s == LUCENT_OK; c++)
            if (!(o->albedo[c] >= 0 && o->albedo[c] <= 1))
                s = lucent_json_fail(n, "albedo", LUCENT_ERR_PARSE, "must be in [0, 1], got %g", o->albedo[c]);
    } else if (lucent_json_has(n, "albedo_texture")) {
        const char *file;
        char path[LUCENT_SCENE_PATH_SIZE];
        o->albedo_source = LUCENT_ALBEDO_TEXTURE;
        s = lucent_json_string(n, "albedo_texture", &file);
        join_path(base_dir, file, path, sizeof path);
        if (s == LUCENT_OK && !skip && lucent_image_load(path, &o->albedo_texture) != LUCENT_OK)
            s = lucent_json_fail(n, "albedo_texture", LUCENT_ERR_PARSE, "%s", lucent_last_error());
        if (s == LUCENT_OK && o->mesh) s = make_texcoords(o);
    }
    return s;
}

static lucent_status read_surface(const lucent_json_node *n, lucent_scene_object *o)
{
    double f0 = lucent_fresnel_dielectric(1.0, o->material.eta, NULL); /* ((eta - 1) / (eta + 1))^2 */
    lucent_status s = scene_read_range(n, "roughness", 0.3, 0, 1, &o->roughness);
    if (s == LUCENT_OK) s = scene_read_range(n, "specular_f0", f0, 0, 1, &o->specular_f0);
    if (s == LUCENT_OK) s = scene_read_range(n, "sss_strength", 1, 0, 1, &o->sss_strength);
    if (s == LUCENT_OK) s = lucent_json_bool_or(n, "visible", true, &o->visible);
    if (s == LUCENT_OK) s = lucent_json_bool_or(n, "as_points", false, &o->as_points);
    o->sigma0_set = lucent_json_has(n, "sigma0");
    if (s == LUCENT_OK && o->sigma0_set) s = lucent_json_numbers(n, "sigma0", 3, true, o->sigma0);
    for (int c = 0; c < 3 && s == LUCENT_OK && o->sigma0_set; c++)
        if (!(o->sigma0[c] >= 0)) s = lucent_json_fail(n, "sigma0", LUCENT_ERR_PARSE, "must be >= 0 (mm)");
    return s;
}

lucent_status scene_read_object(const lucent_json_node *n, const char *base_dir, bool skip_meshes,
                                scene_gltf_cache *cache, lucent_scene_object *o)
{
    const char *name;
    memset(o, 0, sizeof *o);
    lucent_status s = lucent_json_check_keys(n, k_object_keys);
    if (s == LUCENT_OK) s = lucent_json_string_or(n, "name", "", &name);
    if (s == LUCENT_OK) snprintf(o->name, sizeof o->name, "%s", name);
    if (s == LUCENT_OK) s = scene_read_range(n, "mm_per_unit", 1, 1e-12, 1e12, &o->mm_per_unit);
    if (s == LUCENT_OK) s = read_transform(n, o->mm_per_unit, o->to_world);
    if (s == LUCENT_OK) s = read_material(n, &o->material);
    if (s == LUCENT_OK) s = read_surface(n, o);
    if (s == LUCENT_OK)
        s = lucent_json_has(n, "points") ? load_points(n, base_dir, skip_meshes, o)
                                         : load_mesh(n, base_dir, skip_meshes, cache, o);
    if (s == LUCENT_OK) s = subdivide(n, o);
    if (s == LUCENT_OK) s = read_albedo(n, base_dir, skip_meshes, o);
    if (s == LUCENT_OK && o->points)
        place_points(o);
    else if (s == LUCENT_OK && o->mesh)
        transform_mesh(o->mesh, o->to_world);
    if (s == LUCENT_OK && o->mesh) s = check_placed(n, o->mesh);
    if (s == LUCENT_OK && !o->name[0]) snprintf(o->name, sizeof o->name, "%s", o->material.name);
    if (s != LUCENT_OK) scene_object_free(o);
    return s;
}

void scene_object_free(lucent_scene_object *o)
{
    lucent_mesh_destroy(o->mesh);
    lucent_surfels_destroy(o->points);
    o->points = NULL;
    lucent_image_destroy(o->albedo_texture);
    free(o->texcoords);
    o->mesh = NULL, o->albedo_texture = NULL, o->texcoords = NULL;
}
