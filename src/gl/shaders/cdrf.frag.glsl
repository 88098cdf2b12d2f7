// The CDRF (Kubo Eq. 5): the irradiance of each light spread over the curvature by the CDRF of
// sigma = sigma0 kappa; with TRANSLUCENCY, light through thin parts modulated by the curvature as in
// the CDRF blog.
#include "surface.glsl"
#include "cdrf.glsl"

uniform float u_cdrf_reach;     // mm: CDRF visibility is tested this far toward the light
uniform float u_curvature_gain; // cdrf+translucency: m = 1 + gain sigma0 kappa

// The CDRF spreads light over an arc of sigma0 mm: visibility is tested where light enters, up to
// u_cdrf_reach mm toward the light past the terminator (none where the light faces the surface), one
// lookup serving diffuse and specular as Lambert's one does.
float method_visibility(int i, vec3 n, vec3 l, float ndl, float offset)
{
    return shadow_visibility(i, v_position + n * offset + l * u_cdrf_reach * (1.0 - max(ndl, 0.0)));
}

vec3 method_irradiance(vec3 e, float ndl, vec3 sigma0)
{
    return e * cdrf3(ndl, sigma0 * v_curvature); // Kubo Eq. 5
}

vec3 method_transmission(vec3 sigma0)
{
#if TRANSLUCENCY
    return clamp(1.0 + u_curvature_gain * sigma0 * v_curvature, 0.0, 2.0);
#else
    return vec3(0.0);
#endif
}
