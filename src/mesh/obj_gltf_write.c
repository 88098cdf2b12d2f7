/* Wavefront OBJ and glTF 2.0 output with texture coordinates (lucent mesh-uv). Both atomic. */
#include <stdlib.h>
#include <string.h>

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

static void put_base64(FILE *f, const unsigned char *data, size_t n)
{
    static const char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t w =
            (uint32_t)data[i] << 16 | (i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0) | (i + 2 < n ? data[i + 2] : 0);
        char out[4] = {k[w >> 18 & 63], k[w >> 12 & 63], i + 1 < n ? k[w >> 6 & 63] : '=', i + 2 < n ? k[w & 63] : '='};
        fwrite(out, 1, 4, f);
    }
}

lucent_status lucent_mesh_write_gltf(const char *path, const lucent_mesh *m)
{
    lucent_uv_split sp = {0};
    size_t nv = m->vertex_count;
    if (m->uvs) {
        lucent_status s = lucent_mesh_uv_split(m, &sp);
        if (s != LUCENT_OK) return s;
        nv = sp.count;
    }
    size_t nf = m->face_count, bytes = nv * 32 + nf * 12;
    unsigned char *buf = malloc(bytes + 1);
    if (!buf) {
        lucent_uv_split_free(&sp);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    float *pos = (float *)buf, *nrm = pos + 3 * nv, *tex = nrm + 3 * nv;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < nv; v++) {
        size_t o = m->uvs ? sp.vertex[v] : v;
        for (int k = 0; k < 3; k++) {
            pos[3 * v + k] = (float)m->positions[3 * o + k], nrm[3 * v + k] = (float)m->normals[3 * o + k];
            lo[k] = fmin(lo[k], pos[3 * v + k]), hi[k] = fmax(hi[k], pos[3 * v + k]);
        }
        tex[2 * v] = m->uvs ? (float)sp.uv[2 * v] : 0, tex[2 * v + 1] = m->uvs ? (float)(1 - sp.uv[2 * v + 1]) : 0;
    }
    uint32_t *idx = (uint32_t *)(tex + 2 * nv);
    memcpy(idx, m->uvs ? sp.faces : m->faces, nf * 3 * sizeof *idx);
    lucent_uv_split_free(&sp);
    lucent_atomic_file *af;
    FILE *f;
    lucent_status s = lucent_atomic_open(path, &af, &f);
    if (s != LUCENT_OK) return free(buf), s;
    fprintf(f,
            "{\"asset\": {\"version\": \"2.0\", \"generator\": \"Lucent %s\"},\n"
            " \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 0}],\n"
            " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2}, "
            "\"indices\": 3, \"mode\": 4}]}],\n",
            LUCENT_VERSION_STRING);
    fprintf(f,
            " \"accessors\": [\n"
            "  {\"bufferView\": 0, \"componentType\": 5126, \"count\": %zu, \"type\": \"VEC3\", "
            "\"min\": [%.9g, %.9g, %.9g], \"max\": [%.9g, %.9g, %.9g]},\n"
            "  {\"bufferView\": 1, \"componentType\": 5126, \"count\": %zu, \"type\": \"VEC3\"},\n"
            "  {\"bufferView\": 2, \"componentType\": 5126, \"count\": %zu, \"type\": \"VEC2\"},\n"
            "  {\"bufferView\": 3, \"componentType\": 5125, \"count\": %zu, \"type\": \"SCALAR\"}],\n",
            nv, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], nv, nv, 3 * nf);
    fprintf(f,
            " \"bufferViews\": [\n"
            "  {\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": %zu, \"target\": 34962},\n"
            "  {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34962},\n"
            "  {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34962},\n"
            "  {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34963}],\n",
            12 * nv, 12 * nv, 12 * nv, 24 * nv, 8 * nv, 32 * nv, 12 * nf);
    fprintf(f, " \"buffers\": [{\"byteLength\": %zu, \"uri\": \"data:application/octet-stream;base64,", bytes);
    put_base64(f, buf, bytes);
    fprintf(f, "\"}]}\n");
    free(buf);
    return finish(af, f, path);
}
