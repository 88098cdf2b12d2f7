// The points method (src/gl/methods/points.c): surfels in storage buffers, read by instance or
// vertex index, and what its passes share. Kim, Bickel, Gross & Choi (seed 001), Figure 1.
#include "common.glsl"
#include "lights.glsl"

struct Surfel {
    vec4 p; // xyz: centre (world mm); w: radius (mm, before radius_scale)
    vec4 n; // xyz: unit normal
    vec4 c; // rgb: albedo (the object's, or the point cloud's colour)
};

layout(std430, binding = 0) readonly buffer Surfels { Surfel surfels[]; };

// An orthonormal tangent basis of n (Duff et al. 2017, as src/base/optics.h).
void surfel_basis(vec3 n, out vec3 t, out vec3 b)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z), d = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * d, -s * n.x);
    b = vec3(d, s + n.y * n.y * a, -n.y);
}

// Grows the NDC box [lo, hi] by the point p (world); false when p is behind the eye.
bool box_add(mat4 vp, vec3 p, inout vec2 lo, inout vec2 hi)
{
    vec4 h = vp * vec4(p, 1.0);
    if (h.w <= 1e-6) return false;
    lo = min(lo, h.xy / h.w);
    hi = max(hi, h.xy / h.w);
    return true;
}

// Corner k (0..3, a triangle strip; the vertex index) of the NDC box, padded by pad.
vec4 box_corner(vec2 lo, vec2 hi, vec2 pad, int k)
{
    lo -= pad, hi += pad;
    return vec4((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y, 0.0, 1.0);
}

const vec4 CULLED = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: no fragments
