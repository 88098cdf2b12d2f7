/* The photon kernel across SIMD lanes: the physics of mc_transport.c (MCML's hop, drop, spin,
 * roulette; Wang, Jacques & Zheng 1995, section 3; equations as in the MCML manual, chapter 3),
 * W photon packets at once, one per lane. Included by mc_avx2.c (W = 8) and mc_avx512.c (W = 16)
 * after each defines W, its vector types and the v_* operations on them; docs/mcml.md, "SIMD paths".
 *
 * The steps run in the lanes: an interaction inside a layer (move, drop, spin), or a boundary
 * (move to it, Fresnel, reflect or refract into the neighbouring layer). What happens about once per
 * photon (an escape and its scores, roulette, the step limit, clear layers) runs per lane in scalar
 * code on the lanes' state in memory, and a lane whose photon ended takes the chunk's next photon at
 * once. Scores:
 *   - absorption per interaction: each step appends its W (counter, cell, weight) triples to a log
 *     that a tight scalar loop adds to the fixed-point counters every LOG_ROWS steps (the misses on
 *     the A(r, z) grid then overlap, as in mc_transport.c). The counter is the lane's own bin
 *     iz + layer of its batch (the a_zl layout of mc_internal.h: one array for A(z) and A per layer;
 *     lanes that score the same bin at once do not wait on each other's additions), added to the
 *     batch's a_zl when the lane moves to another batch and at the chunk's end; mc.c folds a_zl into
 *     A(z) and A per layer after the run, so a packet changing layer scores nothing;
 *   - R and T (r, angle) when a packet escapes, per lane.
 * All scores are integers (weight x plan->scale), so their order does not matter.
 *
 * Random numbers: each lane has its own xoshiro256** state (Blackman & Vigna 2018), seeded at the
 * start of a chunk by hashing a key drawn from the chunk's stream (lucent_rng_init(seed, chunk)) with
 * the lane's number (lucent_rng_init(key, lane)); lanes take the chunk's photons in order as they
 * free up. A chunk is thus a function of its stream alone, and
 * a run is identical for any thread or process count. Every step takes one 64-bit draw per lane
 * (24 bits for the step length, 20 for the deflection, 20 for the azimuth; at a boundary the
 * deflection's 20 bits decide between reflection and refraction), made DRAW_ROWS steps ahead in a
 * loop of their own; roulette and clear layers draw from a second state per lane.
 *
 * Floating point: float, as the scalar kernel; the approximations (one each, tested against libm by
 * tests/test_mc_simd.c) are
 *   - -ln(u), u = m 2^-24, m in [1, 2^24]: exponent from the float's bits, ln of the mantissa by a
 *     degree-7 polynomial (the scalar kernel's): relative error at most 3.1e-7 over every m;
 *   - cos and sin of the azimuth (a quarter-turn index and t in [-pi/4, pi/4)): Taylor polynomials of
 *     degree 8 and 9 (the scalar kernel's): absolute error below 1e-7 with float rounding;
 *   - Henyey-Greenstein's cos theta (MCML manual eq. 3.28) rewritten without cancellation:
 *     cos theta = (k0 + p (k1 + p k2)) / (1 - |g| + |g| p)^2 with p = 2 xi (2 (1 - xi) for g < 0, the
 *     result negated), k0 = -(1 - |g|)^2, k1 = (1 + g^2)(1 - |g|), k2 = |g| (1 + g^2) / 2: absolute
 *     error below 4e-7 for every g in [-1, 1] (the usual float formula loses 1e-3 at |g| = 1e-4,
 *     which is why the scalar kernel goes to double there);
 *   - 1 / sqrt(1 - uz^2) in the rotation: the hardware estimate (2^-14 or 1.5 2^-12) and one Newton
 *     step, and the direction is renormalised by a Newton step after every rotation (as in the
 *     scalar kernel);
 *   - Fresnel's reflectance (MCML manual eq. 3.36, base/optics.h's formula) in float: absolute
 *     error below 1e-6 (the reflection decision compares it with a 20-bit uniform) except within
 *     0.015 of the critical angle's cosine, where R falls from 1 with an infinite slope and the
 *     refracted cosine, sqrt(1 - (1 - ca1^2) (n_i / n_t)^2), loses digits: at most 2.6e-4 there
 *     (measured against the double formula over 10^6 cosines for 11 index pairs, 1-1.5);
 * Except there, each is a deterministic function of its 20 or 24 random bits whose error is below 1e-6 of the
 * quantity: it moves a sampled step or angle by less than the float rounding of the position it
 * is added to, far below what any score can resolve (1e-6 of a step shifts Rd by about 1e-7; the
 * statistical errors of the tests are 1e-4 and more). They do not bias the physics. */

#define MC_WEIGHT_L 1e-4f /* roulette threshold (MCML's WEIGHT) */
#define MC_CHANCE_L 0.1f  /* roulette survival (MCML's CHANCE) */
#define LOG_ROWS 64       /* steps logged between flushes */
#define LOG_N (LOG_ROWS * W)
#define DRAW_ROWS 16 /* steps whose random numbers are made at once */
#define DRAW_N (DRAW_ROWS * W)
#define TAB_N 128 /* layer tables: LUCENT_MC_MAX_LAYERS rounded up, at least W */

