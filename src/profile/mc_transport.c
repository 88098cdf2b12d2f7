/* The photon kernel: MCML's hop, drop, spin, roulette (Wang, Jacques & Zheng 1995, section 3;
 * equations numbered as in the MCML manual, Wang & Jacques 1992/1995 "MCML" chapter 3).
 *
 * Differences from MCML that do not change the physics, only the cost:
 *   - float state; the direction is renormalised by one Newton step after each scattering;
 *   - the azimuth's cosine and sine come from the polar (rejection) method, without cos/sin;
 *   - the step length and the HG cosine share one 64-bit draw (two independent 24-bit fields);
 *   - sqrt(1 - cos^2 theta) sqrt(1 - uz^2) is one sqrt, and one division serves the update;
 *   - scores go to fixed-point counters (order-independent sums: identical for any thread count). */
#include <math.h>

#include "profile/mc_internal.h"

#define MC_WEIGHT 1e-4f  /* roulette threshold (MCML's WEIGHT) */
#define MC_CHANCE 0.1f   /* roulette survival chance (MCML's CHANCE) */
#define MC_COS_ZERO 1e-6f
#define MC_COS_90 1e-6f

static inline float u24(uint64_t bits) /* the low 24 bits as a float in [0, 1) */
{
    return (float)(bits & 0xFFFFFFu) * 5.9604644775390625e-8f;
}

/* Fresnel reflectance for unpolarised light from index n1 into n2 at incidence cosine ca1
 * (MCML manual eq. 3.36); *ca2 receives the cosine of the transmitted angle (Snell, eq. 3.35). */
static float fresnel(float n1, float n2, float ca1, float *ca2)
{
    if (n1 == n2) {
        *ca2 = ca1;
        return 0.0f;
    }
    if (ca1 > 1.0f - MC_COS_ZERO) {
        *ca2 = ca1;
        float r = (n2 - n1) / (n2 + n1);
        return r * r;
    }
    if (ca1 < MC_COS_90) {
        *ca2 = 0.0f;
        return 1.0f;
    }
    float sa1 = sqrtf(1.0f - ca1 * ca1);
    float sa2 = n1 * sa1 / n2;
    if (sa2 >= 1.0f) {
        *ca2 = 0.0f;
        return 1.0f;
    }
    float c2 = sqrtf(1.0f - sa2 * sa2);
    *ca2 = c2;
    float cap = ca1 * c2 - sa1 * sa2; /* cos(a1 + a2) */
    float cam = ca1 * c2 + sa1 * sa2; /* cos(a1 - a2) */
    float sap = sa1 * c2 + ca1 * sa2; /* sin(a1 + a2) */
    float sam = sa1 * c2 - ca1 * sa2; /* sin(a1 - a2) */
    return 0.5f * sam * sam * (cam * cam + cap * cap) / (sap * sap * cam * cam);
}

/* HG cosine of the deflection angle (MCML manual eq. 3.28). */
static inline float hg_cos(const mc_layer_k *L, float xi)
{
    switch (L->hg_kind) {
    case 0: return 2.0f * xi - 1.0f;
    case 1: {
        float t = L->hg_b / (L->hg_c + L->hg_d * xi);
        float c = (L->hg_a - t * t) * L->hg_e;
        return c < -1.0f ? -1.0f : c > 1.0f ? 1.0f : c;
    }
    case 2: {
        double g = L->g, t = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
        double c = (1.0 + g * g - t * t) / (2.0 * g);
        return (float)(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c);
    }
    default: return L->g;
    }
}

typedef struct photon {
    float x, y, z, ux, uy, uz, w;
    int layer;
} photon;

/* New direction after scattering by cos theta = c (MCML manual eqs. 3.30 and 3.31), the
 * azimuth drawn by the polar method: (a, b) uniform in the unit disc gives
 * cos phi = (a^2 - b^2) / r2, sin phi = 2ab / r2 with phi uniform in [0, 2 pi). */
