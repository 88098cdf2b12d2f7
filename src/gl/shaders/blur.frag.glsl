// One 1-D pass of Jimenez's separable subsurface scattering (Freude Algorithm 4.1), for any tap set
// of lucent_kernel_taps; the renderer runs a horizontal and a vertical pass per kernel rank.
// The CPU reference is lucent_ssss_blur_cpu (src/gl/blur_cpu.c), written separately.
//
// Kernel width: a tap's offset o (mm, along the surface) spans o * s / z pixels at linear depth z,
// s = width_scale * height / (2 tan(fov_y / 2)): the projection's pixels per mm at 1 mm, the same
// along x and y for square pixels. This replaces Jimenez's step, sssWidth / (tan(fov_y / 2) z) / 3
// in texture units for both axes, whose divisor 3 is arbitrary and which stretches the kernel by
// width / height along x (Freude Eq. 4.11).
//
// Depth awareness: each of the two pixels a fractional tap reads keeps a fraction a of its weight:
// follow (Jimenez, Freude Eq. 4.12): a = 1 - min(|dz| / R, 1), the rest going to the centre pixel
// (the lerp s = o (1 - t) + i t); gaussian (as EEVEE): a = exp(-dz^2 / (2 (R/2)^2)), the result
// renormalised by the kept weight (the rest to the centre for signed passes); none: a = 1.
// Background pixels (z = 0) give a = 0. R = the kernel's half-width times width_scale (mm).
layout(binding = 0) uniform sampler2D u_source; // rgb: irradiance (or the previous pass)
layout(binding = 1) uniform sampler2D u_depth;  // x: linear depth (mm, 0 = background); y: material
layout(binding = 2) uniform sampler2D u_taps;   // texel (k, material * rank + pass): rgb weight, a offset
                                                // (mm); column count: (R mm, all weights >= 0, 0, 0);
                                                // column count + 1: the pass's sign per channel
uniform ivec2 u_axis;     // (1, 0) horizontal, (0, 1) vertical
uniform int u_pass;       // kernel pass (rank index)
uniform int u_rank;
uniform int u_count;      // taps
uniform int u_vertical;   // 1: the second pass of a kernel pass (applies the sign)
uniform float u_scale;    // s above
uniform int u_filter;     // 0 follow, 1 gaussian, 2 none (lucent_depth_filter)

layout(location = 0) out vec4 o_color;

float kept(float z_sample, float z, float r)
{
    if (z_sample <= 0.0) return 0.0;
    if (u_filter == 2) return 1.0;
    float dz = z_sample - z;
    if (u_filter == 1) return exp(-2.0 * dz * dz / (r * r));
    return 1.0 - min(abs(dz) / r, 1.0);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(u_source, 0) - 1;
    vec2 zm = texelFetch(u_depth, p, 0).xy;
    vec3 centre = texelFetch(u_source, p, 0).rgb;
    if (zm.x <= 0.0) { // background: passes its input through once
        o_color = vec4(u_pass == 0 || u_vertical == 0 ? centre : vec3(0.0), 1.0);
        return;
    }
    int row = int(zm.y + 0.5) * u_rank + u_pass;
    vec4 meta = texelFetch(u_taps, ivec2(u_count, row), 0);
    float step = u_scale / zm.x; // pixels per mm here
    vec3 sum = vec3(0.0), lost = vec3(0.0), total = vec3(0.0);
    for (int k = 0; k < u_count; k++) {
        vec4 tap = texelFetch(u_taps, ivec2(k, row), 0);
        float x = tap.a * step, f = floor(x), t = x - f;
        ivec2 q0 = clamp(p + u_axis * int(f), ivec2(0), last), q1 = clamp(p + u_axis * (int(f) + 1), ivec2(0), last);
        float a0 = kept(texelFetch(u_depth, q0, 0).x, zm.x, meta.x);
        float a1 = kept(texelFetch(u_depth, q1, 0).x, zm.x, meta.x);
        sum += tap.rgb * ((1.0 - t) * a0 * texelFetch(u_source, q0, 0).rgb + t * a1 * texelFetch(u_source, q1, 0).rgb);
        lost += tap.rgb * ((1.0 - t) * (1.0 - a0) + t * (1.0 - a1));
        total += tap.rgb;
    }
    vec3 result;
    if (u_filter == 1 && meta.y > 0.5) {
        vec3 keep = total - lost;
        result = mix(total * centre, sum * total / max(keep, vec3(1e-20)), greaterThan(keep, vec3(1e-6) * total));
    } else {
        result = sum + lost * centre;
    }
    if (u_vertical != 0) result *= texelFetch(u_taps, ivec2(u_count + 1, row), 0).rgb;
    o_color = vec4(result, 1.0);
}
