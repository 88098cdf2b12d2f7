// Light between surfaces: a reflective shadow map's texel (Dachsbacher & Stamminger 2005), the surfel
// light u_light meets first there. Its power out is the object's albedo (the boundary's hemispherical
// albedo, the light a half-space of the material sends back under the tracer's boundary) times the
// light's power on the texel, E_perp A_perp: the texel's area across the light, whatever the face's
// slant (the face takes E_perp n.l over A_perp / n.l). Sent out diffusely: radiosity B = that power
// over the face's area A_perp / n.l.
#include "common.glsl"

in vec3 v_position;
in vec3 v_normal;

uniform int u_light;
uniform vec3 u_albedo;
uniform float u_texel;           // mm: a texel's side at the scene's centre
uniform float u_centre_distance; // mm: the centre's distance from a point light (0: directional)

layout(location = 0) out vec4 o_position; // xyz: mm; w: the surfel's area on its face, mm^2
layout(location = 1) out vec4 o_normal;   // xyz: the face's normal, toward the light
layout(location = 2) out vec4 o_flux;     // rgb: the power the surfel sends out (E x mm^2)

void main()
{
    vec4 lv = u_light_vec[u_light];
    vec3 l = -lv.xyz, e = u_light_rgb[u_light].rgb;
    float across = u_texel * u_texel;
    if (lv.w != 0.0) {
        vec3 d = lv.xyz - v_position;
        float d2 = max(dot(d, d), 1e-12);
        l = d * inversesqrt(d2);
        e /= d2;
        across *= d2 / (u_centre_distance * u_centre_distance);
    }
    vec3 n = normalize(v_normal);
    float c = dot(n, l);
    if (c < 0.05) n = normalize(n + (0.05 - c) * l); // the first surface the light meets faces it
    c = max(dot(n, l), 0.05);
    o_position = vec4(v_position, across / c);
    o_normal = vec4(n, 0.0);
    o_flux = vec4(u_albedo * e * across, 1.0);
}
