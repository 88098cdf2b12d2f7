/* Rusinkiewicz 2004, "Estimating curvatures and their derivatives on triangle meshes":
 * a second fundamental form per face, fitted by least squares to the differences of vertex
 * normals along the three edges (Sec. 3, eq. 4); per vertex, the face tensors are rotated into
 * the vertex's tangent frame and averaged with mixed Voronoi corner weights (Sec. 4), then
 * diagonalised. The 3x3 normal equations are solved exactly (Cramer), not with trimesh2's
 * LDLT, which reads A[2][0] and A[2][1] before filling them. */
#include <stdlib.h>
#include <string.h>

#include "mesh/internal.h"

/* One face: its frame (t, b, n), tensor (e, f, g) in that frame, corner areas. Floats (one
 * 64-byte cache line per face): the per-vertex gather reads faces in mesh order, which in a scan
 * is far from memory order, so this pass is bound by cache misses. */
typedef struct face_tensor {
    float t[3], b[3], n[3];
    float e, f, g;
    float corner[3];
    float pad;
} face_tensor;

enum { PREFETCH_AHEAD = 4 };

typedef struct rus_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const double *normals;
    face_tensor *ft;
    lucent_curvature *out;
    int refit; /* second pass: frames and corner areas already in ft */
} rus_job;

/* Solves the symmetric system [[a, b, 0], [b, a + c, b], [0, b, c]] x = m (eq. 4's normal
 * equations). det = (a + c)(a c - b^2) >= 0; returns 0 when the face is degenerate. */
static int solve_fit(double a, double b, double c, const double *m, double *x)
{
    double det = (a + c) * (a * c - b * b), scale = (a + c) * (a + c) * (a + c);
    if (!(det > 1e-12 * scale)) return 0;
    double i00 = (a + c) * c - b * b, i01 = -b * c, i02 = b * b;
    double i11 = a * c, i12 = -a * b, i22 = a * (a + c) - b * b;
    double inv = 1 / det;
    x[0] = (i00 * m[0] + i01 * m[1] + i02 * m[2]) * inv;
    x[1] = (i01 * m[0] + i11 * m[1] + i12 * m[2]) * inv;
    x[2] = (i02 * m[0] + i12 * m[1] + i22 * m[2]) * inv;
    return 1;
}

static void store_face(const double *t, const double *b, const double *n, const double *x,
                       const double *corner, face_tensor *ft)
{
    for (int k = 0; k < 3; k++) {
        ft->t[k] = (float)t[k], ft->b[k] = (float)b[k], ft->n[k] = (float)n[k];
        ft->corner[k] = (float)corner[k];
    }
    ft->e = (float)x[0], ft->f = (float)x[1], ft->g = (float)x[2], ft->pad = 0;
}

static void face_fit(const rus_job *j, size_t fi, face_tensor *ft)
{
    const uint32_t *t = j->mesh->faces + 3 * fi;
    const double *P = j->mesh->positions, *N = j->normals;
    double e[3][3], n[3], tt[3], bb[3], corner[3];
    for (int k = 0; k < 3; k++) v3_sub(P + 3 * t[(k + 2) % 3], P + 3 * t[(k + 1) % 3], e[k]);
    if (j->refit) { /* positions unchanged since the first pass: keep frame and areas */
        for (int k = 0; k < 3; k++)
            tt[k] = ft->t[k], bb[k] = ft->b[k], n[k] = ft->n[k], corner[k] = ft->corner[k];
    } else {
        mesh_corner_areas(j->mesh, fi, corner);
        memcpy(tt, e[0], sizeof tt);
        v3_normalize(tt);
        v3_cross(e[0], e[1], n);
        v3_normalize(n);
        v3_cross(n, tt, bb);
        v3_normalize(bb);
    }
    double a = 0, b = 0, c = 0, m[3] = {0, 0, 0}, x[3], dn[3];
    for (int k = 0; k < 3; k++) {
        double u = v3_dot(e[k], tt), v = v3_dot(e[k], bb);
        a += u * u, b += u * v, c += v * v;
        v3_sub(N + 3 * t[(k + 2) % 3], N + 3 * t[(k + 1) % 3], dn);
        double dnu = v3_dot(dn, tt), dnv = v3_dot(dn, bb);
        m[0] += dnu * u, m[1] += dnu * v + dnv * u, m[2] += dnv * v;
    }
    if (!solve_fit(a, b, c, m, x)) {
        corner[0] = corner[1] = corner[2] = 0; /* degenerate: no weight */
        x[0] = x[1] = x[2] = 0;
    }
    store_face(tt, bb, n, x, corner, ft);
}

