/* Wavefront OBJ and glTF 2.0 output with texture coordinates (lucent mesh-uv). Both atomic. */
#include <stdlib.h>
#include <string.h>

#include "mesh/gltf.h"
#include "mesh/internal.h"

static lucent_status finish(lucent_atomic_file *af, FILE *f, const char *path)
{
    if (ferror(f)) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}

lucent_status lucent_mesh_write_obj(const char *path, const lucent_mesh *m)
{
    lucent_atomic_file *af;
    FILE *f;
    lucent_status s = lucent_atomic_open(path, &af, &f);
    if (s != LUCENT_OK) return s;
    fprintf(f, "# written by Lucent %s: %zu vertices, %zu faces%s\n", LUCENT_VERSION_STRING, m->vertex_count,
            m->face_count, m->uvs ? ", texture coordinates per corner" : "");
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *p = m->positions + 3 * v;
        fprintf(f, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    }
    for (size_t v = 0; v < m->vertex_count; v++) {
        const double *n = m->normals + 3 * v;
        fprintf(f, "vn %.6g %.6g %.6g\n", n[0], n[1], n[2]);
    }
    for (size_t i = 0; m->uvs && i < 3 * m->face_count; i++)
        fprintf(f, "vt %.9g %.9g\n", m->uvs[2 * i], m->uvs[2 * i + 1]);
    for (size_t t = 0; t < m->face_count; t++) {
        const uint32_t *c = m->faces + 3 * t;
        if (m->uvs)
            fprintf(f, "f %u/%zu/%u %u/%zu/%u %u/%zu/%u\n", c[0] + 1, 3 * t + 1, c[0] + 1, c[1] + 1, 3 * t + 2,
                    c[1] + 1, c[2] + 1, 3 * t + 3, c[2] + 1);
        else
            fprintf(f, "f %u//%u %u//%u %u//%u\n", c[0] + 1, c[0] + 1, c[1] + 1, c[1] + 1, c[2] + 1, c[2] + 1);
    }
    return finish(af, f, path);
}

/* ---- glTF: one buffer (positions, normals, texture coordinates as floats, indices as uint32) ---- */

static char *base64(const unsigned char *data, size_t n)
{
    static const char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    static const char prefix[] = "data:application/octet-stream;base64,";
    char *out = malloc(sizeof prefix + (n + 2) / 3 * 4), *o = out;
    if (!out) return NULL;
    memcpy(o, prefix, sizeof prefix - 1), o += sizeof prefix - 1;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t w =
            (uint32_t)data[i] << 16 | (i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0) | (i + 2 < n ? data[i + 2] : 0);
        *o++ = k[w >> 18 & 63], *o++ = k[w >> 12 & 63];
        *o++ = i + 1 < n ? k[w >> 6 & 63] : '=', *o++ = i + 2 < n ? k[w & 63] : '=';
    }
    *o = '\0';
    return out;
}

/* The vertex data as glTF wants it: vertices split where texture coordinates differ. */
typedef struct gltf_pack {
    unsigned char *buf;
    size_t nv, nf, bytes;
    double lo[3], hi[3];
} gltf_pack;

static lucent_status pack_mesh(const lucent_mesh *m, double scale, gltf_pack *p)
{
    lucent_uv_split sp = {0};
    size_t nv = m->vertex_count, stride = m->uvs ? 32 : 24;
    if (m->uvs) {
        lucent_status s = lucent_mesh_uv_split(m, &sp);
        if (s != LUCENT_OK) return s;
        nv = sp.count;
    }
    *p = (gltf_pack){.nv = nv, .nf = m->face_count, .bytes = nv * stride + m->face_count * 12};
    p->buf = malloc(p->bytes + 1);
    if (!p->buf) {
        lucent_uv_split_free(&sp);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory writing glTF");
    }
    float *pos = (float *)p->buf, *nrm = pos + 3 * nv, *tex = nrm + 3 * nv;
    for (int k = 0; k < 3; k++) p->lo[k] = INFINITY, p->hi[k] = -INFINITY;
    for (size_t v = 0; v < nv; v++) {
        size_t o = m->uvs ? sp.vertex[v] : v;
        for (int k = 0; k < 3; k++) {
            pos[3 * v + k] = (float)(scale * m->positions[3 * o + k]), nrm[3 * v + k] = (float)m->normals[3 * o + k];
            p->lo[k] = fmin(p->lo[k], pos[3 * v + k]), p->hi[k] = fmax(p->hi[k], pos[3 * v + k]);
        }
        if (m->uvs) tex[2 * v] = (float)sp.uv[2 * v], tex[2 * v + 1] = (float)(1 - sp.uv[2 * v + 1]);
    }
    uint32_t *idx = (uint32_t *)(m->uvs ? tex + 2 * nv : tex);
    memcpy(idx, m->uvs ? sp.faces : m->faces, p->nf * 3 * sizeof *idx);
    lucent_uv_split_free(&sp);
    return LUCENT_OK;
}

/* Appends an item to root's array `key` (made when absent); returns the item's index or -1. */
static int append(cJSON *root, const char *key, cJSON *item)
{
    cJSON *list = cJSON_GetObjectItemCaseSensitive(root, key);
    if (!list) list = cJSON_AddArrayToObject(root, key);
    if (!item || !list || !cJSON_AddItemToArray(list, item)) {
        cJSON_Delete(item);
        return -1;
    }
    return cJSON_GetArraySize(list) - 1;
}