#define MC_CAT2(a, b) a##_##b
#define MC_CAT(a, b) MC_CAT2(a, b)
#define MC_FN(name) MC_CAT(name, MC_LANES_SUFFIX)

/* The lanes' state, in memory for the scalar rare-event code (the vector loop keeps it in registers). */
typedef struct lanes {
    _Alignas(64) float x[W], y[W], z[W], ux[W], uy[W], uz[W];
    float w[W];     /* packet weight */
    float sleft[W]; /* step left after a boundary, in mean free paths (0: draw a new one) */
    float ca2[W];   /* the exit cosine of a packet that escapes (for its scores) */
    int32_t layer[W], steps[W];
    int32_t bbase[W];                    /* the photon's batch: offset of its counters */
    uint64_t r0[W], r1[W], r2[W], r3[W]; /* the steps' xoshiro256** state, word k of lane i in rk[i] */
    uint64_t e0[W], e1[W], e2[W], e3[W]; /* a second one for roulette and clear layers */
    unsigned active;                     /* lanes holding a photon */
} lanes;

/* Per-layer constants as tables indexed by layer (permuted or gathered into lanes). */
typedef struct layer_tabs {
    _Alignas(64) float z0[TAB_N], z1[TAB_N], inv_mut[TAB_N], absorb[TAB_N], clear[TAB_N];
    float k0[TAB_N], k1[TAB_N], k2[TAB_N], m0[TAB_N], g[TAB_N], pv[TAB_N], po[TAB_N]; /* HG */
    float mut[TAB_N];
    /* the boundaries above (u) and below (d): n_beyond / n, its inverse squared, cos of the critical angle */
    float eta_u[TAB_N], eta_d[TAB_N], ie_u[TAB_N], ie_d[TAB_N], ie2_u[TAB_N], ie2_d[TAB_N], cc_u[TAB_N], cc_d[TAB_N];
} layer_tabs;

typedef struct kctx {
    const mc_plan *plan;
    int64_t *batch, *grid;
    int64_t *zl;        /* per lane: the a_zl counters of the lane's batch bacc, bin v of lane i at v W + i */
    int32_t bacc[W];    /* the batch (counter offset) zl holds for each lane, -1: none yet */
    int arz;            /* A(r, z) is scored */
    int any_clear;      /* a layer is clear (its lanes go to lane_glass) */
    int any_backward;   /* a layer has g < 0 (HG's xi reversed there) */
    int inner_bends;    /* two neighbouring layers differ in index */
    uint64_t next, end; /* the chunk's photons not yet launched */
    unsigned active;    /* lanes holding a photon */
    int32_t zlim, rlim; /* bin clamps */
    int n_log;
    /* the arrays the vectors load and store whole: aligned to the widest vector (aligned loads of
     * misaligned fields are undefined; UBSan caught it when the fields before them ended at 16 mod 32) */
    _Alignas(64) int32_t log_z[LOG_N]; /* the lane's counter of the depth-and-layer bin, in zl */
    _Alignas(64) int32_t log_c[LOG_N]; /* cell of A(r, z) */
    _Alignas(64) int64_t log_q[LOG_N]; /* absorbed weight, fixed point (weight x plan->scale) */
    /* the next DRAW_ROWS steps' random numbers, every lane's in a row (draws_fill) */
    _Alignas(64) float d_step[DRAW_N], d_xi[DRAW_N], d_cp[DRAW_N], d_sp[DRAW_N], d_c[DRAW_N], d_st[DRAW_N];
    int prefetch; /* the A(r, z) grid is larger than the caches */
    layer_tabs t;
} kctx;

/* ---- per lane, scalar ---- */

static inline uint64_t lane_next(lanes *S, int i)
{
    uint64_t s0 = S->e0[i], s1 = S->e1[i], s2 = S->e2[i], s3 = S->e3[i];
    uint64_t x = s1 * 5u, result = ((x << 7) | (x >> 57)) * 9u, t = s1 << 17;
    s2 ^= s0;
    s3 ^= s1;
    s1 ^= s2;
    s0 ^= s3;
    s2 ^= t;
    s3 = (s3 << 45) | (s3 >> 19);
    S->e0[i] = s0, S->e1[i] = s1, S->e2[i] = s2, S->e3[i] = s3;
    return result;
}

static inline float lane_uniform(lanes *S, int i) { return (float)(lane_next(S, i) >> 40) * 5.9604644775390625e-8f; }

static inline int64_t lane_fixed(const mc_plan *p, double w) { return (int64_t)(w * p->scale + 0.5); }

/* Adds the logged absorption to its counters (the weights converted to fixed point in the lanes): the
 * lanes' own depth-and-layer counters (lanes that score the same bin at once do not then wait on each
 * other's additions) and the shared A(r, z) grid,
 * on a large A(r, z) grid prefetching the cells LOG_AHEAD entries ahead (the prefetches retire at
 * once, so more misses overlap than the reorder window alone allows). */
#define LOG_AHEAD 48
#define LOG_PREFETCH_BYTES (256 << 10) /* grids smaller than this stay in the caches */

