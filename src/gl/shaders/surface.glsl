// The surface pass shared by the mesh methods (lambert, cdrf, ssss): diffuse (pre-blur), specular
// and linear depth in separate targets (Freude 4.2, pass 1). A method's fragment shader includes this
// file and defines the three functions declared below; everything else is common. Radiance units: a
// light's irradiance E on a surface of albedo a gives a E cos / pi.
#include "common.glsl"
#include "lights.glsl"

in vec3 v_position;
in vec3 v_normal;
in float v_curvature;
in vec2 v_uv;

layout(binding = 0) uniform sampler2D u_albedo_map;

uniform vec3 u_albedo;
uniform vec3 u_sigma0;          // mm (cdrf)
uniform int u_use_map;          // albedo from u_albedo_map (linear RGB)
uniform int u_sigma0_from_map;  // sigma0 = d_c^2 (Kubo Eq. 6) from the diffuse map
uniform float u_roughness;
uniform float u_eta;           // the material's index of refraction (the boundary's Fresnel)
uniform vec3 u_sigma_t;        // mm^-1: the material's extinction sigma_a + sigma_s (thin parts' unscattered light)
uniform float u_strength;       // ssss: the blur's share here (object's sss_strength x settings)
uniform float u_material;       // material index (kernel and transmittance row)
uniform float u_object;
uniform int u_transmit_albedo;  // 1: T is the profile's T(s) / T(0), times the albedo (Jimenez);
                                // 0: T is the slab's own transmittance
uniform float u_shadow_offset;  // normal offset, in shadow-map texels

layout(location = 0) out vec4 o_diffuse;  // rgb: diffuse radiance; a: blur strength
layout(location = 1) out vec4 o_specular; // rgb: specular radiance; a: the view cosine mu_o (the exit)
layout(location = 2) out vec2 o_depth;    // x: linear depth (mm, 0 = background); y: material
#if AOV
layout(location = 3) out vec4 o_aov_normal;   // xyz: shading normal; w: curvature
layout(location = 4) out vec4 o_aov_position; // xyz: position (mm); w: object index
layout(location = 5) out vec4 o_aov_light;    // light 0: visibility, 0, thickness
#endif

// The method's part: light i's shadow visibility at the surface (n the shading normal, l toward the
// light, offset the normal offset in mm), the irradiance it gives (E the light's irradiance), and the
// factor of the light transmitted through thin parts (0: none).
float method_visibility(int i, vec3 n, vec3 l, float ndl, float offset);
vec3 method_irradiance(vec3 e, float ndl, vec3 sigma0);
vec3 method_transmission(vec3 sigma0);

uniform int u_tr_sog_count; // the material's profile as Gaussians (translucency.c): variances (mm^2)
uniform vec3 u_tr_sog_var[6];
uniform vec3 u_tr_sog_w[6]; // and weights summing to 1 per channel
uniform float u_convex_carried; // 1: the method's own diffusion carries the light through convex bodies
                                // (the CDRF, fitted to Monte Carlo spheres whose dark side holds it)

#ifdef CURVED
// Curved parts (render.curved_parts; docs/render.md, "Curved parts"): the exitance of the material's
// Monte Carlo spheres behind the tracer's boundary (the spheres bake), over the half-space's at the
// same incidence, per 10 degrees of theta (across) and radius r0 2^(k/2) (down; a last row for the flat
// limit, max(cos theta, 0)), a layer per material: the factor that replaces max(n.l, 0) (or Kubo's
// CDRF) for a point of mean curvature kappa. Past the terminator it holds the light that crosses the
// body, so the convex-body branch of translucency adds none (u_convex_carried).
layout(binding = 10) uniform sampler2DArray u_spheres;
uniform float u_sphere_r0;       // mm: the first row's radius
uniform float u_sphere_reach;    // mm: how far toward the light a point past the terminator is lit from
const float SPHERE_RADII = 16.0; // LUCENT_BAKE_SPHERE_RADII

