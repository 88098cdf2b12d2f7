// tsd, the irradiance texture (GPU Gems 3 14.4.1): sum over lights of E max(n.l, 0) times the shadow
// map's visibility at the texel's surface point and the boundary's entry factor (boundary.glsl, for the
// view cosine of the texel's point), plus, with translucency, the light reaching the back
// of a thin part and leaving here, E max(-n.l, 0) T(s) with s the shadow map's thickness (the house's
// translucency, Jimenez 2010, standing in for the paper's translucent shadow maps, 14.5.2), divided by
// the albedo when T is the slab's own (the final pass multiplies by it); with the sheet tables
// (render.thin_sheet) the sheet's diffuse rest in place of T(s), its lobe added by the final pass. a = 1
// marks the texels a chart covers.
#include "common.glsl"
#include "lights.glsl"

in vec3 v_position;
in vec3 v_normal;

uniform float u_shadow_offset;  // normal offset, in shadow-map texels
uniform int u_translucency;     // light through thin parts
uniform int u_transmit_albedo;  // 1: T is the profile's T(s) / T(0), times the albedo; 0: the slab's own
uniform vec3 u_albedo;
uniform float u_material; // the material's row of the tables

layout(location = 0) out vec4 o_irradiance;

void main()
{
    float n2 = dot(v_normal, v_normal);
    if (!(n2 > 0.0)) { // a vertex without a face of non-zero area: no light, still covered
        o_irradiance = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 n = v_normal * inversesqrt(n2), e = vec3(0.0), through = vec3(0.0);
    vec3 v = normalize(u_eye.xyz - v_position);
    float mu_o = clamp(dot(n, v), 0.0, 1.0);
    for (int i = 0; i < u_counts.x; i++) {
        vec3 l, el = light_incident(i, v_position, l);
        float ndl = dot(n, l), offset = u_light_texel[i].x * u_shadow_offset;
        if (ndl > 0.0)
            e += el * ndl * shadow_visibility(i, v_position + n * offset) * boundary_entry(ndl, mu_o, u_material);
        else if (u_translucency != 0) {
            float s;
            vec3 lobe;
            if (thin_chord(i, v_position, n, ndl, offset, s))
                through += el * -ndl * (u_sheet != 0 ? sheet_through(s, v, l, mu_o, u_material, lobe) : transmittance(s));
        }
    }
    e += bounce_entering(v_position, n, mu_o, u_material); // light between surfaces
    e += u_transmit_albedo != 0 ? through : through / max(u_albedo, vec3(1e-3));
    o_irradiance = vec4(e, 1.0);
}
