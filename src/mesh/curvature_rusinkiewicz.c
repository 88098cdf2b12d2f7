/* Rusinkiewicz 2004, "Estimating curvatures and their derivatives on triangle meshes":
 * a second fundamental form per face, fitted by least squares to the differences of vertex
 * normals along the three edges (Sec. 3, eq. 4); per vertex, the face tensors are rotated into
 * the vertex's tangent plane and averaged with mixed Voronoi corner weights (Sec. 4), then
 * diagonalised. The 3x3 normal equations are solved exactly (Cramer), not with trimesh2's
 * LDLT, which reads A[2][0] and A[2][1] before filling them. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/optics.h"
#include "mesh/internal.h"
#include "mesh/rusinkiewicz.h"

/* Per adjacency slot, written by the first pass's gather: the corner weight w and the turn of
 * the face tensor into the vertex's frame, w cos 2 phi and w sin 2 phi. The second pass fits new
 * face tensors but keeps frames and weights (using the corrected normal for the vertex frame
 * changes nothing measurable), so its gather is a weighted sum of these. */
typedef struct slot_turn {
    float w, wc, ws;
} slot_turn;

enum { PREFETCH_SLOTS = 48 }; /* about 8 vertices ahead; at most MESH_SLOT_PAD */

typedef struct rus_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const float *normals; /* this pass's vertex normals, 3 per vertex */
    face_rec *faces;
    slot_turn *turns;          /* two passes only */
    float *tensors;            /* the second pass's face tensors (mean, diff, off) */
    mesh_principal *principal; /* the first of two passes writes here, the last to out */
    lucent_curvature *out;
    const float *frame_normals; /* the second pass: the first pass's normals, for the frames */
    double scale;               /* 1/mm_per_unit */
    int second;
} rus_job;

static inline float dotf(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* First pass: frame, corner areas and edge coordinates from the positions; 0 (and a record of
 * zeros, no weight) for a degenerate face. */
static int face_frame(const double *P, const uint32_t *v, face_rec *r)
{
    v3 p0 = v3_load(P + 3 * (size_t)v[0]), p1 = v3_load(P + 3 * (size_t)v[1]), p2 = v3_load(P + 3 * (size_t)v[2]);
    /* vectors by value: the edges stay in registers (stored edges that a cross product reloads
     * two at a time are what store forwarding cannot serve) */
    v3 e0 = v3_sub(p2, p1), e1 = v3_sub(p0, p2), e2 = v3_sub(p1, p0), x = v3_cross(e0, e1);
    double l[3] = {v3_dot(e0, e0), v3_dot(e1, e1), v3_dot(e2, e2)}, corner[3];
    double x2 = v3_dot(x, x);
    if (!(x2 > 0) || !(l[0] > 0) || !isfinite(x2)) {
        memset(r, 0, sizeof *r);
        return 0;
    }
    double xl = sqrt(x2), len = sqrt(l[0]), q = 1 / (xl * len), in = q * len, it = q * xl, il = it * it;
    mesh_mixed_areas(l, xl, in, corner); /* Meyer et al. 2003, Fig. 4 */
    r->t[0] = (float)(e0.x * it), r->t[1] = (float)(e0.y * it), r->t[2] = (float)(e0.z * it);
    r->n[0] = (float)(x.x * in), r->n[1] = (float)(x.y * in), r->n[2] = (float)(x.z * in);
    for (int k = 0; k < 3; k++) r->corner[k] = (float)corner[k];
    r->u1 = (float)(v3_dot(e0, e1) * il), r->w1 = (float)(xl * il), r->inv_len = (float)it, r->unused = 0;
    return 1;
}

/* Frames first, then tensors, in separate loops: each iteration of either is short enough for
 * several faces to be in flight at once (together they were latency-bound). */
static lucent_status faces_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const rus_job *j = ctx;
    for (uint64_t f = begin; j->second == 0 && f < end; f++)
        face_frame(j->mesh->positions, j->mesh->faces + 3 * f, j->faces + f);
    if (j->second)
        mesh_rus_fit_faces(j->mesh->faces, j->normals, j->faces, begin, end, j->tensors, 3);
    else
        mesh_rus_fit_faces(j->mesh->faces, j->normals, j->faces, begin, end,
                           (float *)j->faces + offsetof(face_rec, mean) / sizeof(float), 16);
    return LUCENT_OK;
}

/* A tangent frame (pu, pv) at the unit normal n, pu x pv = n (lucent_basis, base/optics.h: Duff
 * et al. 2017). 0 for a zero normal. */
static int tangent_frame(const float *nf, double *n, double *pu, double *pv)
{
    double l2 = (double)nf[0] * nf[0] + (double)nf[1] * nf[1] + (double)nf[2] * nf[2];
    if (!(l2 > 0)) return 0;
    double s = 1 / sqrt(l2);
    v3 u = v3_make(nf[0] * s, nf[1] * s, nf[2] * s), t, b;
    lucent_basis(u, &t, &b);
    v3_store(u, n), v3_store(t, pu), v3_store(b, pv);
    return 1;
}