// The row of curvature kappa: 2 log2(r / r0) for r = 1 / kappa up to the last radius, then linear in
// kappa to the flat row at kappa 0 (concave points are flat), as a texture coordinate.
float curved_row(float kappa)
{
    float last = SPHERE_RADII - 1.0, rmax = u_sphere_r0 * exp2(0.5 * last), k = max(kappa, 0.0);
    return k * rmax >= 1.0 ? clamp(2.0 * log2(1.0 / (k * u_sphere_r0)), 0.0, last) : last + (1.0 - k * rmax);
}

// The spheres' exitance factor for light at n.l = ndl (the table's first half).
vec3 curved_factor(float ndl, float kappa)
{
    float x = acos(clamp(ndl, -1.0, 1.0)) / PI;
    return texture(u_spheres, vec3(x, (curved_row(kappa) + 0.5) / (2.0 * (SPHERE_RADII + 1.0)), u_material)).rgb;
}

// How the light from l leaves toward v: on a small body it leans down the surface, away from the light,
// 1 + beta v . f with f the unit tangent away from the light (the table's second half).
vec3 curved_lean(float ndl, float kappa, vec3 n, vec3 l, vec3 v)
{
    float x = acos(clamp(ndl, -1.0, 1.0)) / PI;
    vec3 beta = texture(u_spheres, vec3(x, (curved_row(kappa) + SPHERE_RADII + 1.5) / (2.0 * (SPHERE_RADII + 1.0)),
                                        u_material)).rgb;
    vec3 f = n * ndl - l;
    float fl = length(f), vf = fl > 1e-6 ? dot(v, f) / fl : 0.0;
    return max(1.0 + beta * vf, vec3(0.0));
}

// Past the terminator a point is lit through its body from where the light ray enters it (the shadow
// map's thickness, up to u_sphere_reach): that entry point's visibility.
float curved_visibility(int i, vec3 n, vec3 l, float ndl, float offset)
{
    float through = 0.0;
    if (ndl < 0.0) {
        float s = shadow_thickness(i, v_position - n * offset);
        if (s >= 0.0) through = min(s, u_sphere_reach) + 2.0 * offset;
    }
    return shadow_visibility(i, v_position + n * offset + l * through);
}
#endif

// The profile's power outside radius s over its total, sum_k w_k exp(-s^2 / (2 v_k)) (Jimenez 2010).
vec3 profile_tail(float s)
{
    vec3 t = vec3(0.0);
    for (int k = 0; k < u_tr_sog_count; k++) t += u_tr_sog_w[k] * exp(-s * s / (2.0 * u_tr_sog_var[k]));
    return t;
}

