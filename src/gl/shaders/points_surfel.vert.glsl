// Per-surfel work, one vertex per surfel with the rasteriser off. STAGE 0: the irradiance resampled
// onto the surfels of level 0 (Kim et al. 2.2: "the diffuse color determined as the dot-product of
// the light direction and the surface normal", with the shadow test, times the boundary's entry
// factor for the surfel's view cosine, boundary.glsl), made the diffuse radiance albedo (E / pi +
// ambient) plus the light through thin parts (as ssss's surface pass; with the sheet tables the lobe
// toward the eye joins the diffuse rest here, both over the exit curve the compose pass applies, and
// is diffused with it). STAGE 1: a
// coarser level's radiance, the area-weighted mean of its children's (area ~ radius^2).
#include "points.glsl"

layout(std430, binding = 1) buffer Radiance { vec4 radiance[]; }; // rgb: radiance; w: area weight
layout(std430, binding = 2) readonly buffer ChildStart { uint child_start[]; };
layout(std430, binding = 3) readonly buffer Children { uint children[]; };

uniform int u_first;
uniform int u_impulse;       // >= 0: only that surfel (of the object's level 0) is lit, radiance 1
uniform int u_translucency;
uniform int u_transmit_albedo;
uniform float u_shadow_offset; // shadow-map texels
uniform float u_material;      // the object's row of the tables

void main()
{
    int j = u_first + gl_VertexID;
    Surfel s = surfels[j];
    float area = s.p.w * s.p.w;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
#if STAGE == 0
    vec3 p = s.p.xyz, n = s.n.xyz, e_sum = vec3(0.0), through = vec3(0.0);
    vec3 v = normalize(u_eye.xyz - p);
    float mu_o = abs(dot(n, v)); // the side facing the eye (splats show both)
    for (int i = 0; i < u_counts.x; i++) {
        vec3 l, e = light_incident(i, p, l);
        float ndl = dot(n, l), offset = u_light_texel[i].x * u_shadow_offset;
        e_sum += e * max(ndl, 0.0) * shadow_visibility(i, p + n * offset) * boundary_entry(max(ndl, 0.0), mu_o, u_material);
        float c;
        vec3 lobe;
        if (u_translucency != 0 && ndl < 0.0 && thin_chord(i, p, n, ndl, offset, c)) {
            vec3 t;
            if (u_sheet != 0) {
                t = sheet_through(c, v, l, mu_o, u_material, lobe);
                t += lobe / max(boundary_exit(mu_o, u_material), vec3(1e-3));
            } else {
                t = transmittance(c);
            }
            through += e * -ndl * t;
        }
    }
    e_sum += bounce_entering(p, n, mu_o, u_material); // light between surfaces
    vec3 l_out = s.c.rgb * (e_sum / PI + u_ambient.rgb) + through / PI * (u_transmit_albedo != 0 ? s.c.rgb : vec3(1.0));
    if (u_impulse >= 0) l_out = vec3(gl_VertexID == u_impulse ? 1.0 : 0.0);
    radiance[j] = vec4(l_out, area);
#else
    vec3 sum = vec3(0.0);
    float w = 0.0;
    for (uint k = child_start[j]; k < child_start[j + 1]; k++) {
        vec4 c = radiance[children[k]];
        sum += c.rgb * c.w, w += c.w;
    }
    radiance[j] = vec4(w > 0.0 ? sum / w : vec3(0.0), area);
#endif
}