static lucent_status faces_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    rus_job *j = ctx;
    for (uint64_t f = begin; f < end; f++) face_fit(j, f, j->ft + f);
    return LUCENT_OK;
}

/* Rotates the frame (u, v), normal old_n = u x v, so that its normal becomes new_n (trimesh2's
 * rot_coord_sys). */
static void rotate_frame(const double *u, const double *v, const double *old_n, const double *new_n,
                         double *ru, double *rv)
{
    double perp[3], dperp[3];
    double nd = v3_dot(old_n, new_n);
    memcpy(ru, u, 3 * sizeof *ru), memcpy(rv, v, 3 * sizeof *rv);
    if (nd <= -1) {
        for (int k = 0; k < 3; k++) ru[k] = -ru[k], rv[k] = -rv[k];
        return;
    }
    double inv = 1 / (1 + nd);
    for (int k = 0; k < 3; k++) perp[k] = new_n[k] - nd * old_n[k], dperp[k] = (old_n[k] + new_n[k]) * inv;
    double su = v3_dot(ru, perp), sv = v3_dot(rv, perp);
    for (int k = 0; k < 3; k++) ru[k] -= dperp[k] * su, rv[k] -= dperp[k] * sv;
}

/* Re-expresses the face tensor in the vertex frame (pu, pv), Sec. 4.1. */
static void project_tensor(const face_tensor *ft, const double *pu, const double *pv, const double *pn,
                           double *dest)
{
    double ru[3], rv[3], n[3] = {ft->n[0], ft->n[1], ft->n[2]};
    double t[3] = {ft->t[0], ft->t[1], ft->t[2]}, b[3] = {ft->b[0], ft->b[1], ft->b[2]};
    rotate_frame(pu, pv, pn, n, ru, rv);
    double u1 = v3_dot(ru, t), v1 = v3_dot(ru, b), u2 = v3_dot(rv, t), v2 = v3_dot(rv, b);
    dest[0] = ft->e * u1 * u1 + ft->f * 2 * u1 * v1 + ft->g * v1 * v1;
    dest[1] = ft->e * u1 * u2 + ft->f * (u1 * v2 + u2 * v1) + ft->g * v1 * v2;
    dest[2] = ft->e * u2 * u2 + ft->f * 2 * u2 * v2 + ft->g * v2 * v2;
}

/* Eigen-decomposition of the 2x2 tensor [[ku, kuv], [kuv, kv]] in frame (pu, pv) (a Jacobi
 * rotation); writes k1 >= k2 and their directions. */
static void diagonalize(const double *pu, const double *pv, const double *k, lucent_curvature *o, size_t v)
{
    double c = 1, s = 0, tt = 0;
    if (k[1] != 0) {
        double h = 0.5 * (k[2] - k[0]) / k[1];
        tt = h < 0 ? 1 / (h - sqrt(1 + h * h)) : 1 / (h + sqrt(1 + h * h));
        c = 1 / sqrt(1 + tt * tt), s = tt * c;
    }
    double k1 = k[0] - tt * k[1], k2 = k[2] + tt * k[1], *d1 = o->dir1 + 3 * v, *d2 = o->dir2 + 3 * v;
    for (int i = 0; i < 3; i++) d1[i] = c * pu[i] - s * pv[i], d2[i] = s * pu[i] + c * pv[i];
    if (k1 < k2) {
        double tmp[3];
        memcpy(tmp, d1, sizeof tmp), memcpy(d1, d2, sizeof tmp), memcpy(d2, tmp, sizeof tmp);
        double x = k1;
        k1 = k2, k2 = x;
    }
    o->k1[v] = k1, o->k2[v] = k2, o->mean[v] = 0.5 * (k1 + k2), o->gauss[v] = k1 * k2;
}

