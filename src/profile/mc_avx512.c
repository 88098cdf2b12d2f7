/* The photon kernel in 16 lanes of AVX-512 (F, DQ, BW, VL): the operations mc_lanes.h is written
 * in, then the kernel. Compiled with -mavx512f -mavx512dq -mavx512bw -mavx512vl -mavx2 -mfma
 * (CMakeLists.txt) and called only where lucent_isa_active() says the CPU has them (mc.c). */
#include "profile/mc_internal.h"

#if defined(LUCENT_SIMD_X86) && defined(__AVX512F__) && defined(__AVX512DQ__) && defined(__AVX512BW__) &&              \
    defined(__AVX512VL__) && defined(__FMA__)
#include <immintrin.h>
#include <math.h>
#include <string.h>

#define W 16
#define MC_LANES_SUFFIX avx512

typedef __m512 vf;
typedef __m512i vi;
typedef __mmask16 vm;
typedef struct vu {
    __m512i a, b; /* lanes 0-7, 8-15 */
} vu;

static inline vf v_set1(float a) { return _mm512_set1_ps(a); }
static inline vf v_load(const float *p) { return _mm512_load_ps(p); }
static inline vf v_loadu(const float *p) { return _mm512_loadu_ps(p); }
static inline void v_store(float *p, vf a) { _mm512_storeu_ps(p, a); }
static inline vf v_add(vf a, vf b) { return _mm512_add_ps(a, b); }
static inline vf v_sub(vf a, vf b) { return _mm512_sub_ps(a, b); }
static inline vf v_mul(vf a, vf b) { return _mm512_mul_ps(a, b); }
static inline vf v_div(vf a, vf b) { return _mm512_div_ps(a, b); }
static inline vf v_fma(vf a, vf b, vf c) { return _mm512_fmadd_ps(a, b, c); }   /* a b + c */
static inline vf v_fms(vf a, vf b, vf c) { return _mm512_fmsub_ps(a, b, c); }   /* a b - c */
static inline vf v_fnma(vf a, vf b, vf c) { return _mm512_fnmadd_ps(a, b, c); } /* c - a b */
static inline vf v_sqrt(vf a) { return _mm512_sqrt_ps(a); }
static inline vf v_min(vf a, vf b) { return _mm512_min_ps(a, b); } /* b where a is NaN */
static inline vf v_max(vf a, vf b) { return _mm512_max_ps(a, b); }
static inline vf v_abs(vf a) { return _mm512_abs_ps(a); }
static inline vf v_and(vf a, vf b) { return _mm512_and_ps(a, b); }
static inline vf v_xor(vf a, vf b) { return _mm512_xor_ps(a, b); }
static inline vf v_blend(vm m, vf a, vf b) { return _mm512_mask_blend_ps(m, a, b); } /* m ? b : a */
static inline vf v_zero_unless(vm m, vf a) { return _mm512_maskz_mov_ps(m, a); }
static inline vm v_lt(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
static inline vm v_gt(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
static inline vm v_le(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
static inline vm v_eq(vf a, vf b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }
/* 1 / sqrt(a): the estimate (relative error below 2^-14) and one Newton step */
static inline vf v_rsqrt_nr(vf a)
{
    vf y = _mm512_rsqrt14_ps(a);
    vf h = _mm512_mul_ps(_mm512_mul_ps(a, _mm512_set1_ps(0.5f)), y);
    return _mm512_mul_ps(y, _mm512_fnmadd_ps(h, y, _mm512_set1_ps(1.5f)));
}

static inline vi vi_set1(int32_t a) { return _mm512_set1_epi32(a); }
static inline vi vi_load(const int32_t *p) { return _mm512_load_si512(p); }
static inline vi vi_loadu(const int32_t *p) { return _mm512_loadu_si512(p); }
static inline void vi_store(int32_t *p, vi a) { _mm512_storeu_si512(p, a); }
static inline vi vi_add(vi a, vi b) { return _mm512_add_epi32(a, b); }
static inline vi vi_sub(vi a, vi b) { return _mm512_sub_epi32(a, b); }
static inline vi vi_mullo(vi a, vi b) { return _mm512_mullo_epi32(a, b); }
static inline vi vi_and(vi a, vi b) { return _mm512_and_si512(a, b); }
static inline vi vi_or(vi a, vi b) { return _mm512_or_si512(a, b); }
static inline vi vi_max(vi a, vi b) { return _mm512_max_epi32(a, b); }
static inline vm vi_gt(vi a, vi b) { return _mm512_cmpgt_epi32_mask(a, b); }
static inline vm vi_eq(vi a, vi b) { return _mm512_cmpeq_epi32_mask(a, b); }
static inline vi vi_blend(vm m, vi a, vi b) { return _mm512_mask_blend_epi32(m, a, b); } /* m ? b : a */
static inline vm vi_ne0(vi a) { return _mm512_test_epi32_mask(a, a); }
#define LOG2W 4
static inline vi vi_iota(void) { return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15); }
#define vi_srli(a, n) _mm512_srli_epi32((a), (n))
#define vi_slli(a, n) _mm512_slli_epi32((a), (n))
#define vi_srai(a, n) _mm512_srai_epi32((a), (n))
static inline vi v_cvtt(vf a) { return _mm512_cvttps_epi32(a); }
static inline vf v_cvt(vi a) { return _mm512_cvtepi32_ps(a); }
static inline vi v_asi(vf a) { return _mm512_castps_si512(a); }
static inline vf v_asf(vi a) { return _mm512_castsi512_ps(a); }

static inline vm m_and(vm a, vm b) { return (vm)(a & b); }
static inline vm m_or(vm a, vm b) { return (vm)(a | b); }
static inline vm m_andnot(vm a, vm b) { return (vm)(a & ~b); } /* a and not b */
static inline unsigned m_bits(vm a) { return (unsigned)a; }
static inline vm m_from_bits(unsigned b) { return (vm)b; }

/* round(a) as 64-bit integers into p[0..15] (|a| < 2^62; nearest, the MXCSR default) */
static inline void v_store_fixed(int64_t *p, vf a)
{
    _mm512_storeu_si512(p, _mm512_cvtps_epi64(_mm512_castps512_ps256(a)));
    _mm512_storeu_si512(p + 8, _mm512_cvtps_epi64(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a), 1))));
}

