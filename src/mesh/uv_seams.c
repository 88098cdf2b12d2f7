/* Texture seams for texture-space diffusion (d'Eon, Luebke & Enderton 2007, GPU Gems 3 14.4.3): for
 * the texels just outside a chart, where the same surface point lies in the chart across the seam.
 *
 * A seam edge is an edge whose two faces give its corners different texture coordinates (two charts,
 * or one chart meeting itself, as on a latitude-longitude sphere). Seen from face f (chart A) the
 * edge runs from corner a to corner b, e = (b - a) / |b - a| in A's texels, n its normal pointing out
 * of f; seen from the face g across it (chart B) the same corners give e' and n' pointing into g.
 * A texel centre x near the edge, x = a + t e + h n, is the surface point reached by walking t along
 * the edge and h across it; in B that walk is a' + s (t e' + h n'), s = |b' - a'| / |b - a| the ratio
 * of the two charts' texel densities along the edge (the edge's length in 3-D is one). The map is the
 * unfolding of the two faces into one plane about their edge, exact on a flat surface; its derivative
 * J = s (e' e^T + n' n^T) carries a direction in A's texels to B's. Each texel within `reach` texels
 * of a seam edge keeps the map of its nearest seam edge. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

typedef struct seam_candidate {
    uint64_t texel;  /* y size + x */
    double distance; /* to the edge, texels */
    lucent_uv_seam_texel value;
} seam_candidate;

static int cmp_candidate(const void *a, const void *b)
{
    const seam_candidate *x = a, *y = b;
    if (x->texel != y->texel) return x->texel < y->texel ? -1 : 1;
    return (x->distance > y->distance) - (x->distance < y->distance);
}

typedef struct seam_list {
    seam_candidate *at;
    size_t count, cap;
} seam_list;

static bool list_push(seam_list *l, const seam_candidate *c)
{
    if (l->count == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 1024;
        seam_candidate *n = realloc(l->at, cap * sizeof *n);
        if (!n) return false;
        l->at = n, l->cap = cap;
    }
    l->at[l->count++] = *c;
    return true;
}

/* The texture coordinates (texels) of vertex v in face f, NULL when f has no such corner. */
static const double *corner_uv(const lucent_mesh *m, uint32_t f, uint32_t v)
{
    for (int k = 0; k < 3; k++)
        if (m->faces[3 * f + (uint32_t)k] == v) return m->uvs + 6 * f + 2 * k;
    return NULL;
}

/* One side of an edge in texels: origin a, unit direction e, unit normal n toward (into = true) or
 * away from the face's third corner c; the edge's length. */
static double edge_frame(const double a[2], const double b[2], const double c[2], int size, bool into, double o[2],
                         double e[2], double n[2])
{
    double dx = (b[0] - a[0]) * size, dy = (b[1] - a[1]) * size, len = hypot(dx, dy);
    if (!(len > 0)) return 0;
    o[0] = a[0] * size, o[1] = a[1] * size, e[0] = dx / len, e[1] = dy / len;
    n[0] = -e[1], n[1] = e[0];
    double side = n[0] * (c[0] * size - o[0]) + n[1] * (c[1] * size - o[1]); /* > 0: c on n's side */
    if ((side > 0) != into) n[0] = -n[0], n[1] = -n[1];
    return len;
}