/* A tangent frame at v: the first incident edge, made perpendicular to the normal. */
static int vertex_frame(const rus_job *j, uint32_t v, double *pu, double *pv)
{
    const double *n = j->normals + 3 * v;
    uint32_t a = j->adj->start[v];
    const uint32_t *t = j->mesh->faces + 3 * j->adj->face[a];
    double e[3];
    v3_sub(j->mesh->positions + 3 * t[(j->adj->corner[a] + 1) % 3], j->mesh->positions + 3 * v, e);
    v3_cross(e, n, pu);
    if (v3_normalize(pu) == 0) return 0;
    v3_cross(n, pu, pv);
    return v3_normalize(pv) > 0;
}

static void vertex_curvature(const rus_job *j, uint32_t v)
{
    const mesh_adjacency *adj = j->adj;
    double pu[3], pv[3], area = 0, k[3] = {0, 0, 0}, kf[3];
    if (adj->start[v] == adj->start[v + 1] || !vertex_frame(j, v, pu, pv)) {
        j->out->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) area += j->ft[adj->face[a]].corner[adj->corner[a]];
    if (!(area > 0)) {
        j->out->flags[v] |= LUCENT_CURVATURE_INVALID;
        return;
    }
    for (uint32_t a = adj->start[v]; a < adj->start[v + 1]; a++) {
        const face_tensor *ft = j->ft + adj->face[a];
        double w = ft->corner[adj->corner[a]] / area;
        if (w == 0) continue;
        project_tensor(ft, pu, pv, j->normals + 3 * v, kf);
        for (int i = 0; i < 3; i++) k[i] += w * kf[i];
    }
    diagonalize(pu, pv, k, j->out, v);
}

static lucent_status vertices_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const rus_job *j = ctx;
    const mesh_adjacency *adj = j->adj;
    for (uint64_t v = begin; v < end; v++) {
        /* the face records are far apart in memory: fetch those of a later vertex now */
        if (v + PREFETCH_AHEAD < end)
            for (uint32_t a = adj->start[v + PREFETCH_AHEAD]; a < adj->start[v + PREFETCH_AHEAD + 1]; a++)
                __builtin_prefetch(j->ft + adj->face[a]);
        vertex_curvature(j, (uint32_t)v);
    }
    return LUCENT_OK;
}

/* Normal curvature of vertex v's tensor along direction e. */
static double normal_curvature(const lucent_curvature *o, uint32_t v, const double *e)
{
    double a = v3_dot(e, o->dir1 + 3 * v), b = v3_dot(e, o->dir2 + 3 * v), s = a * a + b * b;
    return s > 0 ? (o->k1[v] * a * a + o->k2[v] * b * b) / s : 0;
}

/* The neighbour nb of v lifted onto the model curve (see refine_normal), in world space. */
static void lift(const rus_job *j, uint32_t v, uint32_t nb, double *dest)
{
    const lucent_curvature *o = j->out;
    const double *n = j->normals + 3 * v, *d1 = o->dir1 + 3 * v, *d2 = o->dir2 + 3 * v;
    double e[3];
    v3_sub(j->mesh->positions + 3 * nb, j->mesh->positions + 3 * v, e);
    double du = v3_dot(e, d1), dv = v3_dot(e, d2);
    double r2 = du * du + dv * dv, kn = r2 > 0 ? (o->k1[v] * du * du + o->k2[v] * dv * dv) / r2 : 0;
    double kb = r2 > 0 && !(o->flags[nb] & LUCENT_CURVATURE_INVALID) ? normal_curvature(o, nb, e) : kn;
    /* a curve whose curvature goes linearly from kn to kb: height -(2 kn + kb)/3 s^2/2 */
    double kc = (2 * kn + kb) / 3;
    double q = 1 - kc * kc * r2, h = -kc * r2 / (1 + sqrt(q > 0 ? q : 0)); /* fmax is a libm call here */
    for (int i = 0; i < 3; i++) dest[i] = du * d1[i] + dv * d2[i] + h * n[i];
}

enum { LIFT_CACHE = 32 };

/* Lifted neighbour nb, from a small per-vertex cache (each neighbour is in two faces). */
static const double *lifted(const rus_job *j, uint32_t v, uint32_t nb, uint32_t *ids, double (*vec)[3], int *count,
                            double *spare)
{
    for (int i = 0; i < *count; i++)
        if (ids[i] == nb) return vec[i];
    double *dest = *count < LIFT_CACHE ? vec[*count] : spare; /* full: not cached */
    if (*count < LIFT_CACHE) ids[(*count)++] = nb;
    lift(j, v, nb, dest);
    return dest;
}

