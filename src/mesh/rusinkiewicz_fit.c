/* The per-face fit of Rusinkiewicz 2004 (Sec. 3, eq. 4): the face's second fundamental form
 * fitted by least squares to the differences of the vertex normals along its three edges.
 * Four faces at a time with SSE2 where there is one (every x86-64); the scalar code (other
 * machines, the last faces of a range, or built with LUCENT_NO_SIMD) does the same float
 * operations in the same order, so both give identical results. */
#include <stddef.h>

#include "mesh/rusinkiewicz.h"

#if defined(__SSE2__) && !defined(LUCENT_NO_SIMD)
#include <emmintrin.h>
#define FIT_SSE2 1
#else
#define FIT_SSE2 0
#endif

static inline float dotf(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Edge k (opposite corner k) is (uk, wk) in (t, b), in units of edge 0's length (so the
 * arithmetic is scale-free), its normal difference (duk, dwk); m = sum over edges of
 * (du u, du w + dw u, dw w). The normal equations [[a, b, 0], [b, a + c, b], [0, b, c]] x = m
 * are solved exactly (Cramer), not with trimesh2's LDLT, which reads A[2][0] and A[2][1] before
 * filling them; their determinant is (a + c)(a c - b^2), and a c - b^2 = 3 (u0 w1)^2 by
 * Lagrange's identity (every pair of edges spans twice the area), so it is computed without
 * cancellation. Returns 0 when degenerate. */
static int fit_tensor(const face_rec *r, const float *n0, const float *n1, const float *n2, float *dest)
{
    const float *t = r->t, *n = r->n;
    float b[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    float u1 = r->u1, w1 = r->w1, u2 = -1 - u1; /* edges (1, 0), (u1, w1), (u2, -w1) */
    float t0 = dotf(n0, t), t1 = dotf(n1, t), t2 = dotf(n2, t), b0 = dotf(n0, b), b1 = dotf(n1, b), b2 = dotf(n2, b);
    float du0 = t2 - t1, du1 = t0 - t2, du2 = t1 - t0, dw0 = b2 - b1, dw1 = b0 - b2, dw2 = b1 - b0;
    float a = 1 + u1 * u1 + u2 * u2, ab = w1 * (u1 - u2), c = 2 * w1 * w1;
    float m0 = du0 + du1 * u1 + du2 * u2, m1 = w1 * (du1 - du2) + dw0 + dw1 * u1 + dw2 * u2, m2 = w1 * (dw1 - dw2);
    float q = 3 * w1 * w1, s = a + c; /* a c - b^2, with u0 = 1 */
    if (r->corner[0] + r->corner[1] + r->corner[2] == 0 || !(q > 1e-12f * s * s) || !(q < 1e30f)) return 0;
    float i00 = q + c * c, i01 = -ab * c, i02 = ab * ab, i11 = a * c, i12 = -a * ab, i22 = q + a * a;
    float inv = r->inv_len / (s * q); /* back to the mesh's units: curvature scales as 1/L */
    float x0 = (i00 * m0 + i01 * m1 + i02 * m2) * inv, x1 = (i01 * m0 + i11 * m1 + i12 * m2) * inv;
    float x2 = (i02 * m0 + i12 * m1 + i22 * m2) * inv;
    dest[0] = 0.5f * (x0 + x2), dest[1] = 0.5f * (x0 - x2), dest[2] = x1;
    return 1;
}

static void fit_face(const uint32_t *v, const float *N, const face_rec *r, float *dest)
{
    if (!fit_tensor(r, N + 3 * (size_t)v[0], N + 3 * (size_t)v[1], N + 3 * (size_t)v[2], dest))
        dest[0] = dest[1] = dest[2] = 0;
}

#if FIT_SSE2
_Static_assert(sizeof(face_rec) == 64 && offsetof(face_rec, n) == 12 && offsetof(face_rec, off) == 32 &&
                   offsetof(face_rec, u1) == 48,
               "fit4 reads face_rec as 16 floats");

/* Four rows of four floats, transposed: lane i of dest[k] is row i's float k. */
static inline void load4(const float *r0, const float *r1, const float *r2, const float *r3, __m128 dest[4])
{
    dest[0] = _mm_loadu_ps(r0), dest[1] = _mm_loadu_ps(r1), dest[2] = _mm_loadu_ps(r2), dest[3] = _mm_loadu_ps(r3);
    _MM_TRANSPOSE4_PS(dest[0], dest[1], dest[2], dest[3]);
}

static inline __m128 dot4(const __m128 *a, const __m128 *b)
{
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a[0], b[0]), _mm_mul_ps(a[1], b[1])), _mm_mul_ps(a[2], b[2]));
}

/* a x + b y + c z, in that order. */
static inline __m128 comb3(__m128 a, __m128 x, __m128 b, __m128 y, __m128 c, __m128 z)
{
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a, x), _mm_mul_ps(b, y)), _mm_mul_ps(c, z));
}

/* The corner normals of faces f .. f + 3: N[k] = (x, y, z) of corner k, lane i face f + i. */
static void corner_normals4(const uint32_t *v, const float *N, __m128 dest[3][4])
{
    for (int k = 0; k < 3; k++)
        load4(N + 3 * (size_t)v[k], N + 3 * (size_t)v[3 + k], N + 3 * (size_t)v[6 + k], N + 3 * (size_t)v[9 + k],
              dest[k]);
}