static void log_flush_z(kctx *k)
{
    int64_t *b = k->zl;
#pragma GCC unroll 4
    for (int j = 0; j < k->n_log; j++) b[k->log_z[j]] += k->log_q[j];
    k->n_log = 0;
}

static void log_flush_rz(kctx *k)
{
    int64_t *b = k->zl, *g = k->grid + k->plan->lay.a_rz;
    int n = k->n_log, j = 0;
    if (k->prefetch)
#pragma GCC unroll 4
        for (; j < n - LOG_AHEAD; j++) {
            __builtin_prefetch(g + k->log_c[j + LOG_AHEAD], 1, 3);
            b[k->log_z[j]] += k->log_q[j];
            g[k->log_c[j]] += k->log_q[j];
        }
#pragma GCC unroll 4
    for (; j < n; j++) {
        b[k->log_z[j]] += k->log_q[j];
        g[k->log_c[j]] += k->log_q[j];
    }
    k->n_log = 0;
}

static inline void log_flush(kctx *k, int arz)
{
    if (arz)
        log_flush_rz(k);
    else
        log_flush_z(k);
}

/* Adds lane i's counters (and what the log holds for them) to its batch's a_zl and zeroes them. */
static void lane_counters_out(kctx *k, int i)
{
    const mc_plan *p = k->plan;
    log_flush(k, k->arz);
    int64_t *dest = k->batch + k->bacc[i] + p->lay.a_zl, *src = k->zl + i;
    for (int v = 0; v < p->nz + p->layer_count; v++) dest[v] += src[(size_t)v * W], src[(size_t)v * W] = 0;
}

/* The lane takes the chunk's next photon, or goes idle (a valid state that scores nothing). */
static void lane_launch(kctx *k, lanes *S, int i)
{
    const mc_plan *p = k->plan;
    S->x[i] = S->y[i] = 0.0f;
    S->z[i] = p->launch_z;
    S->ux[i] = S->uy[i] = 0.0f;
    S->uz[i] = 1.0f;
    S->w[i] = p->w_launch;
    S->sleft[i] = 0.0f;
    S->layer[i] = p->launch_layer;
    S->steps[i] = 0;
    S->bbase[i] = 0;
    if (k->next == k->end) {
        S->active &= ~(1u << i);
        S->w[i] = 1.0f;
        return;
    }
    uint64_t photon = k->next++;
    uint64_t b = photon * (uint64_t)p->batches / p->photons; /* contiguous photon ranges */
    S->bbase[i] = (int32_t)(b * p->lay.batch_size);
    S->active |= 1u << i;
    if (k->bacc[i] != S->bbase[i]) { /* the lane's counters go to the batch they were made in */
        if (k->bacc[i] >= 0) lane_counters_out(k, i);
        k->bacc[i] = S->bbase[i];
    }
}

/* Scores a packet leaving through the top (up) or the bottom with exit cosine ca (outside). */
static void lane_exit(kctx *k, lanes *S, int i, float ca, int up)
{
    const mc_plan *p = k->plan;
    const mc_layout *l = &p->lay;
    int64_t w = lane_fixed(p, S->w[i]);
    float rb = sqrtf(S->x[i] * S->x[i] + S->y[i] * S->y[i]) * p->inv_dr;
    int ir = rb >= (float)p->r_lim ? p->r_lim : (int)rb;
    int ia = 0;
    if (p->na > 1) {
        ia = (int)(acosf(ca < 0.0f ? 0.0f : ca > 1.0f ? 1.0f : ca) * (float)p->inv_da);
        if (ia > p->na - 1) ia = p->na - 1;
    }
    int64_t *b = k->batch + S->bbase[i];
    b[(up ? l->rd_r : l->tt_r) + (size_t)ir] += w;
    b[(up ? l->rd_a : l->tt_a) + (size_t)ia] += w;
    k->grid[(up ? l->rd_ra : l->tt_ra) + (size_t)ir * (size_t)p->na + (size_t)ia] += w;
}

/* The packet sits on the top (up) or bottom boundary of its layer: reflect, refract into the
 * neighbour, or escape (MCML's CrossUpOrNot / CrossDnOrNot; MCML manual eqs. 3.35, 3.36 through
 * base/optics.h, in double). Returns 1 when it escaped. */
static int lane_cross(kctx *k, lanes *S, int i, int up)
{
    const mc_plan *p = k->plan;
    const mc_layer_k *L = &p->layers[S->layer[i]];
    float ca1 = fabsf(S->uz[i]), ca2 = ca1, r;
    float nt = up ? L->n_up : L->n_down;
    if (ca1 <= (up ? L->cos_crit_up : L->cos_crit_down)) {
        r = 1.0f; /* total internal reflection */
    } else {
        double ct;
        r = (float)lucent_fresnel_dielectric(ca1, (double)nt / L->n, &ct);
        ca2 = (float)ct;
    }
    if (r >= 1.0f || (r > 0.0f && lane_uniform(S, i) < r)) {
        S->uz[i] = -S->uz[i];
        return 0;
    }
    if ((up && S->layer[i] == 0) || (!up && S->layer[i] == p->layer_count - 1)) {
        lane_exit(k, S, i, ca2, up);
        return 1;
    }
    float kk = L->n / nt;
    S->ux[i] *= kk;
    S->uy[i] *= kk;
    S->uz[i] = up ? -ca2 : ca2;
    S->layer[i] += up ? -1 : 1;
    return 0;
}

