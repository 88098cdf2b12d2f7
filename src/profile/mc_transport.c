/* The photon kernel: MCML's hop, drop, spin, roulette (Wang, Jacques & Zheng 1995, section 3;
 * equations numbered as in the MCML manual, Wang & Jacques 1992/1995 "MCML" chapter 3).
 *
 * Differences from MCML that do not change the physics, only the cost:
 *   - float state; the direction is renormalised by one Newton step after each HG scattering;
 *   - random draws are prepared 64 at a time (rbuf_fill, a vectorisable loop): one 64-bit draw
 *     per interaction gives the step length (24 bits, -ln by a polynomial), the deflection
 *     (20 bits) and the azimuth (20 bits, cos and sin by polynomials, no rejection);
 *   - isotropic layers (g = 0) draw the new direction directly, uniform on the sphere;
 *   - scores go to fixed-point counters (order-independent sums: identical for any thread
 *     count); A(r, z) scores pass through a short log applied in bulk (cache misses overlap). */
#include <math.h>
#include <string.h>

#include "profile/mc_internal.h"

#define MC_WEIGHT 1e-4f /* roulette threshold (MCML's WEIGHT) */
#define MC_CHANCE 0.1f  /* roulette survival chance (MCML's CHANCE) */

/* -ln(m 2^-24) for m in [1, 2^24]: the step length in mean free paths (MCML manual eq. 3.19)
 * without a libm call. m = 2^e f with f in [sqrt(1/2), sqrt(2)) (from the float's bits), and
 * ln f = t P(t), t = f - 1, P a degree-7 polynomial fitted at Chebyshev nodes of
 * [sqrt(1/2) - 1, sqrt(2) - 1]: relative error at most 3.1e-7 over every m (tests/test_mc_simd.c measures the
 * same polynomial in the lanes; float rounding is 6e-8), exact 0 at
 * m = 2^24. */
static inline float neg_log_u24(uint32_t m)
{
    float x = (float)m;
    uint32_t ix;
    memcpy(&ix, &x, sizeof ix);
    ix -= 0x3F3504F3u;       /* the bits of sqrt(1/2) */
    int e = (int)(ix >> 23); /* m >= 1: ix stays positive; e = floor(log2(m / sqrt(1/2))) */
    uint32_t fb = (ix & 0x7FFFFFu) + 0x3F3504F3u;
    float f;
    memcpy(&f, &fb, sizeof f);
    float t = f - 1.0f; /* exact (Sterbenz) */
    float p = -0.0989535074f;
    p = p * t + 0.161262479f;
    p = p * t - 0.172782061f;
    p = p * t + 0.199133479f;
    p = p * t - 0.24968907f;
    p = p * t + 0.33334606f;
    p = p * t - 0.500003751f;
    p = p * t + 0.999999968f;
    return (float)(24 - e) * 0.693147180559945f - t * p;
}

/* HG cosine of the deflection angle (MCML manual eq. 3.28; base/optics.h): float with the
 * layer's prepared constants, double where |g| is small (the float formula cancels there). */
static inline float hg_cos(const mc_layer_k *L, float xi)
{
    switch (L->hg_kind) {
    case 0: return 2.0f * xi - 1.0f;
    case 1: return lucent_hg_sample_cos_f(&L->hg, xi);
    case 2: return (float)lucent_hg_sample_cos(L->g, xi);
    default: return L->g;
    }
}

typedef struct photon {
    float x, y, z, ux, uy, uz, w;
    int layer;
} photon;

/* Random numbers are drawn MC_RB at a time from the chunk's stream and turned at once, in a
 * loop the compiler can vectorise, into everything a step may need: each 64-bit draw gives a
 * step length -ln(xi) (its top 24 bits), a deflection variable v (the next 20 bits: HG's xi,
 * or cos theta = 1 - 2v for isotropic scattering) and an azimuth (the low 20 bits: cos phi and
 * sin phi by polynomials, no rejection). Fresnel and roulette decisions take the top 24 bits of
 * a draw as a uniform. The kernel consumes draws in order, so a chunk's photons remain a
 * function of its stream alone. */
#define MC_RB 64

