/* Every use of an individual render setting in the evaluations, kept together: the method a
 * compare run applies, its description in the tables, the tonemapping of its PNGs and the size
 * --scale gives a scene. */
#include <math.h>
#include <stdio.h>

#include "eval/internal.h"

lucent_status eval_method_settings(const char *method, lucent_render_settings *rs)
{
    return lucent_render_method_parse(method, &rs->method, &rs->kernel_model, &rs->kernel_rank);
}

void eval_method_describe(const lucent_render_settings *rs, char *dest, size_t size)
{
    if (rs->method == LUCENT_METHOD_SSSS)
        snprintf(dest, size, "%s rank %d, %d taps, %s profile, depth filter %s%s%s%s",
                 lucent_kernel_model_name(rs->kernel_model), rs->kernel_rank, rs->taps, rs->profile,
                 lucent_depth_filter_name(rs->depth_filter), rs->translucency ? ", " : "",
                 rs->translucency ? lucent_transmittance_name(rs->transmittance) : "",
                 rs->translucency ? " translucency" : "");
    else if (rs->method != LUCENT_METHOD_LAMBERT)
        snprintf(dest, size, "%s, %s, sigma0 from %s%s%s", lucent_cdrf_variant_name(rs->cdrf_variant),
                 rs->cdrf_lut ? "LUT" : "closed form",
                 rs->sigma0_source == LUCENT_SIGMA0_FIT ? "the sphere fit" : "the diffuse colour",
                 rs->method == LUCENT_METHOD_CDRF_TRANSLUCENCY ? ", translucency " : "",
                 rs->method == LUCENT_METHOD_CDRF_TRANSLUCENCY ? lucent_transmittance_name(rs->transmittance) : "");
    else
        snprintf(dest, size, "Lambert + specular lobe");
}

lucent_tonemap_desc eval_tonemap(const lucent_render_settings *rs)
{
    return (lucent_tonemap_desc){.op = rs->tonemap, .exposure = (float)rs->exposure};
}

void eval_scale_overrides(const lucent_scene *scene, double scale, char width[48], char height[48])
{
    snprintf(width, 48, "render.width=%ld", lround(fmax(1, scene->render.width * scale)));
    snprintf(height, 48, "render.height=%ld", lround(fmax(1, scene->render.height * scale)));
}