/* Removes the bias of Max's normal at v. Max's weights are exact when the neighbours lie on a
 * sphere; where curvature is anisotropic and the neighbourhood irregular they tilt. The tilt is
 * predicted by applying Max's formula to the same neighbourhood lifted onto the osculating
 * quadric z = -1/2 (k1 u^2 + k2 v^2) (curvature from the first pass, outward normals), whose
 * true normal is known, and subtracted. A symmetric neighbourhood predicts no tilt. */

static void refine_normal(const rus_job *j, uint32_t v, double *dest)
{
    const double *n = j->normals + 3 * v;
    double m[3] = {0, 0, 0}, x[3], vec[LIFT_CACHE][3], spare[2][3];
    uint32_t ids[LIFT_CACHE];
    int count = 0;
    memcpy(dest, n, 3 * sizeof *dest);
    if (j->out->flags[v] & LUCENT_CURVATURE_INVALID) return;
    for (uint32_t a = j->adj->start[v]; a < j->adj->start[v + 1]; a++) {
        const uint32_t *t = j->mesh->faces + 3 * j->adj->face[a];
        int c = j->adj->corner[a];
        const double *e0 = lifted(j, v, t[(c + 1) % 3], ids, vec, &count, spare[0]);
        const double *e1 = lifted(j, v, t[(c + 2) % 3], ids, vec, &count, spare[1]);
        double w = v3_dot(e0, e0) * v3_dot(e1, e1);
        if (!(w > 0)) continue;
        v3_cross(e0, e1, x);
        double iw = 1 / w;
        for (int i = 0; i < 3; i++) m[i] += x[i] * iw;
    }
    if (v3_normalize(m) == 0) return;
    double mn = v3_dot(m, n);
    for (int i = 0; i < 3; i++) dest[i] = n[i] - (m[i] - mn * n[i]);
    if (v3_normalize(dest) == 0) memcpy(dest, n, 3 * sizeof *dest);
}

typedef struct refine_job {
    const rus_job *rj;
    double *dest;
} refine_job;

static lucent_status refine_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    refine_job *r = ctx;
    for (uint64_t v = begin; v < end; v++) refine_normal(r->rj, (uint32_t)v, r->dest + 3 * v);
    return LUCENT_OK;
}

static lucent_status estimate(rus_job *job, lucent_pool *pool)
{
    size_t nv = job->mesh->vertex_count;
    for (size_t v = 0; v < nv; v++) job->out->flags[v] &= (uint8_t)~LUCENT_CURVATURE_INVALID;
    lucent_status s = lucent_parallel_for(pool, job->mesh->face_count, 8192, faces_chunk, job);
    if (s == LUCENT_OK) s = lucent_parallel_for(pool, nv, 4096, vertices_chunk, job);
    return s;
}

lucent_status mesh_curvature_rusinkiewicz(const lucent_mesh *mesh, const mesh_adjacency *adj,
                                          lucent_pool *pool, int fast, lucent_curvature *dest)
{
    double *normals = malloc((3 * mesh->vertex_count + 1) * sizeof *normals);
    face_tensor *ft = aligned_alloc(64, (mesh->face_count + 1) * sizeof *ft);
    lucent_status s = normals && ft ? LUCENT_OK
                                    : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    double *refined = s == LUCENT_OK && !fast ? malloc((3 * mesh->vertex_count + 1) * sizeof *refined) : NULL;
    if (s == LUCENT_OK && !fast && !refined) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "curvature: out of memory");
    rus_job job = {mesh, adj, normals, ft, dest, 0};
    if (s == LUCENT_OK) s = mesh_max_normals(mesh, adj, pool, normals);
    if (s == LUCENT_OK) s = estimate(&job, pool);
    refine_job rj = {&job, refined};
    if (s == LUCENT_OK && !fast) s = lucent_parallel_for(pool, mesh->vertex_count, 4096, refine_chunk, &rj);
    job.normals = refined, job.refit = 1;
    if (s == LUCENT_OK && !fast) s = estimate(&job, pool);
    free(normals), free(ft), free(refined);
    return s;
}
