/* The curvature CSV: rows made with the library's own "%.9g" (src/base/format_g.c, the same
 * characters as printf, several times faster), written in blocks of about 1 MiB. */
#include <stdio.h>
#include <stdlib.h>

#include "base/format_g.h"
#include "mesh/internal.h"

enum { BLOCK = 1 << 20, ROW_MAX = 20 + 7 * LUCENT_FORMAT_G_MAX + 8 };

/* "v,x,y,z,k1,k2,mean,gauss,flags\n" of vertex v at dest; returns its length. */
static size_t format_row(char *dest, const lucent_mesh *m, const lucent_curvature *c, size_t v)
{
    const double values[7] = {
        m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2], c->k1[v], c->k2[v], c->mean[v],
        c->gauss[v]};
    char *o = dest + lucent_format_u64(dest, v);
    for (int k = 0; k < 7; k++) *o++ = ',', o += lucent_format_g(o, values[k], 9);
    *o++ = ',', o += lucent_format_u64(o, c->flags[v]);
    *o++ = '\n';
    return (size_t)(o - dest);
}

lucent_status lucent_curvature_write_csv(const char *path, const lucent_mesh *mesh, const lucent_curvature *curv)
{
    char *block = malloc(BLOCK + ROW_MAX);
    if (!block) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    lucent_atomic_file *af;
    FILE *f;
    lucent_status s = lucent_atomic_open(path, &af, &f);
    if (s != LUCENT_OK) {
        free(block);
        return s;
    }
    fputs("vertex,x,y,z,k1,k2,mean,gauss,flags\n", f);
    size_t len = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        len += format_row(block + len, mesh, curv, v);
        if (len >= BLOCK || v + 1 == mesh->vertex_count) fwrite(block, 1, len, f), len = 0;
    }
    free(block);
    if (ferror(f)) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}
