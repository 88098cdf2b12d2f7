// A diffusion splat at a pixel: the visible surface point x there (the attribute pass's normalised
// position) receives area G(v, |x - c|) of the surfel's radiance, and the same weight alone, so the
// level's image is sum w L / sum w (normalised splatting; on a plane of spacing s a single lit
// surfel of radiance 1 gives s^2 G(v, r)). Only pixels of the same object facing the same side.
#include "common.glsl"

layout(binding = 5) uniform sampler2D u_g_position; // w Sum: position, w
layout(binding = 6) uniform sampler2D u_g_normal;
layout(binding = 7) uniform sampler2D u_g_object;

uniform float u_object;

flat in vec3 v_c;
flat in vec3 v_n;
flat in vec3 v_radiance;
flat in float v_variance;
flat in float v_amplitude;
flat in float v_support2;

layout(location = 0) out vec4 o_level; // rgb: sum w L; a: sum w

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 g = texelFetch(u_g_position, p, 0);
    if (g.w <= 0.0 || texelFetch(u_g_object, p, 0).x != u_object + 1.0) discard;
    vec3 d = g.xyz / g.w - v_c;
    float d2 = dot(d, d);
    if (d2 > v_support2 || dot(texelFetch(u_g_normal, p, 0).xyz, v_n) <= 0.0) discard;
    float w = v_amplitude * exp(-0.5 * d2 / v_variance);
    o_level = vec4(v_radiance * w, w);
}