typedef struct rbuf {
    int next;
    float u[MC_RB];             /* uniform in [0, 1), 24 bits */
    float step[MC_RB];          /* -ln(1 - u) in (0, 16.7], mean free paths */
    float v[MC_RB];             /* uniform in (0, 1), 20 bits */
    float ct[MC_RB], st[MC_RB]; /* 1 - 2v and sqrt(1 - ct^2) = 2 sqrt(v (1 - v)) */
    float cp[MC_RB], sp[MC_RB]; /* cos phi, sin phi, phi uniform in [0, 2 pi) */
} rbuf;

static void rbuf_fill(rbuf *b, lucent_rng *rng)
{
    uint64_t raw[MC_RB];
    for (int i = 0; i < MC_RB; i++) raw[i] = lucent_rng_next(rng);
    for (int i = 0; i < MC_RB; i++) {
        int32_t hi = (int32_t)(raw[i] >> 40);
        b->u[i] = (float)hi * 5.9604644775390625e-8f; /* 2^-24 */
        b->step[i] = neg_log_u24((uint32_t)(hi + 1));
        float v = ((float)(int32_t)((raw[i] >> 20) & 0xFFFFFu) + 0.5f) * 9.5367431640625e-7f;
        b->v[i] = v; /* 2^-20, midpoints: never 0 or 1 */
        b->ct[i] = 1.0f - 2.0f * v;
        /* phi = quadrant pi/2 + t, t uniform in [-pi/4, pi/4): covers [-pi/4, 7 pi/4) evenly.
         * Taylor series of cos and sin at 0 to degree 8 and 9: errors below 3e-8 and 2e-9. */
        int32_t ph = (int32_t)(raw[i] & 0xFFFFFu);
        int32_t quad = ph >> 18;
        float t = ((float)(ph & 0x3FFFF) + 0.5f) * 5.9921124e-6f - 0.78539816f; /* pi/2^19 */
        float t2 = t * t;
        float c = 1.0f + t2 * (-0.5f + t2 * (1.0f / 24 + t2 * (-1.0f / 720 + t2 * (1.0f / 40320))));
        float sn = t * (1.0f + t2 * (-1.0f / 6 + t2 * (1.0f / 120 + t2 * (-1.0f / 5040 + t2 * (1.0f / 362880)))));
        /* rotate (c, sn) by quadrant * 90 degrees */
        float c1 = (quad & 1) ? -sn : c, s1 = (quad & 1) ? c : sn;
        float sign = (quad & 2) ? -1.0f : 1.0f;
        b->cp[i] = sign * c1;
        b->sp[i] = sign * s1;
    }
    for (int i = 0; i < MC_RB; i++) b->st[i] = 2.0f * sqrtf(b->v[i] * (1.0f - b->v[i]));
    b->next = 0;
}

/* The index of the next draw in b. */
static inline int rbuf_take(rbuf *b, lucent_rng *rng)
{
    if (b->next == MC_RB) rbuf_fill(b, rng);
    return b->next++;
}

/* New direction after scattering by cos theta = c, sin theta = st, azimuth (cp, sp) (MCML
 * manual eqs. 3.30 and 3.31). */
static inline void spin(photon *p, float c, float st, float cp, float sp)
{
    float ux = p->ux, uy = p->uy, uz = p->uz;
    float nx, ny, nz;
    if (fabsf(uz) > 0.99999f) {
        nx = st * cp;
        ny = st * sp;
        nz = uz >= 0.0f ? c : -c;
    } else {
        float q = 1.0f - uz * uz;
        float k = st / sqrtf(q); /* sin theta / sqrt(1 - uz^2) */
        nx = k * (ux * uz * cp - uy * sp) + ux * c;
        ny = k * (uy * uz * cp + ux * sp) + uy * c;
        nz = -k * q * cp + uz * c;
    }
    float n2 = nx * nx + ny * ny + nz * nz;
    float f = 1.5f - 0.5f * n2; /* one Newton step towards |u| = 1 */
    p->ux = nx * f;
    p->uy = ny * f;
    p->uz = nz * f;
}

static inline int64_t fixed(const mc_plan *plan, float w) { return (int64_t)((double)w * plan->scale + 0.5); }

static inline int radial_bin(const mc_plan *plan, float x, float y)
{
    float r = sqrtf(x * x + y * y) * plan->inv_dr;
    return r >= (float)plan->r_lim ? plan->r_lim : (int)r;
}

