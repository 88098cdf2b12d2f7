/* The random-walk family: engines that turn a colour and a radius into a homogeneous medium and trace
 * it. Each engine's albedo inversion and radius are computed from its own definition:
 *   Blender 3.x Cycles, Random Walk (3.4's closure/bssrdf.h bssrdf_setup_radius and
 *     integrator/subsurface_random_walk.h, shipped with Debian's blender): radius' = radius sqrt(3 (1 -
 *     alpha')), alpha' the classical dipole's reduced albedo of the colour with Fdr(Subsurface IOR), found by
 *     12 bisection steps; sigma_t = 1 / (radius' (1 - g)); the single-scattering albedo from the colour by
 *     Chiang, Kutz & Burley 2016 with Wrenninge et al.'s fit in g (subsurface_random_walk_remap), below 0.2
 *     raised to 0.2 with the throughput scaled by alpha / 0.2; the walk enters and leaves through a diffuse,
 *     index-matched interface;
 *   OpenPBR 1.1, Subsurface: mu_t = 1 / (subsurface_radius x subsurface_radius_scale), the single-scattering
 *     albedo from subsurface_color by van de Hulst's relation inverted (the spec's example), HG g =
 *     subsurface_scatter_anisotropy, under the dielectric interface of specular_ior.
 * The model's profile and total are, at unit extinction and rescaled (R(r) = sigma_t^2 R1(sigma_t r)), Cycles'
 * own walk (cycles_walk.c) or, for OpenPBR's dielectric slab, Lucent's Monte Carlo (lucent/mc.h). The fit finds the colour whose medium reflects the truth's T
 * (secant steps on the Monte Carlo total), then the extinction that minimises e_p. */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"
#include "lucent/mc.h"

/* ---- the engines' definitions ---- */

/* Jensen et al. 2001's dipole Rd as Cycles writes it (bssrdf_dipole_compute_Rd), with 4A/3 given. */
static double cycles_dipole_rd(double alpha_prime, double fourthird_a)
{
    double s = sqrt(3.0 * (1.0 - alpha_prime));
    return 0.5 * alpha_prime * (1.0 + exp(-fourthird_a * s)) * exp(-s);
}

double lucent_engine_cycles_rw_radius(double albedo, double radius, double ior)
{
    double eta = fmin(fmax(ior, 1.01), 3.8), inv = 1.0 / eta;
    double fdr = inv * (-1.440 * inv + 0.710) + 0.668 + 0.0636 * eta; /* Jensen's Fdr, as Cycles writes it */
    double fa = 4.0 / 3.0 * (1.0 + fdr) / (1.0 - fdr);
    double ap;
    if (albedo < 1e-4) {
        ap = 0.0;
    } else if (albedo >= 0.995) {
        ap = 0.999999;
    } else { /* bssrdf_dipole_compute_alpha_prime: 12 bisection steps, the last midpoint */
        double x0 = 0.0, x1 = 1.0, mid = 0.5;
        for (int i = 0; i < 12; i++) {
            mid = 0.5 * (x0 + x1);
            if (cycles_dipole_rd(mid, fa) < albedo)
                x0 = mid;
            else
                x1 = mid;
        }
        ap = mid;
    }
    return radius * sqrt(3.0 * (1.0 - ap));
}

double lucent_engine_cycles_rw_alpha(double albedo, double g)
{
    double g2 = g * g, g3 = g2 * g, g4 = g3 * g, g5 = g4 * g, g6 = g5 * g, g7 = g6 * g;
    /* the coefficients of subsurface_random_walk_remap (Blender 3.4) */
    double a = 1.8260523782 - 1.28451056436 * g - 1.79904629312 * g2 + 9.19393289202 * g3 - 22.8215585862 * g4 +
               32.0234874259 * g5 - 23.6264803333 * g6 + 7.21067002658 * g7;
    double b = 4.98511194385 +
               0.127355959438 * exp(31.1491581433 * g - 201.847017512 * g2 + 841.576016723 * g3 - 2018.09288505 * g4 +
                                    2731.71560286 * g5 - 1935.41424244 * g6 + 559.009054474 * g7);
    double c = 1.09686102424 - 0.394704063468 * g + 1.05258115941 * g2 - 8.83963712726 * g3 + 28.8643230661 * g4 -
               46.8802913581 * g5 + 38.5402837518 * g6 - 12.7181042538 * g7;
    double d = 0.496310210422 + 0.360146581622 * g - 2.15139309747 * g2 + 17.8896899217 * g3 - 55.2984010333 * g4 +
               82.065982243 * g5 - 58.5106008578 * g6 + 15.8478295021 * g7;
    double e = 4.23190299701 +
               0.00310603949088 * exp(76.7316253952 * g - 594.356773233 * g2 + 2448.8834203 * g3 - 5576.68528998 * g4 +
                                      7116.60171912 * g5 - 4763.54467887 * g6 + 1303.5318055 * g7);
    double f = 2.40602999408 - 2.51814844609 * g + 9.18494908356 * g2 - 79.2191708682 * g3 + 259.082868209 * g4 -
               403.613804597 * g5 + 302.85712436 * g6 - 87.4370473567 * g7;
    double blend = pow(albedo, 0.25);
    double alpha = (1.0 - blend) * a * pow(atan(b * albedo), c) + blend * d * pow(atan(e * albedo), f);
    return fmin(fmax(alpha, 0.0), 0.999999);
}

