/* The transmittance of a thin part for translucency (lucent/profile.h; docs/render.md,
 * "Translucency"). Slab: the total transmittance T(s) of a slab of the material, thickness s, lit at
 * normal incidence on one face, from Lucent's Monte Carlo; for uniform lighting the spatial integral
 * of the pencil-beam transmittance, so light E reaching the back face leaves the front with exitance
 * E T(s), radiance E T(s) / pi. Profile (Jimenez 2010): the profile's power beyond the thickness. */
#include <math.h>
#include <string.h>

#include "lucent/mc.h"
#include "lucent/profile.h"

#define THINNEST 1e-3 /* mm: the first sample (a thickness <= 0 means a half-space to lucent_mc) */

/* The sample thicknesses: s_k = s_max (k / (SAMPLES - 1))^2, the first one THINNEST. */
static double sample_thickness(double s_max, int k)
{
    double t = (double)k / (LUCENT_SLAB_SAMPLES - 1);
    return fmax(s_max * t * t, THINNEST);
}

/* s_max = 5 / sigma_tr of the slowest channel (T is e^-5 of its thin-slab value there), but at most
 * 100 transport mean free paths of the sparsest channel: without absorption sigma_tr is 0 and T falls
 * only as 1 / s, and the walks through a slab grow as its optical thickness squared. */
void lucent_slab_transmittance_grid(const lucent_material *m, lucent_slab_transmittance *dest)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    double tr = INFINITY, tp = INFINITY;
    for (int c = 0; c < 3; c++)
        dest->sigma_tr[c] = d.sigma_tr[c], tr = fmin(tr, d.sigma_tr[c]), tp = fmin(tp, d.sigma_t_prime[c]);
    dest->s_max = fmin(5 / fmax(tr, 1e-3), 100 / fmax(tp, 1e-3));
    for (int k = 0; k < LUCENT_SLAB_SAMPLES; k++) dest->thickness[k] = sample_thickness(dest->s_max, k);
}

lucent_status lucent_slab_transmittance_run(const lucent_material *m, uint64_t photons, lucent_pool *pool,
                                            lucent_slab_transmittance *dest)
{
    lucent_slab_transmittance_grid(m, dest);
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < LUCENT_SLAB_SAMPLES; k++) {
            lucent_mc_layer layer = {.n = m->eta,
                                     .sigma_a = m->sigma_a[c],
                                     .sigma_s = m->sigma_s[c],
                                     .g = m->g[c],
                                     .thickness = dest->thickness[k]};
            lucent_mc_desc d = {.layers = &layer,
                                .layer_count = 1,
                                .photons = photons,
                                .seed = 1 + (uint64_t)k,
                                .grid = {.dr = 1, .dz = 1, .nr = 1, .nz = 1, .na = 1},
                                .batches = 4,
                                .pool = pool,
                                .label = "translucency: slab transmittance"};
            lucent_mc_result res = {0};
            lucent_status s = lucent_mc_run(&d, &res);
            if (s != LUCENT_OK) return lucent_error_context(s, "material %s: slab transmittance", m->name);
            dest->value[k][c] = res.tt;
            lucent_mc_result_free(&res);
        }
    return LUCENT_OK;
}

/* Log-linear between the samples, diffusion's exponential tail beyond the last. */
double lucent_slab_transmittance_eval(const lucent_slab_transmittance *t, int c, double s)
{
    const double floor_t = 1e-30;
    if (s <= THINNEST) return t->value[0][c];
    if (s >= t->s_max) return t->value[LUCENT_SLAB_SAMPLES - 1][c] * exp(-t->sigma_tr[c] * (s - t->s_max));
    int k = (int)floor(sqrt(s / t->s_max) * (LUCENT_SLAB_SAMPLES - 1));
    if (k >= LUCENT_SLAB_SAMPLES - 1) k = LUCENT_SLAB_SAMPLES - 2;
    double s0 = t->thickness[k], s1 = t->thickness[k + 1], w = (s - s0) / (s1 - s0);
    double l0 = log(fmax(t->value[k][c], floor_t)), l1 = log(fmax(t->value[k + 1][c], floor_t));
    return exp(l0 + w * (l1 - l0));
}

/* Light entering a uniformly lit back face of a slab of thickness s reaches the front point opposite
 * from every entry point at distance rho = sqrt(r^2 + s^2); with the profile R(rho) that is
 * integral 2 pi r R(sqrt(r^2 + s^2)) dr = integral_s^inf 2 pi rho R(rho) drho: the profile's power
 * outside radius s. With R piecewise constant over the bins, bin k holding [k dr, (k+1) dr], the tail
 * is exact: sum_{k > K} R_k pi ((k+1)^2 - k^2) dr^2 + R_K pi ((K+1)^2 dr^2 - s^2), K = floor(s / dr). */
double lucent_profile_tail(const lucent_profile *p, int c, double s)
{
    double dr = p->dr, t = 0;
    int K = (int)floor(s / dr);
    if (K >= p->count) return 0;
    for (int k = p->count - 1; k > K; k--)
        t += p->value[c][k] * M_PI * ((k + 1.0) * (k + 1.0) - (double)k * k) * dr * dr;
    return t + p->value[c][K] * M_PI * ((K + 1.0) * (K + 1.0) * dr * dr - s * s);
}
