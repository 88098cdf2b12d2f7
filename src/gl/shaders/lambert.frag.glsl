// Lambert diffuse with the boundary's GGX reflection (the baseline; Kubo Table 1).
#include "surface.glsl"

float method_visibility(int i, vec3 n, vec3 l, float ndl, float offset)
{
    return shadow_visibility(i, v_position + n * offset);
}

vec3 method_irradiance(vec3 e, float ndl, vec3 sigma0)
{
    return e * max(ndl, 0.0);
}

vec3 method_transmission(vec3 sigma0)
{
    return vec3(0.0);
}
