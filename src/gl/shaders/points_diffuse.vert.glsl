// Splat-based diffusion (Kim et al. 2.2): each surfel of the chosen level spreads its radiance as a
// Gaussian of variance v (one of the sum of Gaussians), in object space: the screen box of the
// sphere of sog_cutoff standard deviations around it. The variance is at least the surfel's own
// reconstruction variance (radius / cutoff)^2, so a level never samples a Gaussian narrower than
// its spacing allows (for those the result is the splatted irradiance itself, the paper's first
// image).
#include "points.glsl"

layout(std430, binding = 1) readonly buffer Radiance { vec4 radiance[]; };

uniform int u_first;
uniform float u_variance;   // mm^2
uniform float u_radius_scale;
uniform float u_cutoff;     // the reconstruction's standard deviations at the radius
uniform float u_support;    // standard deviations of the diffusion splat
uniform vec2 u_viewport;

flat out vec3 v_c;
flat out vec3 v_n;
flat out vec3 v_radiance;
flat out float v_variance;
flat out float v_amplitude;
flat out float v_support2;

void main()
{
    int j = u_first + gl_InstanceID;
    Surfel s = surfels[j];
    vec4 l = radiance[j];
    float sr = s.p.w * u_radius_scale / u_cutoff, v = max(u_variance, sr * sr), rho = u_support * sqrt(v);
    v_c = s.p.xyz, v_n = s.n.xyz, v_radiance = l.rgb, v_variance = v, v_support2 = rho * rho;
    v_amplitude = l.w / (2.0 * PI * v); // area x G(v, 0)
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    bool front = true;
    for (int k = 0; k < 8; k++)
        front = box_add(u_view_proj, s.p.xyz + rho * vec3((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0,
                                                         (k & 4) != 0 ? 1.0 : -1.0), lo, hi) && front;
    if (!front) lo = vec2(-1.0), hi = vec2(1.0); // the sphere reaches behind the eye: the whole view
    gl_Position = box_corner(max(lo, vec2(-1.0)), min(hi, vec2(1.0)), 2.0 / u_viewport, gl_VertexID);
}
