// One Gaussian of the sum done: its normalised image times its RGB weight added to the diffuse sum
// (d'Eon & Luebke 2007: R(r) = sum_i w_i G(v_i, r); Kim et al. 2.2: "combined by weighted addition"),
// and the weight itself, so that a pixel no splat of some Gaussian reached (at silhouettes, where the
// attribute pass's position leaves the surface) is normalised by the weights that did.
layout(binding = 5) uniform sampler2D u_level; // rgb: sum w L; a: sum w
layout(binding = 7) uniform sampler2D u_g_object;

uniform vec3 u_weight; // this Gaussian's weights, the channel's weights summing to 1
uniform float u_object;

layout(location = 0) out vec4 o_sum;    // rgb: sum of the weighted images
layout(location = 1) out vec4 o_weight; // rgb: sum of the weights that reached the pixel

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(u_level, p, 0);
    if (a.w <= 0.0 || texelFetch(u_g_object, p, 0).x != u_object + 1.0) discard;
    o_sum = vec4(u_weight * a.rgb / a.w, 0.0);
    o_weight = vec4(u_weight, 0.0);
}