/* A clear layer (MCML's HopInGlass): straight to the boundary and across. Returns 1 when the packet
 * ended (escaped, or lost flying parallel to the layers, as in mc_transport.c). */
static int lane_glass(kctx *k, lanes *S, int i)
{
    const mc_layer_k *L = &k->plan->layers[S->layer[i]];
    if (S->uz[i] == 0.0f) return 1;
    int up = S->uz[i] < 0.0f;
    float zb = up ? L->z0 : L->z1, d = (zb - S->z[i]) / S->uz[i];
    S->x[i] += d * S->ux[i];
    S->y[i] += d * S->uy[i];
    S->z[i] = zb;
    return lane_cross(k, S, i, up);
}

/* Every rare event of lane i after a step: `esc` (the packet escaped through a boundary: its exit
 * cosine in ca2[i]), `roul` (its weight fell below MC_WEIGHT_L in an interaction); clear layers and
 * the step limit are read here. */
static void lane_rare(kctx *k, lanes *S, int i, int esc, int roul)
{
    int ended = 0;
    if (k->plan->layers[S->layer[i]].clear) {
        ended = lane_glass(k, S, i);
    } else if (esc) {
        lane_exit(k, S, i, S->ca2[i], S->uz[i] < 0.0f);
        ended = 1;
    } else if (roul) { /* Russian roulette (MCML manual section 3.8) */
        if (lane_uniform(S, i) < MC_CHANCE_L)
            S->w[i] = S->w[i] / MC_CHANCE_L;
        else
            ended = 1;
    }
    if (!ended && S->steps[i] >= LUCENT_MC_MAX_STEPS) { /* dropped unscored, counted */
        k->batch[S->bbase[i] + (int32_t)k->plan->lay.capped]++;
        ended = 1;
    }
    if (ended) lane_launch(k, S, i);
}

/* ---- the lanes ---- */

/* -ln(m 2^-24) for m in [1, 2^24] (MCML manual eq. 3.19), as neg_log_u24 in mc_transport.c:
 * m = 2^e f, f in [sqrt(1/2), sqrt(2)), ln f = t P(t), t = f - 1. */
static inline vf v_neglog24(vi m)
{
    vi ix = vi_sub(v_asi(v_cvt(m)), vi_set1(0x3F3504F3));
    vi e = vi_srai(ix, 23);
    vf t = v_sub(v_asf(vi_add(vi_and(ix, vi_set1(0x7FFFFF)), vi_set1(0x3F3504F3))), v_set1(1.0f));
    vf p = v_set1(-0.0989535074f);
    p = v_fma(p, t, v_set1(0.161262479f));
    p = v_fma(p, t, v_set1(-0.172782061f));
    p = v_fma(p, t, v_set1(0.199133479f));
    p = v_fma(p, t, v_set1(-0.24968907f));
    p = v_fma(p, t, v_set1(0.33334606f));
    p = v_fma(p, t, v_set1(-0.500003751f));
    p = v_fma(p, t, v_set1(0.999999968f));
    return v_fnma(t, p, v_mul(v_cvt(vi_sub(vi_set1(24), e)), v_set1(0.693147180559945f)));
}

/* cos and sin of phi = quarter pi/2 + t, t uniform in [-pi/4, pi/4), from 20 bits (the top two
 * the quarter): Taylor series at 0 to degree 8 and 9, then the quarter-turn (mc_transport.c). */
static inline void v_sincos20(vi ph, vf *c_out, vf *s_out)
{
    vf t = v_fma(v_cvt(vi_and(ph, vi_set1(0x3FFFF))), v_set1(5.9921124e-6f), v_set1(2.9960562e-6f - 0.78539816f));
    vf t2 = v_mul(t, t);
    vf c = v_fma(t2, v_set1(1.0f / 40320), v_set1(-1.0f / 720));
    c = v_fma(c, t2, v_set1(1.0f / 24));
    c = v_fma(c, t2, v_set1(-0.5f));
    c = v_fma(c, t2, v_set1(1.0f));
    vf s = v_fma(t2, v_set1(1.0f / 362880), v_set1(-1.0f / 5040));
    s = v_fma(s, t2, v_set1(1.0f / 120));
    s = v_fma(s, t2, v_set1(-1.0f / 6));
    s = v_mul(v_fma(s, t2, v_set1(1.0f)), t);
    vm odd = vi_ne0(vi_and(ph, vi_set1(1 << 18)));
    vf sign = v_asf(vi_slli(vi_and(ph, vi_set1(1 << 19)), 12)); /* bit 19 to the sign bit */
    vf c1 = v_blend(odd, c, v_xor(s, v_set1(-0.0f))), s1 = v_blend(odd, s, c);
    *c_out = v_xor(c1, sign);
    *s_out = v_xor(s1, sign);
}

/* Henyey-Greenstein's cos theta from xi in (0, 1), in the cancellation-free form of the header. */
static inline vf v_hg(vf xi, vf k0, vf k1, vf k2, vf m0, vf g, vf pv, vf po)
{
    vf p = v_fma(xi, pv, po);
    vf d = v_fma(g, p, m0);
    vf mu = v_div(v_fma(p, v_fma(p, k2, k1), k0), v_mul(d, d)); /* d > 0 */
    return v_min(v_max(mu, v_set1(-1.0f)), v_set1(1.0f));
}

