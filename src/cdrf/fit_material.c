/* sigma0 of a material: Monte Carlo spheres of the given radii (Kubo Fig. 6; lucent_cdrf_sphere_run)
 * fitted together (lucent_cdrf_fit_spheres). Cost (2 shared cores, 40000 photons per channel and
 * sphere, radii 2, 5, 10, 20 mm): Skin1 1.2 s, marble 8.4 s, jade 12.6 s (high albedos walk long). */
#include <stdio.h>
#include <stdlib.h>

#include "lucent/cdrf.h"

lucent_status lucent_cdrf_fit_material(const lucent_cdrf_material_fit_desc *desc, lucent_cdrf_fit *dest,
                                       lucent_cdrf_sphere_result **spheres)
{
    static const double k_radii[LUCENT_CDRF_FIT_RADIUS_COUNT] = LUCENT_CDRF_FIT_RADII;
    const double *radii = desc->radii ? desc->radii : k_radii;
    int n = desc->radii ? desc->radius_count : LUCENT_CDRF_FIT_RADIUS_COUNT;
    if (spheres) *spheres = NULL;
    if (n < 1 || n > LUCENT_CDRF_FIT_MAX_RADII)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF fit: 1 to %d radii, got %d", LUCENT_CDRF_FIT_MAX_RADII,
                            n);
    lucent_cdrf_sphere_result *res = calloc((size_t)n, sizeof *res);
    if (!res) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < n && s == LUCENT_OK; i++) {
        char label[96];
        snprintf(label, sizeof label, "%s%ssphere r = %g mm", desc->label ? desc->label : "", desc->label ? ": " : "",
                 radii[i]);
        lucent_cdrf_sphere_desc sd = {.material = desc->material,
                                      .radius = radii[i],
                                      .roughness = desc->roughness,
                                      .photons = desc->photons,
                                      .bins = desc->bins,
                                      .cone = desc->cone,
                                      .seed = desc->seed * 64 + (uint64_t)i,
                                      .pool = desc->pool,
                                      .label = label};
        s = lucent_cdrf_sphere_run(&sd, &res[i]);
    }
    if (s == LUCENT_OK) s = lucent_cdrf_fit_spheres(res, n, desc->variant, desc->sigma0_max, dest);
    if (s == LUCENT_OK && spheres)
        *spheres = res;
    else
        free(res);
    return s;
}