static int add_view(cJSON *root, size_t offset, size_t length, int target)
{
    cJSON *v = cJSON_CreateObject();
    if (v &&
        !(cJSON_AddNumberToObject(v, "buffer", 0) && cJSON_AddNumberToObject(v, "byteOffset", (double)offset) &&
          cJSON_AddNumberToObject(v, "byteLength", (double)length) && cJSON_AddNumberToObject(v, "target", target)))
        cJSON_Delete(v), v = NULL;
    return append(root, "bufferViews", v);
}

static int add_accessor(cJSON *root, int view, int type, size_t count, const char *kind, const gltf_pack *bounds)
{
    cJSON *a = cJSON_CreateObject();
    bool ok = a && cJSON_AddNumberToObject(a, "bufferView", view) &&
              cJSON_AddNumberToObject(a, "componentType", type) && cJSON_AddNumberToObject(a, "count", (double)count) &&
              cJSON_AddStringToObject(a, "type", kind);
    if (ok && bounds)
        ok = lucent_json_add_numbers(a, "min", bounds->lo, 3) && lucent_json_add_numbers(a, "max", bounds->hi, 3);
    if (!ok) cJSON_Delete(a), a = NULL;
    return view < 0 ? (cJSON_Delete(a), -1) : append(root, "accessors", a);
}

lucent_status gltf_add_mesh(cJSON *root, const lucent_mesh *m, double scale, int material, int *index)
{
    gltf_pack p;
    lucent_status s = pack_mesh(m, scale, &p);
    if (s != LUCENT_OK) return s;
    char *uri = base64(p.buf, p.bytes);
    free(p.buf);
    cJSON *buffer = cJSON_CreateObject();
    bool ok = uri && buffer && cJSON_AddNumberToObject(buffer, "byteLength", (double)p.bytes) &&
              cJSON_AddStringToObject(buffer, "uri", uri) && append(root, "buffers", buffer) == 0;
    free(uri);
    if (!ok) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory writing glTF");
    size_t nv = p.nv, at = 24 * nv;
    int pos = add_accessor(root, add_view(root, 0, 12 * nv, 34962), 5126, nv, "VEC3", &p);
    int nrm = add_accessor(root, add_view(root, 12 * nv, 12 * nv, 34962), 5126, nv, "VEC3", NULL);
    int tex = m->uvs ? add_accessor(root, add_view(root, at, 8 * nv, 34962), 5126, nv, "VEC2", NULL) : 0;
    at += m->uvs ? 8 * nv : 0;
    int idx = add_accessor(root, add_view(root, at, 12 * p.nf, 34963), 5125, 3 * p.nf, "SCALAR", NULL);
    cJSON *mesh = cJSON_CreateObject(), *prims = mesh ? cJSON_AddArrayToObject(mesh, "primitives") : NULL;
    cJSON *prim = cJSON_CreateObject(), *attr = prim ? cJSON_AddObjectToObject(prim, "attributes") : NULL;
    ok = pos >= 0 && nrm >= 0 && tex >= 0 && idx >= 0 && prims && attr &&
         cJSON_AddNumberToObject(attr, "POSITION", pos) && cJSON_AddNumberToObject(attr, "NORMAL", nrm) &&
         (!m->uvs || cJSON_AddNumberToObject(attr, "TEXCOORD_0", tex)) &&
         cJSON_AddNumberToObject(prim, "indices", idx) && cJSON_AddNumberToObject(prim, "mode", 4) &&
         (material < 0 || cJSON_AddNumberToObject(prim, "material", material)) && cJSON_AddItemToArray(prims, prim);
    if (!ok) cJSON_Delete(prim), prim = NULL;
    *index = ok ? append(root, "meshes", mesh) : (cJSON_Delete(mesh), -1);
    return *index >= 0 ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory writing glTF");
}

lucent_status lucent_mesh_write_gltf(const char *path, const lucent_mesh *m)
{
    char generator[64];
    snprintf(generator, sizeof generator, "Lucent %s", LUCENT_VERSION_STRING);
    cJSON *root = cJSON_CreateObject(), *asset = root ? cJSON_AddObjectToObject(root, "asset") : NULL;
    bool ok = asset && cJSON_AddStringToObject(asset, "version", "2.0") &&
              cJSON_AddStringToObject(asset, "generator", generator) && cJSON_AddNumberToObject(root, "scene", 0);
    cJSON *scene = cJSON_CreateObject(), *nodes = scene ? cJSON_AddArrayToObject(scene, "nodes") : NULL;
    ok = nodes && cJSON_AddItemToArray(nodes, cJSON_CreateNumber(0)) && ok;
    ok = append(root, "scenes", scene) == 0 && ok; /* append owns the item, also when it fails */
    cJSON *node = cJSON_CreateObject();
    ok = node && cJSON_AddNumberToObject(node, "mesh", 0) && ok;
    ok = append(root, "nodes", node) == 0 && ok;
    int mesh = -1;
    lucent_status s =
        ok ? gltf_add_mesh(root, m, 1, -1, &mesh) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (s == LUCENT_OK) s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}
