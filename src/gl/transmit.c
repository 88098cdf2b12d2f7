/* The transmittance of a thin part for translucency (docs/render.md, "Translucency"): the total
 * transmittance T(s) of a slab of the material, thickness s, lit at normal incidence on one face,
 * from Lucent's Monte Carlo (lucent/mc.h: MCML's physics, Fresnel boundaries of the material's eta
 * in air). Light E reaching the back face of a locally flat part leaves the front with exitance
 * E T(s) (for uniform lighting the spatial integral of the pencil-beam transmittance), radiance
 * E T(s) / pi.
 *
 * Sampled at SAMPLES thicknesses on a quadratic grid up to s_max = 5 / sigma_tr (the slowest
 * channel's diffusion length: T is e^-5 of its thin-slab value there; at most 100 transport mean
 * free paths); between samples T is
 * interpolated in log space, beyond s_max it decays as exp(-sigma_tr s), the asymptote of diffusion
 * theory. Kept on disk per material beside the sigma0 fits. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "gl/renderer_internal.h"
#include "lucent/mc.h"

enum { SAMPLES = 20 };
#define DEFAULT_PHOTONS 20000
#define THINNEST 1e-3 /* mm: the first sample (a thickness <= 0 means a half-space to lucent_mc) */

/* The sample thicknesses: s_k = s_max (k / (SAMPLES - 1))^2, the first one THINNEST. */
static double sample_thickness(double s_max, int k)
{
    double t = (double)k / (SAMPLES - 1);
    return fmax(s_max * t * t, THINNEST);
}

/* s_max = 5 / sigma_tr of the slowest channel, but at most 100 transport mean free paths of the
 * sparsest channel: without absorption sigma_tr is 0 and T falls only as 1 / s, and the walks through
 * a slab grow as its optical thickness squared. Fills sigma_tr per channel. */
static double thickest_sample(const lucent_material *m, double sigma_tr[3])
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    double tr = INFINITY, tp = INFINITY;
    for (int c = 0; c < 3; c++) sigma_tr[c] = d.sigma_tr[c], tr = fmin(tr, d.sigma_tr[c]), tp = fmin(tp, d.sigma_t_prime[c]);
    return fmin(5 / fmax(tr, 1e-3), 100 / fmax(tp, 1e-3));
}

static void table_key(const lucent_material *m, uint64_t photons, char *dest, size_t size)
{
    snprintf(dest, size,
             "slab-transmittance v1 %s sa %.17g %.17g %.17g ss %.17g %.17g %.17g g %.17g %.17g %.17g eta %.17g "
             "photons %llu samples %d seed 1",
             m->name, m->sigma_a[0], m->sigma_a[1], m->sigma_a[2], m->sigma_s[0], m->sigma_s[1], m->sigma_s[2], m->g[0],
             m->g[1], m->g[2], m->eta, (unsigned long long)photons, SAMPLES);
}

static lucent_status simulate(const lucent_material *m, double s_max, uint64_t photons, lucent_pool *pool,
                              double t[SAMPLES][3])
{
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < SAMPLES; k++) {
            lucent_mc_layer layer = {.n = m->eta, .sigma_a = m->sigma_a[c], .sigma_s = m->sigma_s[c], .g = m->g[c],
                                     .thickness = sample_thickness(s_max, k)};
            lucent_mc_desc d = {.layers = &layer, .layer_count = 1, .photons = photons, .seed = 1 + (uint64_t)k,
                                .grid = {.dr = 1, .dz = 1, .nr = 1, .nz = 1, .na = 1}, .batches = 4, .pool = pool,
                                .label = "translucency: slab transmittance"};
            lucent_mc_result res = {0};
            lucent_status s = lucent_mc_run(&d, &res);
            if (s != LUCENT_OK) return lucent_error_context(s, "material %s: slab transmittance", m->name);
            t[k][c] = res.tt;
            lucent_mc_result_free(&res);
        }
    return LUCENT_OK;
}

static void cache_write(const char *dir, const char *path, const char *key, double s_max, double t[SAMPLES][3])
{
    cJSON *json = cJSON_CreateObject();
    double s[SAMPLES];
    for (int k = 0; k < SAMPLES; k++) s[k] = sample_thickness(s_max, k);
    if (json) {
        lucent_json_add_numbers(json, "thickness_mm", s, SAMPLES);
        lucent_json_add_numbers(json, "transmittance", &t[0][0], 3 * SAMPLES); /* [k][channel] */
    }
    gl_cache_write(dir, path, key, json);
}

/* T at thickness s of channel c from the samples (log-linear between them, diffusion's exponential
 * tail beyond the last). */
static double interpolate(double t[SAMPLES][3], double s_max, const double sigma_tr[3], int c, double s)
{
    const double floor_t = 1e-30;
    if (s <= THINNEST) return t[0][c];
    if (s >= s_max) return t[SAMPLES - 1][c] * exp(-sigma_tr[c] * (s - s_max));
    int k = (int)floor(sqrt(s / s_max) * (SAMPLES - 1));
    if (k >= SAMPLES - 1) k = SAMPLES - 2;
    double s0 = sample_thickness(s_max, k), s1 = sample_thickness(s_max, k + 1), w = (s - s0) / (s1 - s0);
    double l0 = log(fmax(t[k][c], floor_t)), l1 = log(fmax(t[k + 1][c], floor_t));
    return exp(l0 + w * (l1 - l0));
}

lucent_status gl_transmit_slab(const lucent_material *m, const lucent_renderer_desc *desc, int size, float *table,
                               double *range)
{
    double sigma_tr[3], s_max = thickest_sample(m, sigma_tr);
    uint64_t photons = desc->transmit_photons ? desc->transmit_photons : DEFAULT_PHOTONS;
    double t[SAMPLES][3];
    char key[640], path[1200];
    table_key(m, photons, key, sizeof key);
    bool cached = false;
    if (desc->cache_dir && desc->cache_dir[0]) {
        gl_cache_path(desc->cache_dir, "transmittance", key, path, sizeof path);
        cached = gl_cache_read(path, key, "transmittance", 3 * SAMPLES, &t[0][0]);
    }
    if (!cached) {
        double t0 = lucent_clock_ms();
        lucent_status s = simulate(m, s_max, photons, desc->pool, t);
        if (s != LUCENT_OK) return s;
        lucent_log(LUCENT_LOG_INFO, "slab transmittance of %s: %d thicknesses to %.3g mm in %.1f s", m->name, SAMPLES,
                   s_max, (lucent_clock_ms() - t0) * 1e-3);
        if (desc->cache_dir && desc->cache_dir[0]) cache_write(desc->cache_dir, path, key, s_max, t);
    }
    *range = 2 * s_max; /* the table runs to where T is e^-10 of thin: nothing visible beyond */
    for (int j = 0; j < size; j++)
        for (int c = 0; c < 3; c++)
            table[3 * j + c] = j == size - 1 ? 0.0f : (float)interpolate(t, s_max, sigma_tr, c, *range * j / (size - 1));
    return LUCENT_OK;
}