static inline void spin(photon *p, float c, lucent_rng *rng)
{
    float a, b, r2;
    do {
        uint64_t bits = lucent_rng_next(rng);
        a = (float)(int32_t)(uint32_t)bits * 4.656612873077393e-10f; /* 2^-31 */
        b = (float)(int32_t)(uint32_t)(bits >> 32) * 4.656612873077393e-10f;
        r2 = a * a + b * b;
    } while (r2 > 1.0f || r2 < 1e-12f);
    float cp = a * a - b * b, sp = 2.0f * a * b; /* r2 cos phi, r2 sin phi */
    float s2 = 1.0f - c * c;
    if (s2 < 0.0f) s2 = 0.0f;
    float ux = p->ux, uy = p->uy, uz = p->uz;
    float nx, ny, nz;
    if (fabsf(uz) > 0.99999f) {
        float s = sqrtf(s2) / r2;
        nx = s * cp;
        ny = s * sp;
        nz = uz >= 0.0f ? c : -c;
    } else {
        float q = 1.0f - uz * uz;
        float sq = sqrtf(s2 * q);   /* sin theta sqrt(1 - uz^2) */
        float inv = 1.0f / (r2 * q);
        float k = sq * inv;          /* sin theta / (sqrt(1 - uz^2) r2) */
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

static inline int64_t fixed(const mc_plan *plan, float w)
{
    return (int64_t)((double)w * plan->scale + 0.5);
}

static inline int radial_bin(const mc_plan *plan, float x, float y)
{
    float r = sqrtf(x * x + y * y) * plan->inv_dr;
    return r >= (float)plan->r_lim ? plan->r_lim : (int)r;
}

/* Scores a photon leaving through the top (up) or the bottom with exit cosine ca (outside). */
static void score_exit(const mc_plan *plan, const photon *p, float ca, int up, int64_t *batch,
                       int64_t *grid)
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
static int cross(const mc_plan *plan, photon *p, int up, lucent_rng *rng, int64_t *batch,
                 int64_t *grid)
{
    const mc_layer_k *L = &plan->layers[p->layer];
    float ca1 = fabsf(p->uz), ca2 = ca1, r;
    float nt = up ? L->n_up : L->n_down;
    if (ca1 <= (up ? L->cos_crit_up : L->cos_crit_down))
        r = 1.0f; /* total internal reflection */
    else
        r = fresnel(L->n, nt, ca1, &ca2);
    int reflect = r >= 1.0f || (r > 0.0f && lucent_rng_uniformf(rng) < r);
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

static void drop(const mc_plan *plan, photon *p, const mc_layer_k *L, int64_t *batch,
                 int64_t *grid)
{
    const mc_layout *l = &plan->lay;
    float w0 = p->w;
    p->w = w0 - w0 * L->absorb; /* MCML manual eq. 3.23 */
    int64_t q = fixed(plan, w0 - p->w); /* exact when absorb <= 1/2 (Sterbenz): no weight lost */
    float zb = p->z * plan->inv_dz;
    int iz = zb >= (float)plan->z_lim ? plan->z_lim : (int)zb;
    batch[l->a_z + (size_t)iz] += q;
    batch[l->a_l + (size_t)p->layer] += q;
    if (plan->score_a_rz) {
        int ir = radial_bin(plan, p->x, p->y);
        grid[l->a_rz + (size_t)ir * (size_t)(plan->nz + 1) + (size_t)iz] += q;
    }
}

/* One photon packet from launch to escape or death. */
static void trace_one(const mc_plan *plan, lucent_rng *rng, int64_t *batch, int64_t *grid)
{
    photon p = {0.0f, 0.0f, plan->launch_z, 0.0f, 0.0f, 1.0f, plan->w_launch, plan->launch_layer};
    float sleft = 0.0f; /* step left over after a boundary, in mean free paths */
    for (;;) {
        const mc_layer_k *L = &plan->layers[p.layer];
        if (L->clear) { /* MCML's HopInGlass */
            if (p.uz == 0.0f) return;
            int up = p.uz < 0.0f;
            float zb = up ? L->z0 : L->z1;
            float d = (zb - p.z) / p.uz;
            p.x += d * p.ux;
            p.y += d * p.uy;
            p.z = zb;
            if (cross(plan, &p, up, rng, batch, grid)) return;
            continue;
        }
        uint64_t bits = 0;
        int have_bits = 0;
        float s;
        if (sleft > 0.0f) {
            s = sleft * L->inv_mut;
        } else { /* MCML manual eq. 3.19: s = -ln(xi) / mu_t, xi in (0, 1] */
            bits = lucent_rng_next(rng);
            have_bits = 1;
            s = -logf((float)((bits >> 40) + 1) * 5.9604644775390625e-8f) * L->inv_mut;
        }
        float zn = p.z + s * p.uz; /* tested without a division; db only on a hit */
        if (zn > L->z1 || zn < L->z0) { /* hits a boundary (MCML manual section 3.6) */
            int up = p.uz < 0.0f;
            float db = ((up ? L->z0 : L->z1) - p.z) / p.uz;
            if (db < 0.0f) db = 0.0f;
            if (db > s) db = s;
            p.x += db * p.ux;
            p.y += db * p.uy;
            p.z = up ? L->z0 : L->z1;
            sleft = (s - db) * L->mut;
            if (cross(plan, &p, up, rng, batch, grid)) return;
            continue;
        }
        p.x += s * p.ux;
        p.y += s * p.uy;
        p.z = zn;
        sleft = 0.0f;
        drop(plan, &p, L, batch, grid);
        float xi = have_bits ? u24(bits) : lucent_rng_uniformf(rng);
        spin(&p, hg_cos(L, xi), rng);
        if (p.w < MC_WEIGHT) { /* Russian roulette (MCML manual section 3.8) */
            if (lucent_rng_uniformf(rng) < MC_CHANCE)
                p.w /= MC_CHANCE;
            else
                return;
        }
    }
}

void mc_trace(const mc_plan *plan, lucent_rng *rng, uint64_t begin, uint64_t end,
              int64_t *batch, int64_t *grid)
{
    uint64_t n = plan->photons, b = (uint64_t)plan->batches;
    for (uint64_t i = begin; i < end; i++) {
        uint64_t k = i * b / n; /* the batch of photon i: contiguous photon ranges */
        trace_one(plan, rng, batch + k * plan->lay.batch_size, grid);
    }
}