/* Scores a photon leaving through the top (up) or the bottom with exit cosine ca (outside). */
static void score_exit(const mc_plan *plan, const photon *p, float ca, int up, int64_t *batch, int64_t *grid)
{
    const mc_layout *l = &plan->lay;
    int64_t w = fixed(plan, p->w);
    int ir = radial_bin(plan, p->x, p->y);
    double ang = acos(ca < 0.0f ? 0.0 : ca > 1.0f ? 1.0 : (double)ca);
    int ia = (int)(ang * plan->inv_da);
    if (ia > plan->na - 1) ia = plan->na - 1;
    batch[(up ? l->rd_r : l->tt_r) + (size_t)ir] += w;
    batch[(up ? l->rd_a : l->tt_a) + (size_t)ia] += w;
    grid[(up ? l->rd_ra : l->tt_ra) + (size_t)ir * (size_t)plan->na + (size_t)ia] += w;
}

/* The photon sits on the top (up) or bottom boundary of its layer: reflect, refract into the
 * neighbour, or escape (MCML's CrossUpOrNot / CrossDnOrNot). Returns 1 when it escaped. */
static int cross(const mc_plan *plan, photon *p, int up, rbuf *rb, lucent_rng *rng, int64_t *batch, int64_t *grid)
{
    const mc_layer_k *L = &plan->layers[p->layer];
    float ca1 = fabsf(p->uz), ca2 = ca1, r;
    float nt = up ? L->n_up : L->n_down;
    if (ca1 <= (up ? L->cos_crit_up : L->cos_crit_down)) {
        r = 1.0f; /* total internal reflection */
    } else {      /* MCML manual eqs. 3.35, 3.36 (base/optics.h, in double: crossings are rare) */
        double ct;
        r = (float)lucent_fresnel_dielectric(ca1, (double)nt / L->n, &ct);
        ca2 = (float)ct;
    }
    int reflect = r >= 1.0f || (r > 0.0f && rb->u[rbuf_take(rb, rng)] < r);
    if (reflect) {
        p->uz = -p->uz;
        return 0;
    }
    int last = plan->layer_count - 1;
    if ((up && p->layer == 0) || (!up && p->layer == last)) {
        score_exit(plan, p, ca2, up, batch, grid);
        return 1;
    }
    float k = L->n / nt;
    p->ux *= k;
    p->uy *= k;
    p->uz = up ? -ca2 : ca2;
    p->layer += up ? -1 : 1;
    return 0;
}

/* A(r, z) scores are not added to the grid as they happen: the grid (nr x nz counters, 3 MB
 * for MCML's 640 x 640) does not fit in the caches, and a read-modify-write that misses stalls
 * the photon's dependent chain of operations. They are appended to a short log instead (cell,
 * weight) and applied in bulk, a tight loop of independent updates whose misses overlap.
 * Integer sums: the order does not change the result. */
#define MC_RZ_LOG 2048

typedef struct rz_log {
    int32_t cell[MC_RZ_LOG];
    int64_t q[MC_RZ_LOG];
} rz_log;

static void rz_flush(int64_t *grid, const rz_log *log, int n)
{
    for (int i = 0; i < n; i++) grid[log->cell[i]] += log->q[i];
}

/* The scoring targets, resolved from the plan into a local (the kernel's stores to int64
 * counters cannot then force reloads of the plan's size_t offsets). */
typedef struct drop_ctx {
    int64_t *a_z, *a_l, *a_rz;
    rz_log *log;
    int n_log;
    int rz_stride;
    float inv_dz, inv_dr, z_lim_f, r_lim_f;
    int z_lim, r_lim;
    double scale;
} drop_ctx;

static inline void drop(drop_ctx *c, photon *p, const mc_layer_k *L)
{
    float w0 = p->w;
    p->w = w0 - w0 * L->absorb; /* MCML manual eq. 3.23 */
    /* exact when absorb <= 1/2 (Sterbenz): no weight lost */
    int64_t q = (int64_t)((double)(w0 - p->w) * c->scale + 0.5);
    float zb = p->z * c->inv_dz;
    int iz = zb >= c->z_lim_f ? c->z_lim : (int)zb;
    c->a_z[iz] += q;
    c->a_l[p->layer] += q;
    if (c->a_rz) {
        float r = sqrtf(p->x * p->x + p->y * p->y) * c->inv_dr;
        int ir = r >= c->r_lim_f ? c->r_lim : (int)r;
        if (c->n_log == MC_RZ_LOG) {
            rz_flush(c->a_rz, c->log, c->n_log);
            c->n_log = 0;
        }
        c->log->cell[c->n_log] = ir * c->rz_stride + iz;
        c->log->q[c->n_log] = q;
        c->n_log++;
    }
}