/* A layer's constant for every lane: broadcast (one layer), permuted (up to W) or gathered. */
#define LAYER_GET(tab, lay) (MULTI == 0 ? v_set1((tab)[0]) : MULTI == 1 ? v_perm((tab), (lay)) : v_gather((tab), (lay)))

/* The random numbers of the lanes' next DRAW_ROWS steps, made in a loop of their own (the step loop
 * then keeps its registers for the photons): one 64-bit draw per lane and step, 24 bits for the step
 * length, 20 for xi (HG's deflection; at a boundary the reflection's uniform), 20 for the azimuth.
 * With one layer, the deflection's cos theta and sin theta too. */
static inline __attribute__((always_inline)) void draws_fill(kctx *k, lanes *S, const int MULTI, const int ISO)
{
    const layer_tabs *T = &k->t;
    vu r0 = u_load(S->r0), r1 = u_load(S->r1), r2 = u_load(S->r2), r3 = u_load(S->r3);
    for (int j = 0; j < DRAW_N; j += W) {
        vi hi, lo;
        u_next(&r0, &r1, &r2, &r3, &hi, &lo);
        vf xi = v_mul(v_add(v_cvt(vi_srli(lo, 12)), v_set1(0.5f)), v_set1(9.5367431640625e-7f)); /* (0, 1) */
        vf cp, sp;
        v_sincos20(vi_or(vi_slli(vi_and(lo, vi_set1(0xFFF)), 8), vi_and(hi, vi_set1(0xFF))), &cp, &sp);
        v_store(k->d_step + j, v_neglog24(vi_add(vi_srli(hi, 8), vi_set1(1))));
        v_store(k->d_xi + j, xi);
        v_store(k->d_cp + j, cp);
        v_store(k->d_sp + j, sp);
        if (ISO) { /* cos theta = 1 - 2 xi, sin theta = 2 sqrt(xi (1 - xi)) */
            v_store(k->d_c + j, v_fnma(v_set1(2.0f), xi, v_set1(1.0f)));
            v_store(k->d_st + j, v_mul(v_set1(2.0f), v_sqrt(v_mul(xi, v_sub(v_set1(1.0f), xi)))));
        } else if (!MULTI) {
            vf c = v_hg(xi, v_set1(T->k0[0]), v_set1(T->k1[0]), v_set1(T->k2[0]), v_set1(T->m0[0]), v_set1(T->g[0]),
                        v_set1(T->pv[0]), v_set1(T->po[0]));
            v_store(k->d_c + j, c);
            v_store(k->d_st + j, v_sqrt(v_max(v_fnma(c, c, v_set1(1.0f)), v_set1(0.0f))));
        }
    }
    u_store(S->r0, r0), u_store(S->r1, r1), u_store(S->r2, r2), u_store(S->r3, r3);
}

/* Runs the chunk's photons through the lanes. (Two groups of lanes stepped in turn, so that their
 * chains of dependent operations overlap, ran 4-9% slower on a loaded Sapphire Rapids: the core was
 * short of issue slots, not of independent work.) */