/* OpenPBR 1.1, Subsurface: C = (1 - s)(1 - 0.139 s) / (1 + 1.17 s), s = sqrt((1 - a) / (1 - a g)). */
double lucent_engine_openpbr_color(double alpha, double g)
{
    double s = sqrt((1.0 - alpha) / (1.0 - alpha * g));
    return (1.0 - s) * (1.0 - 0.139 * s) / (1.0 + 1.17 * s);
}

double lucent_engine_openpbr_alpha(double color, double g)
{
    double s = 4.09712 + 4.20863 * color - sqrt(9.59217 + 41.6808 * color + 17.7126 * color * color);
    return (1.0 - s * s) / (1.0 - g * s * s);
}

/* ---- one engine's medium ---- */

typedef struct walk {
    lucent_engine_id e;
    double g;   /* the engine's anisotropy */
    double n;   /* the boundary's index in the Monte Carlo */
    double ior; /* Cycles' Subsurface IOR */
} walk;

/* The single-scattering albedo the engine takes for colour C, and the throughput factor (Cycles: below 0.2). */
static double walk_alpha(const walk *w, double color, double *throughput)
{
    *throughput = 1.0;
    if (w->e == LUCENT_ENGINE_OPENPBR) return fmin(fmax(lucent_engine_openpbr_alpha(color, w->g), 0.0), 0.999999);
    double a = lucent_engine_cycles_rw_alpha(color, w->g);
    if (a < 0.2) *throughput = a / 0.2, a = 0.2; /* subsurface_random_walk_coefficients' min_alpha */
    return a;
}

/* sigma_t per unit radius: sigma_t = walk_sigma_per(...) / radius. */
static double walk_sigma_per(const walk *w, double color)
{
    if (w->e == LUCENT_ENGINE_OPENPBR) return 1.0;
    return 1.0 / (lucent_engine_cycles_rw_radius(color, 1.0, w->ior) * (1.0 - w->g));
}

/* The Monte Carlo of the engine's medium at unit extinction. */
typedef struct walk_mc {
    double total; /* T (throughput included) */
    double total_se;
    double dr; /* grid, extinction lengths */
    int count;
    double *cum; /* count + 1 cumulative energies (throughput included) */
} walk_mc;