/* fit_tensor for faces f .. f + 3, lane by lane: the same operations in the same order. */
static void fit4(const uint32_t *v, const float *N, const face_rec *r, float *dest, uint64_t stride)
{
    __m128 A[4], B[4], C[4], D[4], nv[3][4], t[3], n[3], b[3], one = _mm_set1_ps(1), zero = _mm_setzero_ps();
    const float *p = (const float *)r;        /* the records as rows of 16 floats, read in quarters */
    load4(p, p + 16, p + 32, p + 48, A);      /* t0 t1 t2 n0 */
    load4(p + 4, p + 20, p + 36, p + 52, B);  /* n1 n2 mean diff */
    load4(p + 8, p + 24, p + 40, p + 56, C);  /* off c0 c1 c2 */
    load4(p + 12, p + 28, p + 44, p + 60, D); /* u1 w1 inv_len unused */
    corner_normals4(v, N, nv);
    t[0] = A[0], t[1] = A[1], t[2] = A[2], n[0] = A[3], n[1] = B[0], n[2] = B[1];
    b[0] = _mm_sub_ps(_mm_mul_ps(n[1], t[2]), _mm_mul_ps(n[2], t[1]));
    b[1] = _mm_sub_ps(_mm_mul_ps(n[2], t[0]), _mm_mul_ps(n[0], t[2]));
    b[2] = _mm_sub_ps(_mm_mul_ps(n[0], t[1]), _mm_mul_ps(n[1], t[0]));
    __m128 u1 = D[0], w1 = D[1], u2 = _mm_sub_ps(_mm_set1_ps(-1), u1);
    __m128 t0 = dot4(nv[0], t), t1 = dot4(nv[1], t), t2 = dot4(nv[2], t);
    __m128 b0 = dot4(nv[0], b), b1 = dot4(nv[1], b), b2 = dot4(nv[2], b);
    __m128 du0 = _mm_sub_ps(t2, t1), du1 = _mm_sub_ps(t0, t2), du2 = _mm_sub_ps(t1, t0);
    __m128 dw0 = _mm_sub_ps(b2, b1), dw1 = _mm_sub_ps(b0, b2), dw2 = _mm_sub_ps(b1, b0);
    __m128 a = _mm_add_ps(_mm_add_ps(one, _mm_mul_ps(u1, u1)), _mm_mul_ps(u2, u2));
    __m128 ab = _mm_mul_ps(w1, _mm_sub_ps(u1, u2)), c = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(2), w1), w1);
    __m128 m0 = _mm_add_ps(_mm_add_ps(du0, _mm_mul_ps(du1, u1)), _mm_mul_ps(du2, u2));
    __m128 m1 = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(w1, _mm_sub_ps(du1, du2)), dw0), _mm_mul_ps(dw1, u1)),
                           _mm_mul_ps(dw2, u2));
    __m128 m2 = _mm_mul_ps(w1, _mm_sub_ps(dw1, dw2));
    __m128 q = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(3), w1), w1), s = _mm_add_ps(a, c);
    __m128 csum = _mm_add_ps(_mm_add_ps(C[1], C[2]), C[3]);
    __m128 ok = _mm_and_ps(_mm_cmpneq_ps(csum, zero),
                           _mm_and_ps(_mm_cmpgt_ps(q, _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(1e-12f), s), s)),
                                      _mm_cmplt_ps(q, _mm_set1_ps(1e30f))));
    __m128 neg = _mm_set1_ps(-0.0f), nab = _mm_xor_ps(ab, neg);
    __m128 i00 = _mm_add_ps(q, _mm_mul_ps(c, c)), i01 = _mm_mul_ps(nab, c), i02 = _mm_mul_ps(ab, ab);
    __m128 i11 = _mm_mul_ps(a, c), i12 = _mm_mul_ps(_mm_xor_ps(a, neg), ab), i22 = _mm_add_ps(q, _mm_mul_ps(a, a));
    __m128 inv = _mm_div_ps(D[2], _mm_mul_ps(s, q));
    __m128 x0 = _mm_mul_ps(comb3(i00, m0, i01, m1, i02, m2), inv),
           x1 = _mm_mul_ps(comb3(i01, m0, i11, m1, i12, m2), inv);
    __m128 x2 = _mm_mul_ps(comb3(i02, m0, i12, m1, i22, m2), inv), half = _mm_set1_ps(0.5f);
    float out[3][4];
    _mm_storeu_ps(out[0], _mm_and_ps(ok, _mm_mul_ps(half, _mm_add_ps(x0, x2))));
    _mm_storeu_ps(out[1], _mm_and_ps(ok, _mm_mul_ps(half, _mm_sub_ps(x0, x2))));
    _mm_storeu_ps(out[2], _mm_and_ps(ok, x1));
    for (int i = 0; i < 4; i++)
        dest[stride * i] = out[0][i], dest[stride * i + 1] = out[1][i], dest[stride * i + 2] = out[2][i];
}
#endif

void mesh_rus_fit_faces(const uint32_t *faces, const float *normals, const face_rec *recs, uint64_t begin, uint64_t end,
                        float *dest, uint64_t stride)
{
    uint64_t f = begin;
#if FIT_SSE2
    for (; f + 4 <= end; f += 4) fit4(faces + 3 * f, normals, recs + f, dest + stride * f, stride);
#endif
    for (; f < end; f++) fit_face(faces + 3 * f, normals, recs + f, dest + stride * f);
}