static inline __attribute__((always_inline)) void lanes_run(kctx *k, lanes *S, const int MULTI, const int ARZ,
                                                            const int ISO)
{
    const mc_plan *p = k->plan;
    const layer_tabs *T = &k->t;
    const vf inv_dz = v_set1(p->inv_dz), inv_dr = v_set1(p->inv_dr);
    const vf zlim = v_set1((float)k->zlim), rlim = v_set1((float)k->rlim);
    const vi lane_id = vi_iota(), stride = vi_set1(p->nz + 1), izero = vi_set1(0);
    const vi last = vi_set1(p->layer_count - 1);
    const vf zero = v_set1(0.0f), one = v_set1(1.0f), sign = v_set1(-0.0f), qscale = v_set1((float)p->scale);
    const int any_clear = k->any_clear, any_backward = k->any_backward, inner_bends = k->inner_bends;
    vf x = v_load(S->x), y = v_load(S->y), z = v_load(S->z);
    vf ux = v_load(S->ux), uy = v_load(S->uy), uz = v_load(S->uz);
    vf w = v_load(S->w), sleft = v_load(S->sleft);
    vi layer = vi_load(S->layer), steps = vi_load(S->steps), bbase = vi_load(S->bbase);
    vm act = m_from_bits(S->active);
    for (int row = DRAW_N;; row += W) {
        if (row == DRAW_N) draws_fill(k, S, MULTI, ISO), row = 0;
        vf step = v_load(k->d_step + row), xi = v_load(k->d_xi + row);

        /* hop (MCML manual eq. 3.19; the rest of a step after a boundary) */
        vm live = act;
        if (MULTI && any_clear) live = m_andnot(live, v_gt(LAYER_GET(T->clear, layer), zero)); /* lane_glass */
        vf s = v_mul(v_blend(v_gt(sleft, zero), step, sleft), LAYER_GET(T->inv_mut, layer));
        vf zn = v_fma(s, uz, z);
        vf z0 = LAYER_GET(T->z0, layer), z1 = LAYER_GET(T->z1, layer);
        vm hit = m_and(live, m_or(v_gt(zn, z1), v_lt(zn, z0)));
        vm inter = m_andnot(live, hit);
        vf xn = v_fma(s, ux, x), yn = v_fma(s, uy, y);

        /* drop (MCML manual eq. 3.23; exact when absorb <= 1/2, Sterbenz) and its log entry */
        vf w1 = v_fnma(w, LAYER_GET(T->absorb, layer), w);
        vf q = v_zero_unless(inter, v_sub(w, w1));
        vi iz = vi_max(v_cvtt(v_min(v_mul(zn, inv_dz), zlim)), izero);
        vi zi = vi_add(vi_slli(MULTI ? vi_add(iz, layer) : iz, LOG2W), lane_id); /* the lane's own counter */
        if (ARZ) {
            vf rb = v_min(v_mul(v_sqrt(v_fma(xn, xn, v_mul(yn, yn))), inv_dr), rlim);
            vi_store(k->log_c + k->n_log, vi_add(vi_mullo(vi_max(v_cvtt(rb), izero), stride), iz));
        }
        vi_store(k->log_z + k->n_log, zi);
        v_store_fixed(k->log_q + k->n_log, v_mul(q, qscale)); /* q scale is exact: a power of two */
        k->n_log += W;

        /* spin (MCML manual eqs. 3.28 to 3.31) */
        vf cp = v_load(k->d_cp + row), sp = v_load(k->d_sp + row);
        vf nx, ny, nz;
        if (ISO) { /* isotropic: the new direction does not depend on the old (as mc_transport.c) */
            vf st = v_load(k->d_st + row);
            nx = v_mul(st, cp);
            ny = v_mul(st, sp);
            nz = v_load(k->d_c + row);
        } else {
            vf c, st;
            if (MULTI) {
                c = v_hg(xi, LAYER_GET(T->k0, layer), LAYER_GET(T->k1, layer), LAYER_GET(T->k2, layer),
                         LAYER_GET(T->m0, layer), LAYER_GET(T->g, layer),
                         any_backward ? LAYER_GET(T->pv, layer) : v_set1(2.0f),
                         any_backward ? LAYER_GET(T->po, layer) : zero);
                st = v_sqrt(v_max(v_fnma(c, c, one), zero));
            } else {
                c = v_load(k->d_c + row), st = v_load(k->d_st + row);
            }
            vf qz = v_fnma(uz, uz, one);
            vf kq = v_mul(st, v_rsqrt_nr(v_max(qz, v_set1(1e-20f)))); /* sin theta / sqrt(1 - uz^2) */
            vf cpuz = v_mul(cp, uz);
            nx = v_fma(kq, v_fms(ux, cpuz, v_mul(uy, sp)), v_mul(ux, c));
            ny = v_fma(kq, v_fma(uy, cpuz, v_mul(ux, sp)), v_mul(uy, c));
            nz = v_fnma(v_mul(kq, qz), cp, v_mul(uz, c));
            vm pole = v_gt(v_abs(uz), v_set1(0.99999f));
            nx = v_blend(pole, nx, v_mul(st, cp));
            ny = v_blend(pole, ny, v_mul(st, sp));
            nz = v_blend(pole, nz, v_xor(c, v_and(uz, sign)));
            vf f = v_fnma(v_set1(0.5f), v_fma(nx, nx, v_fma(ny, ny, v_mul(nz, nz))), v_set1(1.5f));
            nx = v_mul(nx, f), ny = v_mul(ny, f), nz = v_mul(nz, f);
        }
        x = v_blend(inter, x, xn);
        y = v_blend(inter, y, yn);
        z = v_blend(inter, z, zn);
        w = v_blend(inter, w, w1);
        sleft = v_blend(inter, sleft, zero);
        ux = v_blend(inter, ux, nx);
        uy = v_blend(inter, uy, ny);
        uz = v_blend(inter, uz, nz);

        /* boundaries (MCML manual section 3.6): move there, keep the rest of the step in mean free
         * paths; reflect with Fresnel's probability (eq. 3.36, the formula of base/optics.h; total
         * internal reflection below the critical angle, eq. 3.34), else refract into the next layer
         * (eq. 3.35) or escape */
        vm esc = m_from_bits(0), up = v_lt(uz, zero);
        vf ca2 = zero;
        if (m_bits(hit)) {
            vf db = v_min(v_max(v_div(v_sub(v_blend(up, z1, z0), z), uz), zero), s); /* NaN: 0 */
            x = v_blend(hit, x, v_fma(db, ux, x));
            y = v_blend(hit, y, v_fma(db, uy, y));
            z = v_blend(hit, z, v_blend(up, z1, z0));
            sleft = v_blend(hit, sleft, v_mul(v_sub(s, db), LAYER_GET(T->mut, layer)));
            vf eta = v_blend(up, LAYER_GET(T->eta_d, layer), LAYER_GET(T->eta_u, layer)); /* n_t / n_i */
            vf ca1 = v_abs(uz);
            vm mism = m_andnot(hit, v_eq(eta, one)), reflect = m_from_bits(0); /* matched: R = 0, no bend */
            ca2 = ca1;
            if (m_bits(mism)) {
                vf ie2 = v_blend(up, LAYER_GET(T->ie2_d, layer), LAYER_GET(T->ie2_u, layer));
                vf cc = v_blend(up, LAYER_GET(T->cc_d, layer), LAYER_GET(T->cc_u, layer));
                ca2 = v_blend(mism, ca1, v_sqrt(v_max(v_fnma(v_fnma(ca1, ca1, one), ie2, one), zero))); /* refracted */
                /* rs = a / b, rp = c / d: R = (rs^2 + rp^2) / 2 = (a^2 d^2 + c^2 b^2) / (2 b^2 d^2), one division */
                vf eca2 = v_mul(eta, ca2), eca1 = v_mul(eta, ca1);
                vf ra = v_sub(ca1, eca2), rb = v_add(ca1, eca2), rc = v_sub(ca2, eca1), rd = v_add(ca2, eca1);
                vf ad = v_mul(ra, rd), cb = v_mul(rc, rb), bd = v_mul(rb, rd);
                vf r = v_div(v_fma(ad, ad, v_mul(cb, cb)), v_mul(v_set1(2.0f), v_mul(bd, bd)));
                reflect = m_and(mism, m_or(v_le(ca1, cc), v_lt(xi, r))); /* total internal reflection, Fresnel */
                uz = v_blend(reflect, uz, v_xor(uz, sign));
            }
            vm trans = m_andnot(hit, reflect);
            esc = m_and(trans, m_or(m_and(up, vi_eq(layer, izero)), m_andnot(vi_eq(layer, last), up)));
            if (MULTI) {
                vm inner = m_andnot(trans, esc);
                if (inner_bends) { /* layers of different indices meet: bend (matched: no change) */
                    vf kn = v_blend(up, LAYER_GET(T->ie_d, layer), LAYER_GET(T->ie_u, layer)); /* n_i / n_t */
                    ux = v_blend(inner, ux, v_mul(ux, kn));
                    uy = v_blend(inner, uy, v_mul(uy, kn));
                    uz = v_blend(inner, uz, v_xor(ca2, v_and(uz, sign)));
                }
                layer = vi_blend(inner, layer, vi_add(layer, vi_blend(up, vi_set1(1), vi_set1(-1))));
            }
        }

        steps = vi_add(steps, vi_set1(1));
        vm roul = m_and(inter, v_lt(w, v_set1(MC_WEIGHT_L)));
        vm rare = m_or(m_or(esc, roul), m_and(act, vi_gt(steps, vi_set1(LUCENT_MC_MAX_STEPS - 1))));
        if (MULTI && any_clear) rare = m_or(rare, m_andnot(act, live));
        unsigned rbits = m_bits(rare);
        if (rbits) {
            v_store(S->x, x), v_store(S->y, y), v_store(S->z, z);
            v_store(S->ux, ux), v_store(S->uy, uy), v_store(S->uz, uz);
            v_store(S->w, w), v_store(S->sleft, sleft), v_store(S->ca2, ca2);
            vi_store(S->layer, layer), vi_store(S->steps, steps), vi_store(S->bbase, bbase);
            unsigned ebits = m_bits(esc), qbits = m_bits(roul);
            do {
                int i = __builtin_ctz(rbits);
                rbits &= rbits - 1;
                lane_rare(k, S, i, (int)(ebits >> i) & 1, (int)(qbits >> i) & 1);
            } while (rbits);
            if (!S->active) break;
            x = v_load(S->x), y = v_load(S->y), z = v_load(S->z);
            ux = v_load(S->ux), uy = v_load(S->uy), uz = v_load(S->uz);
            w = v_load(S->w), sleft = v_load(S->sleft);
            layer = vi_load(S->layer), steps = vi_load(S->steps), bbase = vi_load(S->bbase);
            act = m_from_bits(S->active);
        }
        if (k->n_log == LOG_N) log_flush(k, ARZ);
    }
    for (int i = 0; i < W; i++)
        if (k->bacc[i] >= 0) lane_counters_out(k, i);
}