static lucent_status walk_run(const walk *w, double color, uint64_t photons, uint64_t seed, double extent,
                              lucent_pool *pool, walk_mc *dest)
{
    double tp, a = walk_alpha(w, color, &tp);
    dest->dr = 0.025;
    double want = ceil(extent / dest->dr);
    dest->count = want > 40000 ? 40000 : want < 200 ? 200 : (int)want;
    lucent_mc_result r = {0};
    lucent_status s;
    if (w->e == LUCENT_ENGINE_OPENPBR) { /* the spec's dielectric slab: Lucent's Monte Carlo */
        lucent_mc_layer layer = {.n = w->n, .sigma_a = 1.0 - a, .sigma_s = a, .g = w->g, .thickness = INFINITY};
        s = lucent_mc_run(&(lucent_mc_desc){.layers = &layer,
                                            .layer_count = 1,
                                            .photons = photons,
                                            .seed = seed,
                                            .grid = {.dr = dest->dr, .nr = dest->count},
                                            .pool = pool,
                                            .label = "engine model"},
                          &r);
    } else { /* Cycles' own walk */
        r.rd_r = malloc((size_t)dest->count * sizeof *r.rd_r);
        s = r.rd_r ? eng_cycles_walk(a, w->g, photons, seed, dest->dr, dest->count, pool, r.rd_r, &r.rd, &r.rd_se)
                   : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    if (s != LUCENT_OK) {
        lucent_mc_result_free(&r);
        return s;
    }
    free(dest->cum);
    dest->cum = malloc(((size_t)dest->count + 1) * sizeof *dest->cum);
    if (!dest->cum) {
        lucent_mc_result_free(&r);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    dest->cum[0] = 0.0;
    for (int k = 0; k < dest->count; k++)
        dest->cum[k + 1] = dest->cum[k] + tp * r.rd_r[k] * M_PI * (2 * k + 1) * dest->dr * dest->dr;
    dest->total = tp * r.rd, dest->total_se = tp * r.rd_se;
    lucent_mc_result_free(&r);
    return LUCENT_OK;
}

/* The energy within radius u (extinction lengths), uniform in area inside each bin. */
static double walk_energy(const walk_mc *m, double u)
{
    double x = u / m->dr;
    if (x >= m->count) return m->cum[m->count];
    int k = (int)x;
    double a = k * m->dr, b = a + m->dr;
    return m->cum[k] + (m->cum[k + 1] - m->cum[k]) * (u * u - a * a) / (b * b - a * a);
}

/* The model's bin averages on the target's first n bins at extinction sigma_t (mm^-1). */
static void walk_bins(const lucent_engine_target *t, const walk_mc *m, double sigma_t, int n, double *dest)
{
    double dr = t->profile->dr, prev = 0.0;
    for (int j = 0; j < n; j++) {
        double e = walk_energy(m, (j + 1) * dr * sigma_t);
        dest[j] = (e - prev) / (M_PI * (2 * j + 1) * dr * dr);
        prev = e;
    }
}

typedef struct sigma_fit {
    const lucent_engine_target *t;
    const walk_mc *m;
    int c;
    double *u;
} sigma_fit;

static double sigma_error(double sigma_t, void *ctx)
{
    sigma_fit *f = ctx;
    walk_bins(f->t, f->m, sigma_t, f->t->bins[f->c], f->u);
    double ep = eng_profile_error(f->t, f->c, f->u);
    return ep * ep;
}

/* The colour whose medium reflects T: secant steps on the Monte Carlo total, kept inside a bracket. Every
 * run takes the same seed (common random numbers), so the total is a smooth function of the colour and
 * the root is found to within one run's noise. */
static lucent_status find_color(const walk *w, double target, uint64_t photons, uint64_t seed, lucent_pool *pool,
                                double *color)
{
    double lo = 1e-3, hi = 0.999, tp;
    for (double a = 1e-3, b = 0.999; b - a > 1e-6;) { /* no colour whose medium absorbs less than 1e-4 */
        double mid = 0.5 * (a + b);
        (walk_alpha(w, mid, &tp) > 0.9999 ? (b = mid) : (a = mid));
        hi = a;
    }
    double c0 = fmin(fmax(target, lo), hi), f0, c1, f1 = 0;
    walk_mc m = {0};
    lucent_status s = walk_run(w, c0, photons, seed, 10.0, pool, &m);
    f0 = m.total - target;
    (f0 < 0 ? (lo = c0) : (hi = c0));
    c1 = fmin(fmax(c0 - f0, lo + 1e-6), hi - 1e-6);
    for (int i = 1; i < 12 && s == LUCENT_OK; i++) {
        s = walk_run(w, c1, photons, seed, 10.0, pool, &m);
        if (s != LUCENT_OK) break;
        f1 = m.total - target;
        (f1 < 0 ? (lo = c1) : (hi = c1));
        if (fabs(f1) <= 2e-4 * target || hi - lo < 1e-6) break;
        double next = f1 != f0 ? c1 - f1 * (c1 - c0) / (f1 - f0) : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        c0 = c1, f0 = f1, c1 = next;
    }
    free(m.cum);
    *color = c1;
    return s;
}

/* The (top) material's mean reduced extinction over 1 - g: where the search for sigma_t centres. */
static double sigma_guess(const lucent_engine_target *t, const walk *w, int c)
{
    const lucent_material *m = &t->material;
    return (m->sigma_a[c] + m->sigma_s[c] * (1.0 - m->g[c])) / (1.0 - w->g);
}

static void walk_params(const lucent_engine_target *t, const walk *w, const double color[3], const double sigma_t[3],
                        lucent_engine_fit_result *r)
{
    double radius[3];
    for (int c = 0; c < 3; c++) radius[c] = walk_sigma_per(w, color[c]) / sigma_t[c];
    if (w->e == LUCENT_ENGINE_OPENPBR) {
        double rmax = fmax(radius[0], fmax(radius[1], radius[2])), scale[3];
        for (int c = 0; c < 3; c++) scale[c] = radius[c] / rmax;
        eng_param1(r, "subsurface_weight", "", 1.0);
        eng_param(r, "subsurface_color", "", 3, color);
        eng_param1(r, "subsurface_radius", "scene units (mm)", rmax);
        eng_param(r, "subsurface_radius_scale", "", 3, scale);
        eng_param1(r, "subsurface_scatter_anisotropy", "", w->g);
        eng_param1(r, "specular_ior", "", w->n);
        eng_note(r, "mu_t = 1 / (radius x scale); the renderer's albedo inversion taken as van de Hulst's (the spec's "
                    "example): the colour makes that medium, under the dielectric interface, reflect T");
        eng_cannot_common(t, r, true, true);
    } else {
        eng_param_text(r, "Subsurface Method", "Random Walk");
        eng_param(r, "Base Color", "", 3, color);
        eng_param1(r, "Subsurface", "", 1.0);
        eng_param(r, "Subsurface Color", "", 3, color);
        eng_param(r, "Subsurface Radius", "scene units (mm)", 3, radius);
        eng_param1(r, "Subsurface IOR", "", w->ior);
        eng_param1(r, "Subsurface Anisotropy", "", w->g);
        eng_note(r, "one Blender unit is 1 mm; the model is Cycles 3.4's own walk of the medium it builds "
                    "(src/engine/cycles_walk.c)");
        eng_cannot(r, "the refractive boundary: the walk enters and leaves through a diffuse interface (the IOR only "
                      "scales the radius)");
        eng_cannot_common(t, r, true, true);
    }
    bool differs;
    double g = eng_mean_g(t, &differs);
    if (g != w->g)
        eng_cannot(r, "g = %.3g (the engine's anisotropy is limited to %s)", g,
                   w->e == LUCENT_ENGINE_OPENPBR ? "[-1, 1]" : "[0, 0.9]");
}

lucent_status eng_fit_walk(const lucent_engine_target *t, lucent_engine_id e, bool hand,
                           const lucent_engine_fit_desc *desc, lucent_engine_fit_result *r)
{
    double g = eng_mean_g(t, NULL);
    walk w = {.e = e,
              .g = e == LUCENT_ENGINE_OPENPBR ? fmin(fmax(g, -0.99), 0.99) : fmin(fmax(g, 0.0), 0.9),
              .n = e == LUCENT_ENGINE_OPENPBR ? t->material.eta : 1.0,
              .ior = fmin(fmax(t->material.eta, 1.01), 3.8)};
    uint64_t photons = desc && desc->model_photons ? desc->model_photons : LUCENT_ENGINE_MODEL_PHOTONS;
    lucent_pool *pool = desc ? desc->pool : NULL;
    double hand_radius[3];
    if (hand && !eng_hand_radius(t, hand_radius))
        return lucent_error(LUCENT_ERR_UNSUPPORTED,
                            "%s: hand mapping: %s does not absorb in some channel (1 / sigma_tr is infinite)",
                            lucent_engine_name(e), t->material.name);
    int n = t->profile->count;
    double color[3], sigma_t[3], total[3];
    double *m[3] = {malloc((size_t)n * sizeof(double)), malloc((size_t)n * sizeof(double)),
                    malloc((size_t)n * sizeof(double))};
    lucent_status s = m[0] && m[1] && m[2] ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        if (hand)
            color[c] = fmin(t->rd[c], 0.999);
        else
            s = find_color(&w, t->rd[c], photons, 2000 + (uint64_t)c, pool, &color[c]);
        double guess = hand ? walk_sigma_per(&w, color[c]) / hand_radius[c] : sigma_guess(t, &w, c);
        double tp, a = walk_alpha(&w, color[c], &tp);
        double str = sqrt(3.0 * (1.0 - a) * (1.0 - a * w.g)); /* diffusion's sigma_tr per extinction */
        double extent =
            fmax(12.0 / fmax(str, 1e-3), 1.2 * t->profile->count * t->profile->dr * guess * (hand ? 1 : 10));
        walk_mc mc = {0};
        if (s == LUCENT_OK) s = walk_run(&w, color[c], photons, 2000 + (uint64_t)c, extent, pool, &mc);
        if (s == LUCENT_OK) {
            sigma_fit f = {.t = t, .m = &mc, .c = c, .u = m[c]};
            sigma_t[c] = hand ? guess : eng_minimize_log(sigma_error, &f, guess / 10.0, guess * 10.0, 30, NULL);
            walk_bins(t, &mc, sigma_t[c], n, m[c]);
            total[c] = mc.total;
        }
        free(mc.cum);
    }
    if (s == LUCENT_OK) s = eng_finish(t, m, total, r);
    if (s == LUCENT_OK) walk_params(t, &w, color, sigma_t, r);
    for (int c = 0; c < 3; c++) free(m[c]);
    return s;
}
