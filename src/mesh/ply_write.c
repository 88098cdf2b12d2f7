/* Binary little-endian PLY output, with optional colours and scalar properties per vertex. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

static void put_f32(FILE *f, double x)
{
    float v = (float)x;
    unsigned char b[4];
    uint32_t u;
    memcpy(&u, &v, 4);
    for (int i = 0; i < 4; i++) b[i] = (unsigned char)(u >> (8 * i));
    fwrite(b, 1, 4, f);
}

static void put_u32(FILE *f, uint32_t u)
{
    unsigned char b[4];
    for (int i = 0; i < 4; i++) b[i] = (unsigned char)(u >> (8 * i));
    fwrite(b, 1, 4, f);
}

static void write_header(FILE *f, const lucent_mesh *m, const lucent_mesh_ply_extra *x)
{
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment written by Lucent %s\n", LUCENT_VERSION_STRING);
    fprintf(f, "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n", m->vertex_count);
    fprintf(f, "property float nx\nproperty float ny\nproperty float nz\n");
    if (x && x->colors) fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    for (int i = 0; x && i < x->scalar_count; i++) fprintf(f, "property float %s\n", x->names[i]);
    fprintf(f, "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n", m->face_count);
}

static void write_body(FILE *f, const lucent_mesh *m, const lucent_mesh_ply_extra *x)
{
    for (size_t v = 0; v < m->vertex_count; v++) {
        for (int k = 0; k < 3; k++) put_f32(f, m->positions[3 * v + k]);
        for (int k = 0; k < 3; k++) put_f32(f, m->normals[3 * v + k]);
        if (x && x->colors) fwrite(x->colors + 3 * v, 1, 3, f);
        for (int i = 0; x && i < x->scalar_count; i++) put_f32(f, x->values[i][v]);
    }
    for (size_t t = 0; t < m->face_count; t++) {
        fputc(3, f);
        for (int j = 0; j < 3; j++) put_u32(f, m->faces[3 * t + j]);
    }
}

lucent_status lucent_mesh_write_ply(const char *path, const lucent_mesh *mesh, const lucent_mesh_ply_extra *extra)
{
    lucent_atomic_file *af;
    FILE *f;
    lucent_status s = lucent_atomic_open(path, &af, &f);
    if (s != LUCENT_OK) return s;
    write_header(f, mesh, extra);
    write_body(f, mesh, extra);
    if (ferror(f)) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}
