// tsd, one 1-D pass of the Gaussian chain (GPU Gems 3 14.4.2, the convolution passes): the input
// blurred by a Gaussian of standard deviation u_sigma mm along u_axis, taps spaced evenly over
// +-3 sigma (7 taps: d'Eon's spacing of one sigma) with weights exp(-x^2 / 2), the tap spacing in
// texels scaled by the stretch map (texels per mm along that axis) at this texel. Each tap reads the
// two texels about its position linearly, keeping only texels of this texel's chart (the stretch
// map's z), and the sum is divided by the weight kept: a normalised convolution within the chart, so
// that no light comes from the unrelated charts packed beside it. The vertical pass (u_axis.y = 1)
// also writes w G to the second output, which the renderer blends into the sum of Gaussians.
layout(binding = 0) uniform sampler2D u_source;  // rgb; a: 1 where a chart (or its gutter) is
layout(binding = 1) uniform sampler2D u_stretch; // texels per mm along u, v; z: chart + 1 (0: none)

uniform ivec2 u_axis;
uniform float u_sigma; // mm
uniform int u_taps;    // odd
uniform vec3 u_weight; // w_i per channel (vertical pass)

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_sum;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(u_source, 0) - 1;
    vec4 st = texelFetch(u_stretch, p, 0);
    if (st.z <= 0.0) { // outside every chart and its gutter
        o_color = vec4(0.0);
        o_sum = vec4(0.0);
        return;
    }
    float texels = u_sigma * dot(st.xy, vec2(u_axis)); // sigma in texels here
    int half_taps = u_taps / 2;
    float spacing = 3.0 / float(half_taps);             // in sigmas
    vec3 sum = vec3(0.0);
    float kept = 0.0;
    for (int k = -half_taps; k <= half_taps; k++) {
        float x = float(k) * spacing, w = exp(-0.5 * x * x), at = x * texels, f = floor(at), t = at - f;
        ivec2 q0 = clamp(p + u_axis * int(f), ivec2(0), last), q1 = clamp(p + u_axis * (int(f) + 1), ivec2(0), last);
        float w0 = texelFetch(u_stretch, q0, 0).z == st.z ? w * (1.0 - t) : 0.0;
        float w1 = texelFetch(u_stretch, q1, 0).z == st.z ? w * t : 0.0;
        sum += w0 * texelFetch(u_source, q0, 0).rgb + w1 * texelFetch(u_source, q1, 0).rgb;
        kept += w0 + w1;
    }
    o_color = vec4(kept > 0.0 ? sum / kept : texelFetch(u_source, p, 0).rgb, 1.0);
    o_sum = vec4(u_weight * o_color.rgb, 1.0); // a: the Gaussians summed here (the final pass's coverage)
}