static void tabs_prepare(const mc_plan *p, layer_tabs *t)
{
    memset(t, 0, sizeof *t);
    for (int i = 0; i < p->layer_count; i++) {
        const mc_layer_k *L = &p->layers[i];
        double g = fabs(L->g_exact), gg = g * g;
        t->z0[i] = L->z0, t->z1[i] = L->z1;
        t->inv_mut[i] = L->clear ? 0.0f : L->inv_mut; /* clear layers go to lane_glass */
        t->absorb[i] = L->absorb;
        t->clear[i] = L->clear ? 1.0f : 0.0f;
        double sign = L->g_exact < 0 ? -1.0 : 1.0; /* g < 0: -cos theta(|g|, 1 - xi) */
        t->k0[i] = (float)(-sign * (1.0 - g) * (1.0 - g));
        t->k1[i] = (float)(sign * (1.0 + gg) * (1.0 - g));
        t->k2[i] = (float)(sign * g * (1.0 + gg) / 2.0);
        t->m0[i] = (float)(1.0 - g);
        t->g[i] = (float)g;
        t->pv[i] = L->g_exact < 0 ? -2.0f : 2.0f;
        t->po[i] = L->g_exact < 0 ? 2.0f : 0.0f;
        t->mut[i] = L->mut;
        t->eta_u[i] = L->n_up / L->n, t->eta_d[i] = L->n_down / L->n;
        t->ie_u[i] = L->n / L->n_up, t->ie_d[i] = L->n / L->n_down;
        t->ie2_u[i] = t->ie_u[i] * t->ie_u[i], t->ie2_d[i] = t->ie_d[i] * t->ie_d[i];
        t->cc_u[i] = L->cos_crit_up, t->cc_d[i] = L->cos_crit_down;
    }
}