/* Sums v's face tensors, each turned into v's tangent plane by the rotation that takes the
 * face normal to v's normal (Sec. 4.1: exact, not a projection) and weighted by v's corner area
 * (Sec. 4.2). With f's tangent t at angle phi from pu after the rotation, (diff, off) turn by
 * 2 phi. acc: total area, then area times mean, diff and off in (pu, pv). */
static void gather(const rus_job *j, uint32_t v, const float *u, const float *w, const float *n, double acc[4])
{
    const mesh_adjacency *adj = j->adj;
    float sa = 0, sm = 0, sx = 0, sy = 0;
    for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) {
        uint32_t i = adj->corner[a];
        const face_rec *f = j->faces + i / 3;
        __builtin_prefetch(j->faces + adj->corner[a + PREFETCH_SLOTS] / 3); /* records lie far apart */
        float area = f->corner[i % 3];
        float nd = dotf(n, f->n), su = dotf(u, f->n), sv = dotf(w, f->n);
        float tn = dotf(n, f->t), tu = dotf(u, f->t), tv = dotf(w, f->t);
        float den = 1 + nd, k = den > 1e-6f ? tn / den : 0; /* opposite normals: no turn */
        float c = tu - su * k, s = tv - sv * k;             /* cos phi, sin phi */
        float wc = area * (c * c - s * s), ws = area * 2 * c * s;
        sa += area, sm += area * f->mean, sx += f->diff * wc - f->off * ws, sy += f->diff * ws + f->off * wc;
        if (j->turns) j->turns[a] = (slot_turn){area, wc, ws};
    }
    acc[0] = sa, acc[1] = sm, acc[2] = sx, acc[3] = sy;
}

/* The second pass's gather: the first pass's weights and turns, the new tensors. */
static void regather(const rus_job *j, uint32_t v, double acc[4])
{
    const mesh_adjacency *adj = j->adj;
    float sa = 0, sm = 0, sx = 0, sy = 0;
    for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) {
        const slot_turn *t = j->turns + a;
        const float *x = j->tensors + 3 * (size_t)(adj->corner[a] / 3);
        __builtin_prefetch(j->tensors + 3 * (size_t)(adj->corner[a + PREFETCH_SLOTS] / 3));
        sa += t->w, sm += t->w * x[0], sx += t->wc * x[1] - t->ws * x[2], sy += t->ws * x[1] + t->wc * x[2];
    }
    acc[0] = sa, acc[1] = sm, acc[2] = sx, acc[3] = sy;
}

/* Eigen-decomposition of the averaged tensor [[mean + x, y], [y, mean - x]] in (pu, pv):
 * k = mean +- r, (x, y) = r (cos 2 phi, sin 2 phi), k1 along (cos phi, sin phi). Writes the
 * result (last pass), or zeros (invalid). */
static void store_vertex(const rus_job *j, uint32_t v, const double *pu, const double *pv, const double *acc)
{
    double mean = 0, r = 0, c = 1, s = 0, d1[3], d2[3];
    int valid = acc && acc[0] > 0;
    if (valid) {
        double inv = 1 / acc[0], x = acc[2] * inv, y = acc[3] * inv;
        mean = acc[1] * inv, r = sqrt(x * x + y * y);
        double h = r > 0 ? x / r : 1; /* cos 2 phi; half angles without a branch on its sign */
        c = sqrt(0.5 * (1 + h)), s = copysign(sqrt(0.5 * (1 - h)), y);
    }
    double k1 = (mean + r) * j->scale, k2 = (mean - r) * j->scale, gauss = k1 * k2; /* in mm^-1 */
    valid = valid && isfinite(k1) && isfinite(k2) && isfinite(gauss);               /* as lucent_mesh_curvature's */
    for (int k = 0; k < 3; k++) d1[k] = valid ? c * pu[k] + s * pv[k] : 0, d2[k] = valid ? c * pv[k] - s * pu[k] : 0;
    lucent_curvature *o = j->out;
    o->k1[v] = valid ? k1 : 0, o->k2[v] = valid ? k2 : 0;
    o->mean[v] = valid ? mean * j->scale : 0, o->gauss[v] = valid ? gauss : 0;
    memcpy(o->dir1 + 3 * (size_t)v, d1, sizeof d1), memcpy(o->dir2 + 3 * (size_t)v, d2, sizeof d2);
    uint8_t *flags = j->out->flags + v;
    *flags = (uint8_t)(valid ? *flags & ~LUCENT_CURVATURE_INVALID : *flags | LUCENT_CURVATURE_INVALID);
}

/* The first of two passes at vertex v, in floats: its principal frame feeds only the normal
 * correction. The same steps as tangent_frame and store_vertex. */
