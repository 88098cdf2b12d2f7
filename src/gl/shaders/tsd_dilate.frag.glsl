// tsd, seams (GPU Gems 3 14.4.3): a texel outside every chart (coverage 0) joins the chart of the
// nearest covered texel within u_reach texels and takes the mean of that chart's covered texels there,
// for the irradiance and the stretch (with its chart; w stays 0: not covered) alike, so that the blurs and the bilinear look-ups
// at a chart's edge read the chart's own values in the gutter.
layout(binding = 0) uniform sampler2D u_irradiance; // rgb, a: coverage
layout(binding = 1) uniform sampler2D u_stretch;    // texels per mm along u, v; z: chart + 1

uniform int u_reach;

layout(location = 0) out vec4 o_irradiance;
layout(location = 1) out vec4 o_stretch;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(u_irradiance, 0) - 1;
    vec4 c = texelFetch(u_irradiance, p, 0);
    if (c.a > 0.0) {
        o_irradiance = c;
        o_stretch = texelFetch(u_stretch, p, 0);
        return;
    }
    float chart = 0.0, nearest = 1e9;
    for (int y = -u_reach; y <= u_reach; y++)
        for (int x = -u_reach; x <= u_reach; x++) {
            ivec2 q = clamp(p + ivec2(x, y), ivec2(0), last);
            float d = float(x * x + y * y);
            if (d < nearest && texelFetch(u_irradiance, q, 0).a > 0.0) nearest = d, chart = texelFetch(u_stretch, q, 0).z;
        }
    vec4 sum = vec4(0.0), st = vec4(0.0);
    for (int y = -u_reach; y <= u_reach && chart > 0.0; y++)
        for (int x = -u_reach; x <= u_reach; x++) {
            ivec2 q = clamp(p + ivec2(x, y), ivec2(0), last);
            vec4 t = texelFetch(u_irradiance, q, 0), s = texelFetch(u_stretch, q, 0);
            if (t.a > 0.0 && s.z == chart) sum += vec4(t.rgb, 1.0), st += s;
        }
    o_irradiance = sum.a > 0.0 ? vec4(sum.rgb / sum.a, 1.0) : vec4(0.0);
    o_stretch = sum.a > 0.0 ? vec4(st.xy / sum.a, chart, 0.0) : vec4(0.0); // w 0: not covered
}