// Light reaching the back of a thin part and leaving here: E max(-n.l, 0) T(s) (Jimenez 2010; T the
// Monte Carlo slab transmittance or the material's own profile, docs/render.md), times the method's
// factor (the curvature modulation of the CDRF blog for cdrf+translucency). T of a slab is the light
// of a back face lit over its whole extent; through a convex body the lit face curves away and the
// light that crosses near the terminator is the diffusion the blur (or the CDRF) already carries
// round it, so there T is the profile's power beyond the chord, the light that reaches s mm from where
// it entered. Which case a point is in the shadow map's chord tells: on a body that the point's
// osculating sphere (radius 1 / kappa, kappa the mean curvature) describes, the chord along l is
// 2 |n.l| / kappa; a chord much shorter (a thin sheet, kappa ~ 0) is a thin part. The weight of the
// convex case is smoothstep(0.25, 0.75, s kappa / (2 |n.l|)); a method whose diffusion already holds
// the light through convex bodies (u_convex_carried) adds none there. Returns the radiance factor of E / pi
// before the albedo (the profile's part carries it here). With the sheet tables (u_sheet) a thin part's
// T(s) is the sheet's: its diffuse rest, over the exit curve that the compose pass applies, is returned
// (into the diffuse target, blurred); its lobe, which has left through the front face already, goes to
// `lobe` (E / pi factor, added after any blur with the specular).
vec3 transmitted(int i, vec3 n, vec3 v, vec3 l, vec3 e, float ndl, float offset, float mu_o, vec3 sigma0, vec3 albedo,
                 out vec3 lobe)
{
    lobe = vec3(0.0);
    vec3 m = method_transmission(sigma0);
    if (ndl >= 0.0 || all(equal(m, vec3(0.0)))) return vec3(0.0);
    float s;
    vec3 ne;
    if (!thin_chord(i, v_position, n, ndl, offset, s, ne)) return vec3(0.0);
    float convex = u_tr_sog_count > 0 ? smoothstep(0.25, 0.75, s * max(v_curvature, 0.0) / (2.0 * max(-ndl, 1e-3)))
                                      : 0.0;
    vec3 thin;
    if (u_sheet != 0) {
        thin = sheet_through(s, v, l, mu_o, u_material, lobe);
        lobe *= e * -ndl * m * (1.0 - convex);
    } else {
        // the slab's T(s) less its unscattered part (1 - F0)^2 e^(-sigma_t s), which leaves as the lobe
        float r0 = (u_eta - 1.0) / (u_eta + 1.0), t0 = (1.0 - r0 * r0) * (1.0 - r0 * r0);
        vec3 direct = u_transmit_albedo != 0 ? vec3(0.0) : t0 * exp(-u_sigma_t * s);
        thin = max(transmittance(s) - direct, vec3(0.0)) * (u_transmit_albedo != 0 ? albedo : vec3(1.0));
        // the profile's T(s) (Jimenez's model) holds no unscattered part to take out: no lobe beside it
        if (u_transmit_albedo == 0) lobe = PI * e * thin_ballistic(n, v, l, ne, s, u_roughness, u_eta, u_sigma_t) * m;
    }
    vec3 t = mix(thin, albedo * profile_tail(s) * (1.0 - u_convex_carried), convex);
    return e * -ndl * t * m;
}

void main()
{
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 v = normalize(u_eye.xyz - v_position);
    n = face_viewer(n, v);
    float mu_o = clamp(dot(n, v), 0.0, 1.0);
    vec3 albedo = u_use_map != 0 ? texture(u_albedo_map, v_uv).rgb : u_albedo;
    vec3 sigma0 = u_sigma0_from_map != 0 ? albedo * albedo : u_sigma0;
    vec3 irradiance = vec3(0.0), transmitted_e = vec3(0.0), specular = vec3(0.0), lobe_e = vec3(0.0);
    float vis0 = 1.0;
    for (int i = 0; i < u_counts.x; i++) {
        vec3 l, e = light_incident(i, v_position, l);
        float ndl = dot(n, l), offset = u_light_texel[i].x * u_shadow_offset;
        float vis = method_visibility(i, n, l, ndl, offset);
        vec3 entry = boundary_entry(max(ndl, 0.0), mu_o, u_material);
#ifdef CURVED
        entry *= curved_lean(ndl, v_curvature, n, l, v);
#endif
        irradiance += method_irradiance(e, ndl, sigma0) * vis * entry;
        vec3 lobe;
        transmitted_e += transmitted(i, n, v, l, e, ndl, offset, mu_o, sigma0, albedo, lobe);
        lobe_e += lobe;
        specular += e * boundary_reflection(n, v, l, u_roughness, u_eta) * vis;
        if (i == 0) vis0 = vis;
    }
    irradiance += bounce_entering(v_position, n, mu_o, u_material); // light between surfaces
    vec3 through = transmitted_e / PI;
    o_diffuse = vec4(albedo * (irradiance / PI + u_ambient.rgb) + through, u_strength);
    // The diffuse light's way out toward the viewer (boundary.glsl) is applied by the compose pass after
    // any blur, from the view cosine here and the material.
    o_specular = vec4(specular + lobe_e / PI, mu_o);
    o_depth = vec2(dot(v_position - u_eye.xyz, u_forward.xyz), u_material);
#if AOV
    o_aov_normal = vec4(n, v_curvature);
    o_aov_position = vec4(v_position, u_object);
    o_aov_light = vec4(vis0, 0.0, u_counts.x > 0 ? shadow_thickness(0, v_position - n * u_light_texel[0].x *
                                                                                       u_shadow_offset) : -1.0, 0.0);
#endif
}
