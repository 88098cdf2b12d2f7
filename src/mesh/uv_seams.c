/* Texture seams for texture-space diffusion (d'Eon, Luebke & Enderton 2007, GPU Gems 3 14.4.3): for
 * the texels just outside a chart, where the same surface point lies in the chart across the seam.
 *
 * A seam edge is an edge whose two faces give its corners different texture coordinates (two charts,
 * or one chart meeting itself, as on a latitude-longitude sphere). A texel x near such an edge, seen
 * from its face f, is a point of f's plane (f's texture map extended: P = P_a + D_f (x - x_a), D_f the
 * inverse map's derivative); unfolding f's plane about the edge onto the plane of the face g across
 * (the edge's direction kept, the direction out of f across the edge turned into the direction into
 * g) and mapping that point by g's texture map gives the same surface point in g's chart:
 * y = y_a + J (x - x_a), J = D_g^+ R D_f. Exact on a flat surface whatever the two maps (turned,
 * scaled, sheared); on a curved one the unfolding of the two faces. Each texel within `reach` texels of
 * a seam edge keeps the map of its nearest seam edge. */
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

/* The derivative of face f's texture map's inverse: D (3 x 2, column major as two v3) takes a step in
 * texels to the step on the face's plane. false: degenerate in 3-D or in texture space. */
static bool face_inverse(const lucent_mesh *m, uint32_t f, int size, v3 dest[2])
{
    const double *t = m->uvs + 6 * f;
    double a = (t[2] - t[0]) * size, b = (t[4] - t[0]) * size, c = (t[3] - t[1]) * size, d = (t[5] - t[1]) * size;
    double det = a * d - b * c; /* A = [[a, b], [c, d]]: columns the corners' steps in texels */
    if (!(fabs(det) > 0)) return false;
    v3 p0 = v3_load(m->positions + 3 * m->faces[3 * f]);
    v3 e1 = v3_sub(v3_load(m->positions + 3 * m->faces[3 * f + 1]), p0);
    v3 e2 = v3_sub(v3_load(m->positions + 3 * m->faces[3 * f + 2]), p0);
    if (!(v3_length(v3_cross(e1, e2)) > 0)) return false;
    /* D = [e1 e2] A^-1, A^-1 = [[d, -b], [-c, a]] / det */
    dest[0] = v3_scale(v3_add(v3_scale(e1, d), v3_scale(e2, -c)), 1 / det);
    dest[1] = v3_scale(v3_add(v3_scale(e1, -b), v3_scale(e2, a)), 1 / det);
    return true;
}

/* The texel step that gives the 3-D step q (in the face's plane) under D: (D^T D)^-1 D^T q. */
static void step_of(const v3 d[2], v3 q, double dest[2])
{
    double g00 = v3_dot(d[0], d[0]), g01 = v3_dot(d[0], d[1]), g11 = v3_dot(d[1], d[1]), det = g00 * g11 - g01 * g01;
    double r0 = v3_dot(d[0], q), r1 = v3_dot(d[1], q);
    dest[0] = (g11 * r0 - g01 * r1) / det, dest[1] = (g00 * r1 - g01 * r0) / det;
}

/* The unit vector in the plane of edge (a, b) and corner c, perpendicular to the edge, toward c. */
static v3 toward(v3 a, v3 e, v3 c)
{
    v3 q = v3_sub(c, a);
    return v3_normalize(v3_sub(q, v3_scale(e, v3_dot(q, e))));
}

/* The candidates of the texels within reach of the edge from corner k of face f to the face g across:
 * f's plane unfolded about the edge onto g's, J = D_g^+ R D_f (R: the edge direction kept, the
 * direction out of f across the edge turned into the direction into g). */
static bool edge_candidates(const lucent_mesh *m, const uint32_t *chart, uint32_t f, int k, uint32_t g, int size,
                            double reach, seam_list *out)
{
    uint32_t va = m->faces[3 * f + (uint32_t)k], vb = m->faces[3 * f + (uint32_t)(k + 1) % 3];
    uint32_t vc = m->faces[3 * f + (uint32_t)(k + 2) % 3], vd = UINT32_MAX;
    for (int j = 0; j < 3; j++)
        if (m->faces[3 * g + (uint32_t)j] != va && m->faces[3 * g + (uint32_t)j] != vb)
            vd = m->faces[3 * g + (uint32_t)j];
    const double *ua = corner_uv(m, f, va), *ub = corner_uv(m, f, vb), *wa = corner_uv(m, g, va);
    v3 df[2], dg[2];
    if (vd == UINT32_MAX || !wa || !face_inverse(m, f, size, df) || !face_inverse(m, g, size, dg)) return true;
    v3 pa = v3_load(m->positions + 3 * va), pb = v3_load(m->positions + 3 * vb);
    v3 e = v3_normalize(v3_sub(pb, pa));
    v3 out_f = v3_neg(toward(pa, e, v3_load(m->positions + 3 * vc))),
       in_g = toward(pa, e, v3_load(m->positions + 3 * vd));
    double jac[4]; /* row major */
    for (int col = 0; col < 2; col++) {
        v3 q = df[col], turned = v3_add(v3_scale(e, v3_dot(q, e)), v3_scale(in_g, v3_dot(q, out_f)));
        double r[2];
        step_of(dg, turned, r);
        jac[col] = r[0], jac[2 + col] = r[1];
    }
    double o[2] = {ua[0] * size, ua[1] * size}, o2[2] = {wa[0] * size, wa[1] * size};
    double ex = (ub[0] - ua[0]) * size, ey = (ub[1] - ua[1]) * size, la = hypot(ex, ey);
    if (!(la > 0)) return true;
    ex /= la, ey /= la;
    double side = (ex * ((corner_uv(m, f, vc)[1]) * size - o[1]) - ey * ((corner_uv(m, f, vc)[0]) * size - o[0]));
    double lo[2], hi[2];
    for (int i = 0; i < 2; i++) {
        double end = o[i] + la * (i ? ey : ex);
        lo[i] = fmax(0, floor(fmin(o[i], end) - reach)), hi[i] = fmin(size - 1, ceil(fmax(o[i], end) + reach));
    }
    for (double y = lo[1]; y <= hi[1]; y++)
        for (double x = lo[0]; x <= hi[0]; x++) {
            double px = x + 0.5 - o[0], py = y + 0.5 - o[1], t = px * ex + py * ey;
            double h = (ex * py - ey * px) * (side > 0 ? -1 : 1); /* > 0: out of f */
            double tc = fmin(fmax(t, 0), la), d = hypot(px - tc * ex, py - tc * ey);
            if (d > reach || h < -1) continue; /* far, or well inside the face */
            seam_candidate c = {(uint64_t)y * (uint64_t)size + (uint64_t)x, d, {0}};
            c.value.x = (uint32_t)x, c.value.y = (uint32_t)y, c.value.chart = chart[f], c.value.across = chart[g];
            c.value.target[0] = (float)(o2[0] + jac[0] * px + jac[1] * py);
            c.value.target[1] = (float)(o2[1] + jac[2] * px + jac[3] * py);
            for (int i = 0; i < 4; i++) c.value.jacobian[i] = (float)jac[i];
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
    uint32_t *next = malloc((3 * m->face_count + 1) * sizeof *next),
             *chart = malloc((m->face_count + 1) * sizeof *chart);
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
