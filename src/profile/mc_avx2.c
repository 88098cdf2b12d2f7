/* The photon kernel in 8 lanes of AVX2 with FMA: the operations mc_lanes.h is written in, then the
 * kernel. Compiled with -mavx2 -mfma (CMakeLists.txt) and called only where lucent_isa_active()
 * says the CPU has them (mc.c). */
#include "profile/mc_internal.h"

#if defined(LUCENT_SIMD_X86) && defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#include <math.h>
#include <string.h>

#define W 8
#define MC_LANES_SUFFIX avx2

typedef __m256 vf;
typedef __m256i vi;
typedef __m256 vm; /* all ones in a lane that is set */
typedef struct vu {
    __m256i a, b; /* lanes 0-3, 4-7 */
} vu;

static inline vf v_set1(float a) { return _mm256_set1_ps(a); }
static inline vf v_load(const float *p) { return _mm256_load_ps(p); }
static inline vf v_loadu(const float *p) { return _mm256_loadu_ps(p); }
static inline void v_store(float *p, vf a) { _mm256_storeu_ps(p, a); }
static inline vf v_add(vf a, vf b) { return _mm256_add_ps(a, b); }
static inline vf v_sub(vf a, vf b) { return _mm256_sub_ps(a, b); }
static inline vf v_mul(vf a, vf b) { return _mm256_mul_ps(a, b); }
static inline vf v_div(vf a, vf b) { return _mm256_div_ps(a, b); }
static inline vf v_fma(vf a, vf b, vf c) { return _mm256_fmadd_ps(a, b, c); }   /* a b + c */
static inline vf v_fms(vf a, vf b, vf c) { return _mm256_fmsub_ps(a, b, c); }   /* a b - c */
static inline vf v_fnma(vf a, vf b, vf c) { return _mm256_fnmadd_ps(a, b, c); } /* c - a b */
static inline vf v_sqrt(vf a) { return _mm256_sqrt_ps(a); }
static inline vf v_min(vf a, vf b) { return _mm256_min_ps(a, b); } /* b where a is NaN */
static inline vf v_max(vf a, vf b) { return _mm256_max_ps(a, b); }
static inline vf v_and(vf a, vf b) { return _mm256_and_ps(a, b); }
static inline vf v_xor(vf a, vf b) { return _mm256_xor_ps(a, b); }
static inline vf v_abs(vf a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }
static inline vf v_blend(vm m, vf a, vf b) { return _mm256_blendv_ps(a, b, m); } /* m ? b : a */
static inline vf v_zero_unless(vm m, vf a) { return _mm256_and_ps(m, a); }
static inline vm v_lt(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
static inline vm v_gt(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
static inline vm v_le(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
static inline vm v_eq(vf a, vf b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
/* 1 / sqrt(a): the estimate (relative error below 1.5 2^-12) and one Newton step */
static inline vf v_rsqrt_nr(vf a)
{
    vf y = _mm256_rsqrt_ps(a);
    vf h = _mm256_mul_ps(_mm256_mul_ps(a, _mm256_set1_ps(0.5f)), y);
    return _mm256_mul_ps(y, _mm256_fnmadd_ps(h, y, _mm256_set1_ps(1.5f)));
}

static inline vi vi_set1(int32_t a) { return _mm256_set1_epi32(a); }
static inline vi vi_load(const int32_t *p) { return _mm256_load_si256((const __m256i *)p); }
static inline vi vi_loadu(const int32_t *p) { return _mm256_loadu_si256((const __m256i *)p); }
static inline void vi_store(int32_t *p, vi a) { _mm256_storeu_si256((__m256i *)p, a); }
static inline vi vi_add(vi a, vi b) { return _mm256_add_epi32(a, b); }
static inline vi vi_sub(vi a, vi b) { return _mm256_sub_epi32(a, b); }
static inline vi vi_mullo(vi a, vi b) { return _mm256_mullo_epi32(a, b); }
static inline vi vi_and(vi a, vi b) { return _mm256_and_si256(a, b); }
static inline vi vi_or(vi a, vi b) { return _mm256_or_si256(a, b); }
static inline vi vi_max(vi a, vi b) { return _mm256_max_epi32(a, b); }
static inline vm vi_gt(vi a, vi b) { return _mm256_castsi256_ps(_mm256_cmpgt_epi32(a, b)); }
static inline vm vi_eq(vi a, vi b) { return _mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b)); }
static inline vi vi_blend(vm m, vi a, vi b) { return _mm256_blendv_epi8(a, b, _mm256_castps_si256(m)); }
static inline vm vi_ne0(vi a)
{
    return _mm256_castsi256_ps(_mm256_xor_si256(_mm256_cmpeq_epi32(a, _mm256_setzero_si256()), _mm256_set1_epi32(-1)));
}
#define LOG2W 3
static inline vi vi_iota(void) { return _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7); }
#define vi_srli(a, n) _mm256_srli_epi32((a), (n))
#define vi_slli(a, n) _mm256_slli_epi32((a), (n))
#define vi_srai(a, n) _mm256_srai_epi32((a), (n))
static inline vi v_cvtt(vf a) { return _mm256_cvttps_epi32(a); }
static inline vf v_cvt(vi a) { return _mm256_cvtepi32_ps(a); }
static inline vi v_asi(vf a) { return _mm256_castps_si256(a); }
static inline vf v_asf(vi a) { return _mm256_castsi256_ps(a); }

static inline vm m_and(vm a, vm b) { return _mm256_and_ps(a, b); }
static inline vm m_or(vm a, vm b) { return _mm256_or_ps(a, b); }
static inline vm m_andnot(vm a, vm b) { return _mm256_andnot_ps(b, a); } /* a and not b */
static inline unsigned m_bits(vm a) { return (unsigned)_mm256_movemask_ps(a); }
static inline vm m_from_bits(unsigned b)
{
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)b), bit), bit));
}

