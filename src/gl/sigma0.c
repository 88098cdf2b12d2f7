/* sigma0 for the CDRF, fitted to Monte Carlo spheres of the material (Kubo Fig. 6; lucent/cdrf.h),
 * with a modest photon count, and kept on disk per material so that a scene pays for it once.
 * Cost (2 shared cores, 40000 photons per channel and sphere, radii 2, 5, 10, 20 mm): Skin1 1.2 s,
 * marble 8.4 s, jade 12.6 s (high albedos walk long); docs/render.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "gl/renderer_internal.h"

static const double k_radii[] = {2, 5, 10, 20}; /* mm, as `lucent cdrf-fit` */
enum { RADII = 4, FIT_BINS = 18 };
#define DEFAULT_PHOTONS 40000

/* Everything the fit depends on, as text: the cache key (stored in the file and compared). */
static void fit_key(const lucent_material *m, lucent_cdrf_variant v, uint64_t photons, char *dest, size_t size)
{
    snprintf(dest, size,
             "v1 %s sa %.17g %.17g %.17g ss %.17g %.17g %.17g g %.17g %.17g %.17g eta %.17g %s photons %llu radii "
             "2,5,10,20 bins %d seed 1",
             m->name, m->sigma_a[0], m->sigma_a[1], m->sigma_a[2], m->sigma_s[0], m->sigma_s[1], m->sigma_s[2], m->g[0],
             m->g[1], m->g[2], m->eta, lucent_cdrf_variant_name(v), (unsigned long long)photons, FIT_BINS);
}

static void cache_write(const char *dir, const char *path, const char *key, const lucent_cdrf_fit *fit)
{
    cJSON *json = cJSON_CreateObject();
    if (json) {
        lucent_json_add_numbers(json, "sigma0_mm", fit->sigma0, 3);
        lucent_json_add_numbers(json, "kd", fit->kd, 3);
        lucent_json_add_numbers(json, "rms", fit->rms, 3);
        lucent_json_add_numbers(json, "lambert_rms", fit->lambert_rms, 3);
    }
    gl_cache_write(dir, path, key, json);
}

static lucent_status run_fit(const lucent_material *m, lucent_cdrf_variant v, const lucent_renderer_desc *d,
                             uint64_t photons, lucent_cdrf_fit *fit)
{
    lucent_cdrf_sphere_result *res = calloc(RADII, sizeof *res);
    if (!res) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < RADII && s == LUCENT_OK; i++) {
        lucent_cdrf_sphere_desc sd = {.material = m, .radius = k_radii[i], .photons = photons, .bins = FIT_BINS,
                                      .seed = 1, .pool = d->pool, .label = "CDRF sigma0 fit"};
        s = lucent_cdrf_sphere_run(&sd, &res[i]);
    }
    if (s == LUCENT_OK) s = lucent_cdrf_fit_spheres(res, RADII, v, 0, fit);
    free(res);
    return s;
}

lucent_status gl_sigma0_fit(const lucent_material *m, lucent_cdrf_variant variant, const lucent_renderer_desc *desc,
                            double dest[3], bool *cached)
{
    uint64_t photons = desc->sigma0_photons ? desc->sigma0_photons : DEFAULT_PHOTONS;
    char key[640], path[1200];
    fit_key(m, variant, photons, key, sizeof key);
    *cached = false;
    if (desc->cache_dir && desc->cache_dir[0]) {
        gl_cache_path(desc->cache_dir, "sigma0", key, path, sizeof path);
        if (gl_cache_read(path, key, "sigma0_mm", 3, dest)) return *cached = true, LUCENT_OK;
    }
    double t0 = lucent_clock_ms();
    lucent_cdrf_fit fit;
    lucent_status s = run_fit(m, variant, desc, photons, &fit);
    if (s != LUCENT_OK) return s;
    memcpy(dest, fit.sigma0, 3 * sizeof *dest);
    lucent_log(LUCENT_LOG_INFO, "sigma0 of %s (%s): %.3g %.3g %.3g mm, fitted in %.1f s", m->name,
               lucent_cdrf_variant_name(variant), dest[0], dest[1], dest[2], (lucent_clock_ms() - t0) * 1e-3);
    if (desc->cache_dir && desc->cache_dir[0]) cache_write(desc->cache_dir, path, key, &fit);
    return LUCENT_OK;
}
