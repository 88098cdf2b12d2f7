// Light between surfaces (render.bounce; docs/render.md, "Light between surfaces"): the irradiance one
// bounce of each shadow-casting light gives a point, summed over the surfels of the lights' reflective
// shadow maps (Dachsbacher & Stamminger 2005, eq. 1; bounce.frag.glsl, src/gl/bounce.c). A surfel of
// power Phi (albedo x the light's power on it) and area A sends it out diffusely, radiosity Phi / A; at
// distance d it gives
//     dE = Phi cos_r cos_s / (pi d^2 + A)
// with cos_r, cos_s the cosines at the receiver and the surfel: the form factor of a disc of area A seen
// on its axis, pi d^2 / (pi d^2 + A) times the point's, which keeps near surfels finite. No occlusion
// between the two (the paper's approximation). Needs common.glsl (u_counts.y: the surfels, 0 off) and
// boundary.glsl.
struct BounceSurfel {
    vec4 position; // xyz: mm; w: area on its face, mm^2
    vec4 normal;   // xyz
    vec4 flux;     // rgb: the power it sends out
};
layout(std430, binding = 6) readonly buffer BounceSurfels { BounceSurfel u_bounce[]; };

// The irradiance at p (normal n) that light between surfaces gives, and its mean incidence cosine in
// *mu (weighted by the irradiance; 1 where none).
vec3 bounce_irradiance(vec3 p, vec3 n, out float mu)
{
    vec3 e = vec3(0.0);
    float sum = 0.0, cos_sum = 0.0;
    for (int k = 0; k < u_counts.y; k++) {
        vec4 q = u_bounce[k].position;
        vec3 d = q.xyz - p;
        float d2 = dot(d, d), cr = dot(n, d);
        if (cr <= 0.0) continue;
        float cs = -dot(u_bounce[k].normal.xyz, d);
        if (cs <= 0.0) continue;
        float w = cr * cs / (d2 * (PI * d2 + q.w)); // cos_r cos_s / (pi d^2 + A)
        vec3 de = u_bounce[k].flux.rgb * w;
        float m = de.r + de.g + de.b;
        e += de;
        sum += m;
        cos_sum += m * cr * inversesqrt(d2);
    }
    mu = sum > 0.0 ? cos_sum / sum : 1.0;
    return e;
}

// What the methods add to their irradiance: the bounced light at p, times the boundary's entry factor at
// its mean incidence cosine, for the view cosine mu_o and the material's table row.
vec3 bounce_entering(vec3 p, vec3 n, float mu_o, float material)
{
    float mu;
    vec3 e = bounce_irradiance(p, n, mu);
    return e * boundary_entry(mu, mu_o, material);
}