/* The candidates of the texels within reach of the edge from corner k of face f to the face g across. */
static bool edge_candidates(const lucent_mesh *m, const uint32_t *chart, uint32_t f, int k, uint32_t g, int size,
                            double reach, seam_list *out)
{
    uint32_t va = m->faces[3 * f + (uint32_t)k], vb = m->faces[3 * f + (uint32_t)(k + 1) % 3];
    uint32_t vc = m->faces[3 * f + (uint32_t)(k + 2) % 3];
    const double *ua = corner_uv(m, f, va), *ub = corner_uv(m, f, vb), *uc = corner_uv(m, f, vc);
    const double *wa = corner_uv(m, g, va), *wb = corner_uv(m, g, vb), *wc = NULL;
    for (int j = 0; j < 3; j++)
        if (m->faces[3 * g + (uint32_t)j] != va && m->faces[3 * g + (uint32_t)j] != vb) wc = m->uvs + 6 * g + 2 * j;
    if (!wa || !wb || !wc) return true;
    double o[2], e[2], n[2], o2[2], e2[2], n2[2];
    double la = edge_frame(ua, ub, uc, size, false, o, e, n), lb = edge_frame(wa, wb, wc, size, true, o2, e2, n2);
    if (!(la > 0) || !(lb > 0)) return true;
    double s = lb / la, lo[2], hi[2];
    for (int i = 0; i < 2; i++) {
        lo[i] = fmax(0, floor(fmin(o[i], o[i] + la * e[i]) - reach));
        hi[i] = fmin(size - 1, ceil(fmax(o[i], o[i] + la * e[i]) + reach));
    }
    for (double y = lo[1]; y <= hi[1]; y++)
        for (double x = lo[0]; x <= hi[0]; x++) {
            double px = x + 0.5 - o[0], py = y + 0.5 - o[1], t = px * e[0] + py * e[1], h = px * n[0] + py * n[1];
            double tc = fmin(fmax(t, 0), la), d = hypot(px - tc * e[0], py - tc * e[1]);
            if (d > reach || h < -1) continue; /* far, or well inside the face */
            seam_candidate c = {(uint64_t)y * (uint64_t)size + (uint64_t)x, d, {0}};
            c.value.x = (uint32_t)x, c.value.y = (uint32_t)y, c.value.chart = chart[f], c.value.across = chart[g];
            c.value.target[0] = (float)(o2[0] + s * (t * e2[0] + h * n2[0]));
            c.value.target[1] = (float)(o2[1] + s * (t * e2[1] + h * n2[1]));
            /* J = s (e' e^T + n' n^T), row major */
            c.value.jacobian[0] = (float)(s * (e2[0] * e[0] + n2[0] * n[0]));
            c.value.jacobian[1] = (float)(s * (e2[0] * e[1] + n2[0] * n[1]));
            c.value.jacobian[2] = (float)(s * (e2[1] * e[0] + n2[1] * n[0]));
            c.value.jacobian[3] = (float)(s * (e2[1] * e[1] + n2[1] * n[1]));
            if (!list_push(out, &c)) return false;
        }
    return true;
}

static bool is_seam(const lucent_mesh *m, uint32_t f, int k, uint32_t g)
{
    uint32_t va = m->faces[3 * f + (uint32_t)k], vb = m->faces[3 * f + (uint32_t)(k + 1) % 3];
    const double *wa = corner_uv(m, g, va), *wb = corner_uv(m, g, vb);
    const double *ua = m->uvs + 6 * f + 2 * k, *ub = m->uvs + 6 * f + 2 * ((k + 1) % 3);
    return wa && wb && (wa[0] != ua[0] || wa[1] != ua[1] || wb[0] != ub[0] || wb[1] != ub[1]);
}

lucent_status lucent_mesh_uv_seams(const lucent_mesh *m, int size, double reach, lucent_uv_seams *dest)
{
    *dest = (lucent_uv_seams){0};
    if (!m->uvs) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "the mesh has no texture coordinates");
    if (size < 1 || size > 16384 || !(reach > 0 && reach <= 64))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "seams: size must be 1..16384 and reach 0..64 texels");
    uint32_t *next = malloc((3 * m->face_count + 1) * sizeof *next), *chart = malloc((m->face_count + 1) * sizeof *chart);
    seam_list l = {0};
    lucent_status s = next && chart ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the seams");
    if (s == LUCENT_OK) s = mesh_face_neighbours(m, next);
    if (s == LUCENT_OK) s = lucent_mesh_uv_charts(m, chart, NULL);
    for (size_t i = 0; s == LUCENT_OK && i < 3 * m->face_count; i++) {
        uint32_t f = (uint32_t)(i / 3), g = next[i];
        int k = (int)(i % 3);
        if (g != UINT32_MAX && is_seam(m, f, k, g) && !edge_candidates(m, chart, f, k, g, size, reach, &l))
            s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the seams");
    }
    if (s == LUCENT_OK && l.count) qsort(l.at, l.count, sizeof *l.at, cmp_candidate);
    size_t n = 0;
    for (size_t i = 0; s == LUCENT_OK && i < l.count; i++) /* the nearest edge of each texel */
        if (i == 0 || l.at[i].texel != l.at[i - 1].texel) l.at[n++] = l.at[i];
    dest->texels = s == LUCENT_OK ? malloc((n + 1) * sizeof *dest->texels) : NULL;
    if (s == LUCENT_OK && !dest->texels) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for the seams");
    for (size_t i = 0; s == LUCENT_OK && i < n; i++) dest->texels[i] = l.at[i].value;
    if (s == LUCENT_OK) dest->count = n;
    free(l.at), free(next), free(chart);
    return s;
}

void lucent_uv_seams_free(lucent_uv_seams *seams)
{
    free(seams->texels);
    *seams = (lucent_uv_seams){0};
}