static void vertex_first(const rus_job *j, uint32_t v)
{
    const float *m = j->normals + 3 * (size_t)v;
    float l2 = dotf(m, m), n[3], u[3], w[3];
    double acc[4] = {0, 0, 0, 0};
    if (l2 > 0) {
        float s = 1 / sqrtf(l2);
        for (int k = 0; k < 3; k++) n[k] = m[k] * s;
        lucent_basis_f(n, u, w);
        gather(j, v, u, w, n, acc);
    }
    mesh_principal *p = j->principal + v;
    uint8_t *flags = j->out->flags + v;
    if (!(acc[0] > 0)) {
        memset(p, 0, sizeof *p), *flags |= LUCENT_CURVATURE_INVALID;
        return;
    }
    float inv = (float)(1 / acc[0]), x = (float)acc[2] * inv, y = (float)acc[3] * inv, mean = (float)acc[1] * inv;
    float r = sqrtf(x * x + y * y), h = r > 0 ? x / r : 1;
    float c = sqrtf(0.5f * (1 + h)), sn = copysignf(sqrtf(0.5f * (1 - h)), y);
    for (int k = 0; k < 3; k++) p->d1[k] = c * u[k] + sn * w[k], p->d2[k] = c * w[k] - sn * u[k];
    p->k1 = mean + r, p->k2 = mean - r, *flags &= (uint8_t)~LUCENT_CURVATURE_INVALID;
}

static void vertex_curvature(const rus_job *j, uint32_t v)
{
    double n[3], pu[3], pv[3], acc[4];
    float nf[3], uf[3], vf[3];
    if (j->principal) {
        vertex_first(j, v);
        return;
    }
    if (!tangent_frame((j->second ? j->frame_normals : j->normals) + 3 * (size_t)v, n, pu, pv)) {
        pu[0] = pu[1] = pu[2] = pv[0] = pv[1] = pv[2] = 0;
        store_vertex(j, v, pu, pv, NULL);
        return;
    }
    if (j->second) {
        regather(j, v, acc);
    } else {
        for (int k = 0; k < 3; k++) nf[k] = (float)n[k], uf[k] = (float)pu[k], vf[k] = (float)pv[k];
        gather(j, v, uf, vf, nf, acc);
    }
    store_vertex(j, v, pu, pv, acc);
}

static lucent_status vertices_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const rus_job *j = ctx;
    for (uint64_t v = begin; v < end; v++) vertex_curvature(j, (uint32_t)v);
    return LUCENT_OK;
}

static lucent_status pass(const rus_job *job, lucent_pool *pool)
{
    lucent_status s = lucent_parallel_for(pool, job->mesh->face_count, 8192, faces_chunk, (void *)job);
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, job->mesh->vertex_count, 4096, vertices_chunk, (void *)job);
    return s;
}

/* Scratch in one block: face records; for two passes also the first pass's principal frames
 * and, in the same place once the normals are corrected, the second pass's face tensors; the
 * corrected normals and the slot turns. (Fresh pages cost more than the arithmetic here.) */
typedef struct rus_scratch {
    face_rec *faces;
    mesh_principal *principal;
    float *normals, *tensors;
    slot_turn *turns;
} rus_scratch;

static size_t round64(size_t bytes) { return (bytes + 63) / 64 * 64; }

static void *scratch(size_t nv, size_t nf, int fast, rus_scratch *d)
{
    size_t shared = round64(nv * sizeof *d->principal), tensors = round64(3 * nf * sizeof *d->tensors);
    size_t size[4] = {round64(nf * sizeof *d->faces), shared > tensors ? shared : tensors,
                      round64(3 * nv * sizeof *d->normals + 16), round64(3 * nf * sizeof *d->turns)};
    size_t total = size[0] + (fast ? 0 : size[1] + size[2] + size[3]);
    char *block = mesh_alloc_large(total + 64), *at = block;
    if (!block) return NULL;
    *d = (rus_scratch){0};
    d->faces = (face_rec *)at;
    if (fast) return block;
    d->principal = (mesh_principal *)(at += size[0]), d->tensors = (float *)at;
    d->normals = (float *)(at += size[1]), d->turns = (slot_turn *)(at + size[2]);
    return block;
}

lucent_status mesh_curvature_rusinkiewicz(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                          lucent_pool *pool, int fast, double scale, lucent_curvature *dest)
{
    rus_scratch sc;
    void *block = scratch(mesh->vertex_count, mesh->face_count, fast, &sc);
    if (!block) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    rus_job job = {mesh, adj,          fan->normals, sc.faces, sc.turns, sc.tensors, fast ? NULL : sc.principal,
                   dest, fan->normals, scale,        0};
    lucent_status s = pass(&job, pool);
    /* Second pass (Lucent's): Max's normals corrected for their tilt, then the same fit. */
    if (s == LUCENT_OK && !fast) s = mesh_refine_normals(mesh, adj, fan, sc.principal, pool, sc.normals);
    job.normals = sc.normals, job.principal = NULL, job.second = 1;
    if (s == LUCENT_OK && !fast) s = pass(&job, pool);
    free(block);
    return s;
}
