/* Lucent's OBJ reader (Wavefront's geometry format): `v x y z`, `vt u v` and `f a b c ...` lines, indices
 * 1-based or negative (relative to the vertices so far), in the forms a, a/t, a/t/n and a//n; polygons are
 * fan-triangulated. Texture coordinates become the mesh's corner coordinates when every face corner
 * names one (a corner without one, or naming none that exists, drops them all; the geometry stands). Everything else (vn, l, p, o, g, s, usemtl, and mtllib,
 * whose file is never opened) is ignored. Streaming through mesh/reader.h, every index checked, errors name the line. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"
#include "mesh/reader.h"

typedef struct grow {
    void *data;
    size_t count, cap, size;
} grow;

static int grow_push(grow *g, const void *item)
{
    if (g->count == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 4096;
        void *d = realloc(g->data, cap * g->size);
        if (!d) return 0;
        g->data = d, g->cap = cap;
    }
    memcpy((char *)g->data + g->count * g->size, item, g->size);
    g->count++;
    return 1;
}

static lucent_status parse_error(const lucent_reader *r, const char *what)
{
    return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: %s", r->name, (unsigned long long)r->line, what);
}

static lucent_status read_obj(lucent_reader *r, lucent_mesh **dest)
{
    grow pos = {.size = 3 * sizeof(double)}, tri = {.size = 3 * sizeof(uint32_t)};
    grow tex = {.size = 2 * sizeof(double)}, corner = {.size = 6 * sizeof(double)};
    bool all_tex = true; /* every corner so far named a texture coordinate */
    uint32_t *poly = NULL, *poly_t = NULL;
    size_t poly_cap = 0;
    lucent_status s = LUCENT_OK;
    uint64_t limit = lucent_mesh_read_limit();
    for (;;) {
        char *line;
        size_t len;
        if ((s = lucent_reader_line(r, &line, &len)) != LUCENT_OK || !line) break;
        const char *p = line, *end = line + len;
        while (p < end && (*p == ' ' || *p == '\t')) p++;
        if (p + 1 < end && p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            double v[3];
            p += 2;
            for (int k = 0; k < 3; k++)
                if (!lucent_parse_double(&p, end, &v[k]) || !isfinite(v[k])) {
                    s = parse_error(r, "a vertex needs three finite coordinates");
                    goto done;
                }
            /* A fourth value (w) or vertex colours may follow: ignored. */
            if (pos.count >= UINT32_MAX) {
                s = lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: more than 4294967295 vertices", r->name);
                goto done;
            }
            if (!grow_push(&pos, v)) goto oom;
        } else if (p + 2 < end && p[0] == 'v' && p[1] == 't' && (p[2] == ' ' || p[2] == '\t')) {
            double t[2] = {0, 0};
            p += 3;
            for (int k = 0; k < 2; k++)
                if (!lucent_parse_double(&p, end, &t[k]) || !isfinite(t[k])) {
                    s = parse_error(r, "a texture coordinate needs two finite values");
                    goto done;
                }
            if (tex.count >= UINT32_MAX) {
                s = lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: more than 4294967295 texture coordinates", r->name);
                goto done;
            }
            if (!grow_push(&tex, t)) goto oom;
        } else if (p + 1 < end && p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
            p += 2;
            size_t n = 0;
            for (;;) {
                while (p < end && (*p == ' ' || *p == '\t')) p++;
                if (p >= end) break;
                int64_t idx;
                const char *q = p;
                while (q < end && *q != '/' && *q != ' ' && *q != '\t') q++;
                const char *num = p;
                if (!lucent_parse_int64(&num, q, &idx) || num != q) {
                    s = parse_error(r, "a face index is not an integer");
                    goto done;
                }
                /* /t (the texture coordinate), then /n: skipped. */
                int64_t tidx = 0;
                if (q < end && *q == '/' && q + 1 < end && q[1] != '/') {
                    const char *t0 = q + 1, *t1 = t0;
                    while (t1 < end && *t1 != '/' && *t1 != ' ' && *t1 != '\t') t1++;
                    /* a texture index that names no coordinate drops the coordinates (the geometry stands) */
                    int64_t have_t = (int64_t)tex.count, tv = -1;
                    if (lucent_parse_int64(&t0, t1, &tidx) && t0 == t1 && tidx != 0)
                        tv = tidx > 0 ? tidx - 1 : have_t + tidx;
                    tidx = tv >= 0 && tv < have_t ? tv + 1 : 0;
                }
                while (q < end && *q != ' ' && *q != '\t') q++;
                p = q;
                int64_t have = (int64_t)pos.count;
                int64_t v = idx > 0 ? idx - 1 : idx < 0 ? have + idx : -1;
                if (v < 0 || v >= have) {
                    char what[160];
                    snprintf(what, sizeof what, "face index %lld does not name a vertex (%lld defined so far)",
                             (long long)idx, (long long)have);
                    s = parse_error(r, what);
                    goto done;
                }
                if (n == poly_cap) {
                    size_t cap = poly_cap ? 2 * poly_cap : 64;
                    if (cap > ((size_t)1 << 20)) {
                        s = parse_error(r, "a face with more than a million vertices");
                        goto done;
                    }
                    uint32_t *g = realloc(poly, cap * sizeof *g);
                    if (!g) goto oom;
                    poly = g;
                    g = realloc(poly_t, cap * sizeof *g);
                    if (!g) goto oom;
                    poly_t = g, poly_cap = cap;
                }
                poly_t[n] = (uint32_t)tidx; /* 0: none, else the coordinate + 1 */
                all_tex = all_tex && tidx != 0;
                poly[n++] = (uint32_t)v;
            }
            if (n < 3) {
                s = parse_error(r, "a face needs 3 or more vertices");
                goto done;
            }
            for (size_t j = 1; j + 1 < n; j++) {
                uint32_t t[3] = {poly[0], poly[j], poly[j + 1]}, c[3] = {poly_t[0], poly_t[j], poly_t[j + 1]};
                if (!grow_push(&tri, t)) goto oom;
                double uv[6] = {0};
                for (int k = 0; k < 3 && all_tex; k++) memcpy(uv + 2 * k, (double *)tex.data + 2 * (c[k] - 1), 16);
                if (all_tex && !grow_push(&corner, uv)) goto oom;
            }
        }
        /* Anything else: a comment, vt, vn, l, p, o, g, s, usemtl, mtllib (never opened), ... */
        if ((uint64_t)pos.count + tex.count + tri.count > limit) {
            s = lucent_error(LUCENT_ERR_PARSE,
                             "%s: line %llu: more than %llu vertices, texture coordinates and triangles: above the "
                             "read limit (the environment variable LUCENT_MESH_MAX_ELEMENTS raises it)",
                             r->name, (unsigned long long)r->line, (unsigned long long)limit);
            goto done;
        }
    }
done:
    if (s == LUCENT_OK && tri.count == 0)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: no faces in the file (%zu vertices)", r->name, pos.count);
    if (s == LUCENT_OK) s = lucent_mesh_create(pos.count, tri.count, dest);
    if (s == LUCENT_OK) {
        memcpy((*dest)->positions, pos.data, pos.count * pos.size);
        memcpy((*dest)->faces, tri.data, tri.count * tri.size);
        if (all_tex && corner.count == tri.count) (*dest)->uvs = corner.data, corner.data = NULL;
    }
    free(pos.data);
    free(tri.data);
    free(tex.data), free(corner.data);
    free(poly), free(poly_t);
    return s;
oom:
    s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
    goto done;
}

lucent_status lucent_mesh_obj_read(lucent_reader *r, lucent_mesh **dest)
{
    *dest = NULL;
    return read_obj(r, dest);
}