/* round(a) as 64-bit integers into p[0..7] (0 <= a < 2^51, nearest): in double, a + 2^52 has a's
 * integer part in its low mantissa bits (the classic magic-number conversion; AVX2 has no
 * float-to-int64 instruction) */
static inline void v_store_fixed(int64_t *p, vf a)
{
    const __m256d magic = _mm256_set1_pd(4503599627370496.0); /* 2^52 */
    __m256d lo = _mm256_add_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(a)), magic);
    __m256d hi = _mm256_add_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(a, 1)), magic);
    _mm256_storeu_si256((__m256i *)p, _mm256_sub_epi64(_mm256_castpd_si256(lo), _mm256_castpd_si256(magic)));
    _mm256_storeu_si256((__m256i *)(p + 4), _mm256_sub_epi64(_mm256_castpd_si256(hi), _mm256_castpd_si256(magic)));
}

static inline vf v_perm(const float *tab, vi idx) { return _mm256_permutevar8x32_ps(_mm256_loadu_ps(tab), idx); }
static inline vf v_gather(const float *tab, vi idx) { return _mm256_i32gather_ps(tab, idx, 4); }

/* xoshiro256** in every lane (Blackman & Vigna 2018; lucent_rng_next lane by lane): the 64-bit
 * outputs' high and low halves as two vectors of 32-bit lanes. */
static inline vu u_load(const uint64_t *p)
{
    return (vu){_mm256_load_si256((const __m256i *)p), _mm256_load_si256((const __m256i *)(p + 4))};
}
static inline void u_store(uint64_t *p, vu a)
{
    _mm256_store_si256((__m256i *)p, a.a);
    _mm256_store_si256((__m256i *)(p + 4), a.b);
}
#define U_ROL(x, k) _mm256_or_si256(_mm256_slli_epi64((x), (k)), _mm256_srli_epi64((x), 64 - (k)))
static inline __m256i u_step(__m256i *s0, __m256i *s1, __m256i *s2, __m256i *s3)
{
    __m256i x = _mm256_add_epi64(*s1, _mm256_slli_epi64(*s1, 2)); /* s1 * 5 */
    __m256i r = U_ROL(x, 7);
    r = _mm256_add_epi64(r, _mm256_slli_epi64(r, 3)); /* * 9 */
    __m256i t = _mm256_slli_epi64(*s1, 17);
    *s2 = _mm256_xor_si256(*s2, *s0);
    *s3 = _mm256_xor_si256(*s3, *s1);
    *s1 = _mm256_xor_si256(*s1, *s2);
    *s0 = _mm256_xor_si256(*s0, *s3);
    *s2 = _mm256_xor_si256(*s2, t);
    *s3 = U_ROL(*s3, 45);
    return r;
}
static inline void u_next(vu *s0, vu *s1, vu *s2, vu *s3, vi *hi, vi *lo)
{
    __m256 ra = _mm256_castsi256_ps(u_step(&s0->a, &s1->a, &s2->a, &s3->a));
    __m256 rb = _mm256_castsi256_ps(u_step(&s0->b, &s1->b, &s2->b, &s3->b));
    /* per 128-bit half: [a0 a2 b0 b2] of the 32-bit words; then the halves' middle pairs swapped */
    __m256 h = _mm256_shuffle_ps(ra, rb, _MM_SHUFFLE(3, 1, 3, 1)),
           l = _mm256_shuffle_ps(ra, rb, _MM_SHUFFLE(2, 0, 2, 0));
    *hi = _mm256_permute4x64_epi64(_mm256_castps_si256(h), _MM_SHUFFLE(3, 1, 2, 0));
    *lo = _mm256_permute4x64_epi64(_mm256_castps_si256(l), _MM_SHUFFLE(3, 1, 2, 0));
}

#include "profile/mc_lanes.h"

#endif
