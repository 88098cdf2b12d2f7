// tsd, one 1-D pass of the Gaussian chain (GPU Gems 3 14.4.2, the convolution passes): the input
// blurred by a Gaussian of standard deviation u_sigma mm along u_axis, taps spaced evenly over
// +-3 sigma (7 taps: d'Eon's spacing of one sigma) with weights exp(-x^2 / 2), the tap spacing in
// texels scaled by the stretch map (texels per mm along that axis) at this texel. A tap whose two
// texels lie in this texel's chart reads them linearly. A tap past the chart's edge follows the seam
// (14.4.3): the first texel outside the chart on the way (found by bisection) holds the same surface
// point in the chart across (u_seam, lucent_mesh_uv_seams: the two faces of the nearest seam edge
// unfolded into one plane) and the map's derivative J, so the tap reads the other chart at
// target + J (tap - that texel). The vertical pass reads there what the horizontal pass would have
// made along this chart's u: that chart's own horizontal result runs along its own u, turned against
// ours, so the tap blurs u_previous (the horizontal pass's source) along J u itself (its points that
// fall back in this chart read this chart). A tap that finds
// no seam (the mesh's boundary) keeps only texels of this chart, and the sum is divided by the
// weight kept: a normalised convolution, no light from the unrelated charts packed beside. The
// vertical pass (u_axis.y = 1) also writes w G to the second output, which the renderer blends into
// the sum of Gaussians.
layout(binding = 0) uniform sampler2D u_source;   // rgb; horizontal: the previous link, vertical: its result
layout(binding = 1) uniform sampler2D u_stretch;  // texels per mm along u, v; z: chart + 1 (0: none); w: covered
layout(binding = 2) uniform sampler2D u_seam;     // xy: the point across, texels; z: chart + 1 here; w: across
layout(binding = 3) uniform sampler2D u_seam_j;   // J row major
layout(binding = 5) uniform sampler2D u_previous; // vertical pass: the horizontal pass's source

uniform ivec2 u_axis;
uniform float u_sigma; // mm
uniform int u_taps;    // odd
uniform int u_seams;   // 0: no tap follows a seam (each chart alone)
uniform vec3 u_weight; // w_i per channel (vertical pass)

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_sum;

ivec2 g_last;
vec2 g_size;

bool inside(ivec2 q, float chart)
{
    vec4 s = texelFetch(u_stretch, clamp(q, ivec2(0), g_last), 0);
    return s.z == chart && s.w > 0.5;
}

// The first texel outside the chart from p toward p + dir * far (outside), by bisection.
ivec2 first_outside(ivec2 p, ivec2 dir, int far, float chart)
{
    if (!inside(p, chart)) return p;
    int lo = 0, hi = far;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (inside(p + dir * mid, chart)) lo = mid;
        else hi = mid;
    }
    return clamp(p + dir * hi, ivec2(0), g_last);
}

// The source across the seam at q (texels) of chart `across`, with its weight (0: not that chart).
vec4 read_across(sampler2D tex, vec2 q, float across)
{
    ivec2 t = ivec2(floor(q));
    if (any(lessThan(t, ivec2(0))) || any(greaterThan(t, g_last)) || texelFetch(u_stretch, t, 0).z != across)
        return vec4(0.0);
    return vec4(texture(tex, q / g_size).rgb, 1.0);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    g_last = textureSize(u_source, 0) - 1;
    g_size = vec2(g_last + 1);
    vec4 st = texelFetch(u_stretch, p, 0);
    if (st.z <= 0.0) { // outside every chart and its gutter
        o_color = vec4(0.0);
        o_sum = vec4(0.0);
        return;
    }
    float texels = u_sigma * dot(st.xy, vec2(u_axis)); // sigma in texels here
    float across_texels = u_sigma * st.x;              // the horizontal pass's, for taps across a seam
    int half_taps = u_taps / 2;
    float spacing = 3.0 / float(half_taps); // in sigmas
    vec3 sum = vec3(0.0);
    float kept = 0.0;
    for (int k = -half_taps; k <= half_taps; k++) {
        float x = float(k) * spacing, w = exp(-0.5 * x * x), at = x * texels, f = floor(at), t = at - f;
        ivec2 q0 = p + u_axis * int(f), q1 = p + u_axis * (int(f) + 1);
        bool in0 = inside(q0, st.z), in1 = inside(q1, st.z);
        if (in0 && in1) {
            sum += w * ((1.0 - t) * texelFetch(u_source, q0, 0).rgb + t * texelFetch(u_source, q1, 0).rgb);
            kept += w;
            continue;
        }
        ivec2 dir = at < 0.0 ? -u_axis : u_axis;
        int d0 = abs(int(f)), d1 = abs(int(f) + 1); // steps from p to q0, q1 along dir
        int far = (!in0 && (in1 || d0 < d1)) ? d0 : d1;
        ivec2 c = first_outside(p, dir, far, st.z);
        vec4 seam = texelFetch(u_seam, c, 0);
        if (u_seams != 0 && seam.z == st.z && seam.w > 0.0) {
            vec4 jr = texelFetch(u_seam_j, c, 0);
            mat2 J = mat2(jr.x, jr.z, jr.y, jr.w); // columns: J (1, 0), J (0, 1)
            vec2 here = vec2(p) + 0.5 + vec2(u_axis) * at, from = vec2(c) + 0.5; // this chart's frame
            vec4 v = vec4(0.0);
            if (u_axis.x == 1) v = read_across(u_source, seam.xy + J * (here - from), seam.w);
            else
                for (int j = -half_taps; j <= half_taps; j++) { // back in this chart where the point is
                    float y = float(j) * spacing;
                    vec2 h = here + vec2(y * across_texels, 0.0);
                    vec4 r = inside(ivec2(floor(h)), st.z) ? vec4(texture(u_previous, h / g_size).rgb, 1.0)
                                                            : read_across(u_previous, seam.xy + J * (h - from), seam.w);
                    v += exp(-0.5 * y * y) * r;
                }
            if (v.a > 0.0) sum += w * v.rgb / v.a, kept += w;
            continue;
        }
        ivec2 c0 = clamp(q0, ivec2(0), g_last), c1 = clamp(q1, ivec2(0), g_last);
        float w0 = texelFetch(u_stretch, c0, 0).z == st.z ? w * (1.0 - t) : 0.0;
        float w1 = texelFetch(u_stretch, c1, 0).z == st.z ? w * t : 0.0;
        sum += w0 * texelFetch(u_source, c0, 0).rgb + w1 * texelFetch(u_source, c1, 0).rgb;
        kept += w0 + w1;
    }
    o_color = vec4(kept > 0.0 ? sum / kept : texelFetch(u_source, p, 0).rgb, 1.0);
    o_sum = vec4(u_weight * o_color.rgb, 1.0); // a: the Gaussians summed here (the final pass's coverage)
}
