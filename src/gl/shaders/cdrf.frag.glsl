// The CDRF (Kubo Eq. 5): the irradiance of each light spread over the curvature by the CDRF of
// sigma = sigma0 kappa; with TRANSLUCENCY, light through thin parts modulated by the curvature as in
// the CDRF blog.
#include "surface.glsl"
#include "cdrf.glsl"

uniform float u_cdrf_reach;     // mm: CDRF visibility is tested this far toward the light
uniform float u_curvature_gain; // cdrf+translucency: m = 1 + gain sigma0 kappa
uniform int u_sog_count;        // the tail: the profile's Gaussians (0: Kubo's one of sigma0)
uniform vec3 u_sog_sd[8];       // their standard deviations, mm, per channel
uniform vec3 u_sog_w[8];        // their weights, summing to 1 per channel
uniform float u_tail_reach;     // mm: how far through the body the tail's light comes from


// The CDRF spreads light over an arc of sigma0 mm: visibility is tested where light enters, up to
// u_cdrf_reach mm toward the light past the terminator (none where the light faces the surface), one
// lookup serving diffuse and specular as Lambert's one does. With the tail, a point past the terminator
// is lit through its own body from where the light ray enters it: the visibility is that entry
// point's (the shadow map's thickness along the light), as far as the tail reaches.
float method_visibility(int i, vec3 n, vec3 l, float ndl, float offset)
{
#ifdef CURVED
    return curved_visibility(i, n, l, ndl, offset);
#endif
    float shift = u_cdrf_reach * (1.0 - max(ndl, 0.0));
    if (u_sog_count > 0 && ndl < 0.0) {
        float s = shadow_thickness(i, v_position - n * offset);
        if (s >= 0.0) shift = max(shift, min(s, u_tail_reach) + 2.0 * offset);
    }
    return shadow_visibility(i, v_position + n * offset + l * shift);
}

// With the tail: Kubo's Gaussian of sigma0 (fitted to Monte Carlo spheres of the material, so right
// where most of the light is) as long as it holds, and past the terminator, where a Gaussian's tail
// dies faster than any diffusion profile (which falls as exp(-sigma_tr r)), the profile's own falloff:
// Kubo Eq. 5 with the profile's Gaussians (cdrf.c, objects_sog), the larger of the two.
vec3 method_irradiance(vec3 e, float ndl, vec3 sigma0)
{
#ifdef CURVED
    return e * curved_factor(ndl, v_curvature);
#endif
    vec3 kubo = cdrf3(ndl, sigma0 * v_curvature); // Kubo Eq. 5
    if (u_sog_count == 0) return e * kubo;
    vec3 f = vec3(0.0);
    for (int k = 0; k < u_sog_count; k++) f += u_sog_w[k] * cdrf3(ndl, u_sog_sd[k] * v_curvature);
    return e * max(kubo, f);
}

vec3 method_transmission(vec3 sigma0)
{
#if TRANSLUCENCY
    return clamp(1.0 + u_curvature_gain * sigma0 * v_curvature, 0.0, 2.0);
#else
    return vec3(0.0);
#endif
}
