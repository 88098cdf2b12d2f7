// Splats of the visibility, attribute and shadow passes (and the disks baseline): the screen box of
// each surfel's disk, padded by the screen-space prefilter; the fragment shader ray-casts the disk
// (Botsch, Hornung, Zwicker & Kobbelt 2005).
#include "points.glsl"

uniform mat4 u_vp;         // world -> clip of this pass (camera or light)
uniform vec2 u_viewport;   // pixels
uniform int u_first;       // the object's first surfel
uniform float u_radius_scale;
uniform float u_filter_px; // the prefilter's radius, pixels
uniform int u_cull;        // 1: back-facing splats are dropped (camera passes)

flat out vec3 v_c;
flat out vec3 v_n;
flat out float v_r;
flat out vec2 v_centre_px;
flat out vec3 v_albedo;

void main()
{
    Surfel s = surfels[u_first + gl_InstanceID];
    vec3 c = s.p.xyz, n = s.n.xyz;
    float r = s.p.w * u_radius_scale;
    v_c = c, v_n = n, v_r = r, v_albedo = s.c.rgb;
    if (u_cull != 0 && dot(n, u_eye.xyz - c) < 0.0) {
        gl_Position = CULLED;
        return;
    }
    vec3 t, b;
    surfel_basis(n, t, b);
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    bool front = true;
    for (int k = 0; k < 4; k++)
        front = box_add(u_vp, c + r * (((k & 1) != 0 ? t : -t) + ((k & 2) != 0 ? b : -b)), lo, hi) && front;
    vec4 h = u_vp * vec4(c, 1.0);
    if (!front || h.w <= 0.0) {
        gl_Position = CULLED;
        return;
    }
    v_centre_px = (h.xy / h.w * 0.5 + 0.5) * u_viewport;
    gl_Position = box_corner(lo, hi, 2.0 * (u_filter_px + 1.0) / u_viewport, gl_VertexID);
}