void MC_FN(mc_trace)(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid,
                     int64_t *scratch)
{
    _Alignas(64) kctx kc; /* 30 KB on the stack */
    _Alignas(64) lanes ls;
    kctx *k = &kc;
    lanes *S = &ls;
    k->plan = plan, k->batch = batch, k->grid = grid, k->zl = scratch, k->arz = plan->score_a_rz;
    for (int i = 0; i < W; i++) k->bacc[i] = -1;
    k->any_clear = k->any_backward = k->inner_bends = 0;
    for (int i = 0; i < plan->layer_count; i++) {
        k->any_clear |= plan->layers[i].clear, k->any_backward |= plan->layers[i].g_exact < 0;
        k->inner_bends |= i > 0 && plan->layers[i].n != plan->layers[i - 1].n;
    }
    k->next = begin, k->end = end, k->n_log = 0;
    k->zlim = plan->z_lim, k->rlim = plan->r_lim;
    k->prefetch = plan->score_a_rz && (plan->lay.grid_size - plan->lay.a_rz) * sizeof(int64_t) > LOG_PREFETCH_BYTES;
    tabs_prepare(plan, &k->t);
    S->active = 0;
    /* the lanes' streams: one 64-bit key from the chunk's stream, hashed with the lane's number
     * through SplitMix64 (lucent_rng_init), as the chunks' own streams are made from (seed, chunk) */
    uint64_t key = lucent_rng_next(rng);
    for (int i = 0; i < W; i++) {
        lucent_rng a, b;
        lucent_rng_init(key, 2 * (uint64_t)i, &a);
        lucent_rng_init(key, 2 * (uint64_t)i + 1, &b);
        S->r0[i] = a.s[0], S->r1[i] = a.s[1], S->r2[i] = a.s[2], S->r3[i] = a.s[3];
        S->e0[i] = b.s[0], S->e1[i] = b.s[1], S->e2[i] = b.s[2], S->e3[i] = b.s[3];
        S->ca2[i] = 0.0f;
        lane_launch(k, S, i);
    }
    int iso = 1;
    for (int i = 0; i < plan->layer_count; i++) iso &= plan->layers[i].hg_kind == 0 && !plan->layers[i].clear;
    /* one turbid layer: its constants broadcast; else per lane (clear layers are read per lane) */
    int multi = plan->layer_count == 1 && !plan->layers[0].clear ? 0 : plan->layer_count <= W ? 1 : 2;
    if (multi) iso = 0;
    int arz = plan->score_a_rz;
    if (S->active) {
        if (multi == 0 && arz && iso)
            lanes_run(k, S, 0, 1, 1);
        else if (multi == 0 && arz)
            lanes_run(k, S, 0, 1, 0);
        else if (multi == 0 && iso)
            lanes_run(k, S, 0, 0, 1);
        else if (multi == 0)
            lanes_run(k, S, 0, 0, 0);
        else if (multi == 1 && arz)
            lanes_run(k, S, 1, 1, 0);
        else if (multi == 1)
            lanes_run(k, S, 1, 0, 0);
        else if (arz)
            lanes_run(k, S, 2, 1, 0);
        else
            lanes_run(k, S, 2, 0, 0);
    }
}

/* Test hooks (mc_internal.h): the approximations above over arrays (n a multiple of W). */
void MC_FN(mc_simd_neglog)(const uint32_t *m, float *dest, size_t n)
{
    for (size_t i = 0; i < n; i += W) v_store(dest + i, v_neglog24(vi_loadu((const int32_t *)m + i)));
}

void MC_FN(mc_simd_sincos)(const uint32_t *ph, float *c, float *s, size_t n)
{
    for (size_t i = 0; i < n; i += W) {
        vf vc, vs;
        v_sincos20(vi_loadu((const int32_t *)ph + i), &vc, &vs);
        v_store(c + i, vc), v_store(s + i, vs);
    }
}

void MC_FN(mc_simd_hg)(double g, const float *xi, float *mu, size_t n)
{
    mc_plan p;
    memset(&p, 0, sizeof p);
    p.layer_count = 1;
    p.layers[0].g = (float)g;
    p.layers[0].g_exact = g;
    _Alignas(64) layer_tabs tabs;
    layer_tabs *t = &tabs;
    tabs_prepare(&p, t);
    for (size_t i = 0; i < n; i += W)
        v_store(mu + i, v_hg(v_loadu(xi + i), v_set1(t->k0[0]), v_set1(t->k1[0]), v_set1(t->k2[0]), v_set1(t->m0[0]),
                             v_set1(t->g[0]), v_set1(t->pv[0]), v_set1(t->po[0])));
}