static inline vf v_perm(const float *tab, vi idx) { return _mm512_permutexvar_ps(idx, _mm512_loadu_ps(tab)); }
static inline vf v_gather(const float *tab, vi idx) { return _mm512_i32gather_ps(idx, tab, 4); }

/* xoshiro256** in every lane (Blackman & Vigna 2018; lucent_rng_next lane by lane): the 64-bit
 * outputs' high and low halves as two vectors of 32-bit lanes. */
static inline vu u_load(const uint64_t *p) { return (vu){_mm512_load_si512(p), _mm512_load_si512(p + 8)}; }
static inline void u_store(uint64_t *p, vu a)
{
    _mm512_store_si512(p, a.a);
    _mm512_store_si512(p + 8, a.b);
}
static inline __m512i u_step(__m512i *s0, __m512i *s1, __m512i *s2, __m512i *s3)
{
    __m512i x = _mm512_add_epi64(*s1, _mm512_slli_epi64(*s1, 2)); /* s1 * 5 */
    __m512i r = _mm512_rol_epi64(x, 7);
    r = _mm512_add_epi64(r, _mm512_slli_epi64(r, 3)); /* * 9 */
    __m512i t = _mm512_slli_epi64(*s1, 17);
    *s2 = _mm512_xor_si512(*s2, *s0);
    *s3 = _mm512_xor_si512(*s3, *s1);
    *s1 = _mm512_xor_si512(*s1, *s2);
    *s0 = _mm512_xor_si512(*s0, *s3);
    *s2 = _mm512_xor_si512(*s2, t);
    *s3 = _mm512_rol_epi64(*s3, 45);
    return r;
}
static inline void u_next(vu *s0, vu *s1, vu *s2, vu *s3, vi *hi, vi *lo)
{
    __m512i ra = u_step(&s0->a, &s1->a, &s2->a, &s3->a);
    __m512i rb = u_step(&s0->b, &s1->b, &s2->b, &s3->b);
    const __m512i odd = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    *hi = _mm512_permutex2var_epi32(ra, odd, rb);
    *lo = _mm512_permutex2var_epi32(ra, even, rb);
}

#include "profile/mc_lanes.h"

#endif