/* One photon packet from launch to escape or death. */
static void trace_one(const mc_plan *plan, rbuf *rb, lucent_rng *rng, int64_t *batch, int64_t *grid, drop_ctx *dc_out)
{
    drop_ctx dc = *dc_out;
    dc.a_z = batch + plan->lay.a_z;
    dc.a_l = batch + plan->lay.a_l;
    photon p = {0.0f, 0.0f, plan->launch_z, 0.0f, 0.0f, 1.0f, plan->w_launch, plan->launch_layer};
    float sleft = 0.0f; /* step left over after a boundary, in mean free paths */
    for (int steps = 0;; steps++) {
        if (steps == LUCENT_MC_MAX_STEPS) { /* dropped unscored, counted (lucent_mc_result.capped) */
            batch[plan->lay.capped]++;
            break;
        }
        const mc_layer_k *L = &plan->layers[p.layer];
        if (L->clear) { /* MCML's HopInGlass */
            if (p.uz == 0.0f) break;
            int up = p.uz < 0.0f;
            float zb = up ? L->z0 : L->z1;
            float d = (zb - p.z) / p.uz;
            p.x += d * p.ux;
            p.y += d * p.uy;
            p.z = zb;
            if (cross(plan, &p, up, rb, rng, batch, grid)) break;
            continue;
        }
        int k = rbuf_take(rb, rng); /* this step's draw (the deflection uses it too) */
        /* MCML manual eq. 3.19: s = -ln(xi) / mu_t; after a boundary, the rest of the step */
        float s = (sleft > 0.0f ? sleft : rb->step[k]) * L->inv_mut;
        float zn = p.z + s * p.uz;      /* tested without a division; db only on a hit */
        if (zn > L->z1 || zn < L->z0) { /* hits a boundary (MCML manual section 3.6) */
            int up = p.uz < 0.0f;
            float db = ((up ? L->z0 : L->z1) - p.z) / p.uz;
            if (db < 0.0f) db = 0.0f;
            if (db > s) db = s;
            p.x += db * p.ux;
            p.y += db * p.uy;
            p.z = up ? L->z0 : L->z1;
            sleft = (s - db) * L->mut;
            if (cross(plan, &p, up, rb, rng, batch, grid)) break;
            continue;
        }
        p.x += s * p.ux;
        p.y += s * p.uy;
        p.z = zn;
        sleft = 0.0f;
        drop(&dc, &p, L);
        if (L->hg_kind == 0) {
            /* isotropic: the new direction does not depend on the old one (the same
             * distribution as MCML's rotation by an isotropic theta and a uniform phi) */
            float st = rb->st[k];
            p.ux = st * rb->cp[k];
            p.uy = st * rb->sp[k];
            p.uz = rb->ct[k];
        } else {
            float c = hg_cos(L, rb->v[k]);
            float s2 = 1.0f - c * c;
            spin(&p, c, sqrtf(s2 > 0.0f ? s2 : 0.0f), rb->cp[k], rb->sp[k]);
        }
        if (p.w < MC_WEIGHT) { /* Russian roulette (MCML manual section 3.8) */
            if (rb->u[rbuf_take(rb, rng)] < MC_CHANCE)
                p.w /= MC_CHANCE;
            else
                break;
        }
    }
    dc_out->n_log = dc.n_log;
}

void mc_trace(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end, int64_t *batch, int64_t *grid)
{
    uint64_t n = plan->photons, b = (uint64_t)plan->batches;
    rz_log log; /* 24 KB on the stack */
    rbuf rb;
    rb.next = MC_RB;
    int64_t *a_rz = plan->score_a_rz ? grid + plan->lay.a_rz : NULL;
    drop_ctx dc = {NULL,
                   NULL,
                   a_rz,
                   &log,
                   0,
                   plan->nz + 1,
                   plan->inv_dz,
                   plan->inv_dr,
                   (float)plan->z_lim,
                   (float)plan->r_lim,
                   plan->z_lim,
                   plan->r_lim,
                   plan->scale};
    for (uint64_t i = begin; i < end; i++) {
        uint64_t k = i * b / n; /* the batch of photon i: contiguous photon ranges */
        trace_one(plan, &rb, rng, batch + k * plan->lay.batch_size, grid, &dc);
    }
    if (a_rz) rz_flush(a_rz, &log, dc.n_log);
}
