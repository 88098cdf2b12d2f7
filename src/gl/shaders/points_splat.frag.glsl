// The splat of one surfel at a pixel: the view ray through the pixel meets the surfel's plane at q
// (ray-cast splatting, Botsch et al. 2005); the Gaussian weight uses the smaller of q's distance
// from the centre in radii and the pixel's distance from the projected centre in prefilter radii (the
// EWA-style screen-space low-pass of Botsch et al. 2005, section 3.2), so a splat never shrinks below
// the prefilter (where the prefilter alone admits the pixel, the point is the centre: off the disk,
// a grazing plane's q can lie far from the surface). The depth written is q's (depth-correct). The
// visibility and shadow passes take the disks alone (the disks cover the surface; the prefilter
// low-passes the attributes and does not decide what is in front) and push q back along the ray by
// depth_epsilon radii. PASS: 0 visibility / shadow, 1 attributes (additive), 2 disks (opaque, flat).
#include "points.glsl"

uniform mat4 u_vp;
uniform mat4 u_inv_vp;
uniform vec2 u_viewport;
uniform float u_filter_px;
uniform float u_epsilon; // radii
uniform float u_cutoff;  // standard deviations at the radius
uniform float u_f0;
uniform float u_roughness;
uniform float u_object;
uniform float u_material; // the renderer's material row (the shade pass's eta)

flat in vec3 v_c;
flat in vec3 v_n;
flat in float v_r;
flat in vec2 v_centre_px;
flat in vec3 v_albedo;

#if PASS >= 1
layout(location = 0) out vec4 o_position; // w Sum: position, w
layout(location = 1) out vec4 o_normal;   // w Sum: normal, f0
layout(location = 2) out vec4 o_albedo;   // w Sum: albedo, roughness
layout(location = 3) out vec4 o_object;   // not blended: object + 1, 0 (a splat), material, 1
#endif

void main()
{
    vec2 ndc = gl_FragCoord.xy / u_viewport * 2.0 - 1.0;
    vec4 a = u_inv_vp * vec4(ndc, -1.0, 1.0), b = u_inv_vp * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w, d = normalize(b.xyz / b.w - o);
    float dn = dot(d, v_n);
    if (abs(dn) < 1e-6) discard;
    vec3 q = o + d * (dot(v_c - o, v_n) / dn);
    vec3 e = q - v_c;
    float r3 = dot(e, e) / (v_r * v_r);
    vec2 dp = gl_FragCoord.xy - v_centre_px;
    // Visibility from the prefilter's pixels off a disk put the centre's depth a pixel beyond an edge-on
    // disk at an occluding contour, hiding the surface behind (the bunny's paw: highlights of the near
    // surface's grazing normal on the far one); so only the attribute pass uses the prefilter.
    float r2 = PASS != 1 ? r3 : min(r3, dot(dp, dp) / (u_filter_px * u_filter_px));
    if (r2 > 1.0) discard;
    if (r3 > 1.0) q = v_c; // the prefilter admitted a pixel off the disk: the splat acts as a point
#if PASS == 0
    q += d * (u_epsilon * v_r);
#endif
    vec4 h = u_vp * vec4(q, 1.0);
    gl_FragDepth = clamp(h.z / h.w * 0.5 + 0.5, 0.0, 1.0);
#if PASS >= 1
    float w = PASS == 2 ? 1.0 : exp(-0.5 * u_cutoff * u_cutoff * r2);
    o_position = vec4(q, 1.0) * w;
    o_normal = vec4(v_n, u_f0) * w;
    o_albedo = vec4(v_albedo, u_roughness) * w;
    o_object = vec4(u_object + 1.0, 0.0, u_material, 1.0);
#endif
}
