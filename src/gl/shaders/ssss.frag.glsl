// ssss, the surface pass: Lambert irradiance plus the light transmitted through thin parts, blurred
// afterwards by blur.frag.glsl (Freude 4.2, pass 1).
#include "surface.glsl"

uniform int u_translucency; // light through thin parts

float method_visibility(int i, vec3 n, vec3 l, float ndl, float offset)
{
#ifdef CURVED
    return curved_visibility(i, n, l, ndl, offset);
#endif
    return shadow_visibility(i, v_position + n * offset);
}

// Lambert's, or with curved parts the factor of the material's spheres (surface.glsl), blurred after.
vec3 method_irradiance(vec3 e, float ndl, vec3 sigma0)
{
#ifdef CURVED
    return e * curved_factor(ndl, v_curvature);
#endif
    return e * max(ndl, 0.0);
}

vec3 method_transmission(vec3 sigma0)
{
    return vec3(u_translucency != 0 ? 1.0 : 0.0);
}
