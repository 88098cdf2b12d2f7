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

/* Four neighbours are lifted at once with SSE2 (every x86-64 has it); elsewhere, or with
 * LUCENT_NO_SIMD, one at a time. Both do the same float operations in the same order, so their
 * results are identical. */
#if defined(__SSE2__) && !defined(LUCENT_NO_SIMD)
#include <emmintrin.h>
#define LIFT_SSE2 1
#else
#define LIFT_SSE2 0
#endif

enum { PREFETCH_SLOTS = 16 }; /* about 3 vertices ahead */

typedef struct refine_job {
    const lucent_mesh *mesh;
    const mesh_adjacency *adj;
    const mesh_fan *fan;
    const mesh_principal *principal;
    float *dest;
} refine_job;

/* Lifted neighbours of one vertex in its frame (d1, d2, n), in scalar arrays: offset (u, v),
 * height h, inverse squared length il (room for a last group of four). */
enum { LIFT_MAX = 2 * MESH_FAN_MAX + 4 };
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
    float kb = q->k1 * a * a + q->k2 * b * b;                     /* kb s */
    int own = (j->fan->flags[u] & LUCENT_CURVATURE_INVALID) != 0; /* no kb: kb = kn */
    float num = own ? kn2 : s > 0 ? 2 * kn2 * s + kb * r2 : 2 * kn2;
    float den = own ? r2 : s > 0 ? 3 * r2 * s : 3 * r2;
    float k = den > 0 ? num / den : 0, ks2 = k * r2, c = 1 - k * ks2;
    float h = -ks2 / (1 + sqrtf(c > 0 ? c : 0)), l2 = r2 + h * h;
    L->u[i] = du, L->v[i] = dv, L->h[i] = h, L->il[i] = l2 > 0 ? 1 / l2 : 0;
}

#if LIFT_SSE2
/* v's frame, each value in all four lanes. */
typedef struct frame4 {
    __m128 d1[3], d2[3], k1, k2;
} frame4;

static frame4 frame4_of(const mesh_principal *p)
{
    frame4 F;
    for (int k = 0; k < 3; k++) F.d1[k] = _mm_set1_ps(p->d1[k]), F.d2[k] = _mm_set1_ps(p->d2[k]);
    F.k1 = _mm_set1_ps(p->k1), F.k2 = _mm_set1_ps(p->k2);
    return F;
}

static inline __m128 dot4(const __m128 *a, __m128 x, __m128 y, __m128 z)
{
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a[0], x), _mm_mul_ps(a[1], y)), _mm_mul_ps(a[2], z));
}

static inline __m128 select4(__m128 mask, __m128 yes, __m128 no)
{
    return _mm_or_ps(_mm_and_ps(mask, yes), _mm_andnot_ps(mask, no));
}

/* The edges from v to four neighbours, lanes 0..3, as floats. */
static void edges4(const double *P, const double *o, const uint32_t *nb, __m128 *ex, __m128 *ey, __m128 *ez)
{
    const double *p0 = P + 3 * (size_t)nb[0], *p1 = P + 3 * (size_t)nb[1], *p2 = P + 3 * (size_t)nb[2];
    const double *p3 = P + 3 * (size_t)nb[3];
    *ex = _mm_setr_ps((float)(p0[0] - o[0]), (float)(p1[0] - o[0]), (float)(p2[0] - o[0]), (float)(p3[0] - o[0]));
    *ey = _mm_setr_ps((float)(p0[1] - o[1]), (float)(p1[1] - o[1]), (float)(p2[1] - o[1]), (float)(p3[1] - o[1]));
    *ez = _mm_setr_ps((float)(p0[2] - o[2]), (float)(p1[2] - o[2]), (float)(p2[2] - o[2]), (float)(p3[2] - o[2]));
}

