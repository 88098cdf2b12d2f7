/* The normal correction of Lucent's second Rusinkiewicz pass. Max's weights are exact when
 * the neighbours lie on a sphere; where curvature is anisotropic and the neighbourhood
 * irregular, Max's normal tilts, and the normal differences carry the tilt into the tensor.
 * The tilt is predicted by applying Max's formula to the same neighbourhood lifted onto the
 * curve of curvature varying linearly from the vertex's normal curvature to the neighbour's
 * along each edge (first-pass curvatures, outward normals), whose true normal is the vertex's
 * own, and subtracted. A sphere predicts no tilt; a symmetric neighbourhood almost none.
 * Everything is done in the vertex's principal frame (d1, d2, n), where a lifted neighbour is
 * (du, dv, h). */
#include "mesh/internal.h"

enum { PREFETCH_SLOTS = 16 }; /* about 3 vertices ahead */

typedef struct refine_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const mesh_fan *fan;
    const mesh_principal *principal;
    float *dest;
} refine_job;

/* Lifted neighbours of one vertex in its frame (d1, d2, n), in scalar arrays: offset (u, v),
 * height h, inverse squared length il; num, den, r2 are intermediate. */
enum { LIFT_MAX = 2 * MESH_FAN_MAX };
typedef struct lifted {
    float u[LIFT_MAX], v[LIFT_MAX], h[LIFT_MAX], il[LIFT_MAX];
} lifted;

static inline float dotf(const float *a, float x, float y, float z) { return a[0] * x + a[1] * y + a[2] * z; }

/* Neighbour u of v lifted into L[i]: its offset (u, v) in v's tangent plane and the height of a
 * curve whose curvature goes linearly from kn (v's normal curvature along the edge) to kb (u's)
 * over the edge length s, about -(2 kn + kb)/3 s^2/2, as h = -k s^2/(1 + sqrt(1 - k^2 s^2)) with
 * k = (2 kn + kb)/3 (exact for a circle); il = 1/|lifted|^2. One division gives kn, kb and k. */
static inline void lift(const refine_job *j, uint32_t v, uint32_t u, lifted *L, uint32_t i)
{
    const mesh_principal *p = j->principal + v, *q = j->principal + u;
    const double *x = j->mesh->positions + 3 * (size_t)u, *o = j->mesh->positions + 3 * (size_t)v;
    float ex = (float)(x[0] - o[0]), ey = (float)(x[1] - o[1]), ez = (float)(x[2] - o[2]);
    float du = dotf(p->d1, ex, ey, ez), dv = dotf(p->d2, ex, ey, ez), r2 = du * du + dv * dv;
    float kn2 = p->k1 * du * du + p->k2 * dv * dv; /* kn r2 */
    float a = dotf(q->d1, ex, ey, ez), b = dotf(q->d2, ex, ey, ez), s = a * a + b * b;
    float kb = q->k1 * a * a + q->k2 * b * b;      /* kb s */
    int own = (j->fan->flags[u] & LUCENT_CURVATURE_INVALID) != 0; /* no kb: kb = kn */
    float num = own ? kn2 : s > 0 ? 2 * kn2 * s + kb * r2 : 2 * kn2;
    float den = own ? r2 : s > 0 ? 3 * r2 * s : 3 * r2;
    float k = den > 0 ? num / den : 0, ks2 = k * r2, c = 1 - k * ks2;
    float h = -ks2 / (1 + sqrtf(c > 0 ? c : 0)), l2 = r2 + h * h;
    L->u[i] = du, L->v[i] = dv, L->h[i] = h, L->il[i] = l2 > 0 ? 1 / l2 : 0;
}

/* Max's weight of the face (i0, i1), accumulated into m. */
static inline void add_corner(const lifted *L, int i0, int i1, float *m)
{
    float w = L->il[i0] * L->il[i1];
    m[0] += (L->v[i0] * L->h[i1] - L->h[i0] * L->v[i1]) * w;
    m[1] += (L->h[i0] * L->u[i1] - L->u[i0] * L->h[i1]) * w;
    m[2] += (L->u[i0] * L->v[i1] - L->v[i0] * L->u[i1]) * w;
}

/* Max's formula on the lifted neighbourhood (local coordinates). Each slot's next neighbour is
 * lifted once; its previous one is its paired slot's next, or lifted too when unpaired. */
static void lifted_max_normal(const refine_job *j, uint32_t v, float m[3])
{
    const uint32_t *slot = j->adj->corner + j->adj->start[v];
    const uint8_t *pair = j->fan->pair + j->adj->start[v];
    uint32_t count = j->adj->start[v + 1] - j->adj->start[v], prev, other[MESH_FAN_MAX];
    uint32_t extra = 0;
    lifted L;
    m[0] = m[1] = m[2] = 0;
    if (count == 0) return;
    if (count > MESH_FAN_MAX) { /* high valence (rare): each face on its own */
        for (uint32_t a = 0; a < count; a++) {
            uint32_t next;
            mesh_slot_others(j->mesh->faces, slot[a], &next, &prev);
            lift(j, v, next, &L, 0), lift(j, v, prev, &L, 1), add_corner(&L, 0, 1, m);
        }
        return;
    }
    for (uint32_t a = 0; a < count; a++) { /* few loops: each exit costs a misprediction */
        uint32_t next = mesh_prefetch_slot(j->adj, j->mesh->faces, j->adj->start[v] + a, PREFETCH_SLOTS);
        __builtin_prefetch(j->mesh->positions + 3 * (size_t)next), __builtin_prefetch(j->principal + next);
        mesh_slot_others(j->mesh->faces, slot[a], &next, &prev);
        lift(j, v, next, &L, a);
        if (pair[a] != MESH_UNPAIRED) {
            other[a] = pair[a];
        } else {
            other[a] = count + extra++;
            lift(j, v, prev, &L, other[a]);
        }
    }
    for (uint32_t a = 0; a < count; a++) add_corner(&L, (int)a, (int)other[a], m);
}

/* dest = n minus the tangential part of the lifted neighbourhood's unit Max normal. */
static void refine_vertex(const refine_job *j, uint32_t v, float *dest)
{
    const float *n = j->fan->normals + 3 * (size_t)v;
    const mesh_principal *p = j->principal + v;
    float m[3];
    double r[3];
    for (int i = 0; i < 3; i++) dest[i] = n[i];
    if (j->fan->flags[v] & LUCENT_CURVATURE_INVALID) return;
    lifted_max_normal(j, v, m);
    double len = sqrt((double)m[0] * m[0] + (double)m[1] * m[1] + (double)m[2] * m[2]);
    if (!(len > 0) || !isfinite(len)) return;
    for (int i = 0; i < 3; i++) r[i] = n[i] - (m[0] * p->d1[i] + m[1] * p->d2[i]) / len;
    if (v3_normalize(r) == 0) return;
    for (int i = 0; i < 3; i++) dest[i] = (float)r[i];
}

static lucent_status refine_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const refine_job *j = ctx;
    for (uint64_t v = begin; v < end; v++) refine_vertex(j, (uint32_t)v, j->dest + 3 * v);
    return LUCENT_OK;
}

lucent_status mesh_refine_normals(const lucent_mesh *mesh, const mesh_adjacency *adj, const mesh_fan *fan,
                                  const mesh_principal *principal, lucent_pool *pool, float *dest)
{
    refine_job job = {mesh, adj, fan, principal, dest};
    return lucent_parallel_for(pool, mesh->vertex_count, 4096, refine_chunk, &job);
}