/* lift() for neighbours nb[0..3] into L[i..i+3]: the same operations, lane by lane. */
static void lift4(const refine_job *j, const frame4 *F, uint32_t v, const uint32_t *nb, lifted *L, uint32_t i)
{
    __m128 ex, ey, ez, q[8], zero = _mm_setzero_ps(), two = _mm_set1_ps(2), three = _mm_set1_ps(3);
    edges4(j->mesh->positions, j->mesh->positions + 3 * (size_t)v, nb, &ex, &ey, &ez);
    for (int k = 0; k < 4; k++) { /* the neighbours' frames, transposed: q[0..3] = d1, k1; q[4..7] = d2, k2 */
        q[k] = _mm_loadu_ps(j->principal[nb[k]].d1), q[4 + k] = _mm_loadu_ps(j->principal[nb[k]].d2);
    }
    _MM_TRANSPOSE4_PS(q[0], q[1], q[2], q[3]);
    _MM_TRANSPOSE4_PS(q[4], q[5], q[6], q[7]);
    const uint8_t *flags = j->fan->flags;
    __m128 own = _mm_castsi128_ps(_mm_setr_epi32(/* all ones where the neighbour is invalid */
                                                 -((flags[nb[0]] & LUCENT_CURVATURE_INVALID) != 0),
                                                 -((flags[nb[1]] & LUCENT_CURVATURE_INVALID) != 0),
                                                 -((flags[nb[2]] & LUCENT_CURVATURE_INVALID) != 0),
                                                 -((flags[nb[3]] & LUCENT_CURVATURE_INVALID) != 0)));
    __m128 du = dot4(F->d1, ex, ey, ez), dv = dot4(F->d2, ex, ey, ez);
    __m128 r2 = _mm_add_ps(_mm_mul_ps(du, du), _mm_mul_ps(dv, dv));
    __m128 kn2 = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(F->k1, du), du), _mm_mul_ps(_mm_mul_ps(F->k2, dv), dv));
    __m128 a = dot4(q, ex, ey, ez), b = dot4(q + 4, ex, ey, ez), s = _mm_add_ps(_mm_mul_ps(a, a), _mm_mul_ps(b, b));
    __m128 kb = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(q[3], a), a), _mm_mul_ps(_mm_mul_ps(q[7], b), b));
    __m128 spos = _mm_cmpgt_ps(s, zero), kn2x2 = _mm_mul_ps(two, kn2), r2x3 = _mm_mul_ps(three, r2);
    __m128 num = select4(own, kn2, select4(spos, _mm_add_ps(_mm_mul_ps(kn2x2, s), _mm_mul_ps(kb, r2)), kn2x2));
    __m128 den = select4(own, r2, select4(spos, _mm_mul_ps(r2x3, s), r2x3));
    __m128 k = _mm_and_ps(_mm_cmpgt_ps(den, zero), _mm_div_ps(num, den)), ks2 = _mm_mul_ps(k, r2);
    __m128 c = _mm_max_ps(_mm_sub_ps(_mm_set1_ps(1), _mm_mul_ps(k, ks2)), zero);
    __m128 h = _mm_div_ps(_mm_xor_ps(ks2, _mm_set1_ps(-0.0f)), _mm_add_ps(_mm_set1_ps(1), _mm_sqrt_ps(c)));
    __m128 l2 = _mm_add_ps(r2, _mm_mul_ps(h, h));
    __m128 il = _mm_and_ps(_mm_cmpgt_ps(l2, zero), _mm_div_ps(_mm_set1_ps(1), l2));
    _mm_storeu_ps(L->u + i, du), _mm_storeu_ps(L->v + i, dv), _mm_storeu_ps(L->h + i, h), _mm_storeu_ps(L->il + i, il);
}
#endif

/* Max's weight of the face (i0, i1), accumulated into m (doubles: the weight, 1/|e|^4, leaves
 * the float range for edges shorter than about 1e-10 units). */
static inline void add_corner(const lifted *L, int i0, int i1, double *m)
{
    double w = (double)L->il[i0] * L->il[i1];
    m[0] += (L->v[i0] * L->h[i1] - L->h[i0] * L->v[i1]) * w;
    m[1] += (L->h[i0] * L->u[i1] - L->u[i0] * L->h[i1]) * w;
    m[2] += (L->u[i0] * L->v[i1] - L->v[i0] * L->u[i1]) * w;
}

/* Max's formula on the lifted neighbourhood (local coordinates). Each slot's next neighbour is
 * lifted once; its previous one is its paired slot's next, or lifted too when unpaired. */
static void lifted_max_normal(const refine_job *j, uint32_t v, double m[3])
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
    uint32_t nb[LIFT_MAX];
    for (uint32_t a = 0; a < count; a++) { /* few loops: each exit costs a misprediction */
        uint32_t next = mesh_prefetch_slot(j->adj, j->mesh->faces, j->adj->start[v] + a, PREFETCH_SLOTS);
        __builtin_prefetch(j->mesh->positions + 3 * (size_t)next), __builtin_prefetch(j->principal + next);
        mesh_slot_others(j->mesh->faces, slot[a], nb + a, &prev);
        if (pair[a] != MESH_UNPAIRED)
            other[a] = pair[a];
        else
            other[a] = count + extra, nb[count + extra++] = prev;
    }
#if LIFT_SSE2
    frame4 F = frame4_of(j->principal + v);
    for (uint32_t i = count + extra; i % 4; i++) nb[i] = v; /* a lane lifting v itself gives zeros */
    for (uint32_t i = 0; i < count + extra; i += 4) lift4(j, &F, v, nb + i, &L, i);
#else
    for (uint32_t i = 0; i < count + extra; i++) lift(j, v, nb[i], &L, i);
#endif
    for (uint32_t a = 0; a < count; a++) add_corner(&L, (int)a, (int)other[a], m);
}

/* dest = n minus the tangential part of the lifted neighbourhood's unit Max normal. */
static void refine_vertex(const refine_job *j, uint32_t v, float *dest)
{
    const float *n = j->fan->normals + 3 * (size_t)v;
    const mesh_principal *p = j->principal + v;
    double m[3], r[3];
    for (int i = 0; i < 3; i++) dest[i] = n[i];
    if (j->fan->flags[v] & LUCENT_CURVATURE_INVALID) return;
    lifted_max_normal(j, v, m);
    double len = v3_length(v3_load(m)), il = 1 / len;
    if (!(len > 0) || !isfinite(len)) return;
    for (int i = 0; i < 3; i++) r[i] = n[i] - (m[0] * p->d1[i] + m[1] * p->d2[i]) * il;
    v3 u = v3_normalize(v3_load(r));
    if (v3_dot(u, u) == 0) return;
    dest[0] = (float)u.x, dest[1] = (float)u.y, dest[2] = (float)u.z;
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
