// tsd, the final shading (GPU Gems 3 14.4.4): the diffuse from the sum of Gaussians at the
// fragment's texture coordinates, albedo (sum / pi + ambient), the boundary's GGX reflection of the
// other methods with the shadow map's visibility, and in the specular target's alpha the view cosine
// for the compose pass's exit curve (boundary.glsl); the same targets as surface.glsl. With the sheet
// tables (render.thin_sheet) the thin parts' forward lobe is added here, after the texture-space blur,
// as ssss adds it (surface.glsl; docs/render.md, "Thin parts").
#include "common.glsl"
#include "lights.glsl"

in vec3 v_position;
in vec3 v_normal;
in float v_curvature;
in vec2 v_uv;

layout(binding = 3) uniform sampler2D u_sum; // sum_i w_i G_i * E, per channel

uniform vec3 u_albedo;
uniform float u_roughness;
uniform float u_eta;     // the material's index of refraction
uniform float u_material;
uniform float u_object;
uniform float u_shadow_offset;
uniform float u_gaussians; // of this object's sum
uniform int u_translucency; // light through thin parts

layout(location = 0) out vec4 o_diffuse;
layout(location = 1) out vec4 o_specular;
layout(location = 2) out vec2 o_depth;
#if AOV
layout(location = 3) out vec4 o_aov_normal;
layout(location = 4) out vec4 o_aov_position;
layout(location = 5) out vec4 o_aov_light;
#endif

void main()
{
    float n2 = dot(v_normal, v_normal);
    vec3 n = n2 > 0.0 ? v_normal * inversesqrt(n2) : vec3(0.0); // zero: a vertex without a face of area
    if (!gl_FrontFacing) n = -n;
    vec3 v = normalize(u_eye.xyz - v_position), specular = vec3(0.0), local = vec3(0.0);
    if (n2 > 0.0) n = face_viewer(n, v);
    float mu_o = clamp(dot(n, v), 0.0, 1.0);
    float vis0 = 1.0;
    for (int i = 0; i < u_counts.x; i++) {
        vec3 l, e = light_incident(i, v_position, l);
        float vis = shadow_visibility(i, v_position + n * u_light_texel[i].x * u_shadow_offset);
        specular += e * boundary_reflection(n, v, l, u_roughness, u_eta) * vis;
        local += e * max(dot(n, l), 0.0) * vis * boundary_entry(max(dot(n, l), 0.0), mu_o, u_material);
        float ndl = dot(n, l), s;
        vec3 lobe;
        if (u_translucency != 0 && u_sheet != 0 && ndl < 0.0 &&
            thin_chord(i, v_position, n, ndl, u_light_texel[i].x * u_shadow_offset, s)) {
            sheet_through(s, v, l, mu_o, u_material, lobe);
            specular += e * -ndl * lobe / PI;
        }
        if (i == 0) vis0 = vis;
    }
    // The sum's alpha counts the Gaussians summed at a texel: over u_gaussians it is the share of the
    // bilinear look-up that fell on texels of a chart. A face smaller than a texel may have none (its
    // chart was never rasterised): it keeps its own irradiance, undiffused.
    vec4 t = texture(u_sum, v_uv);
    float cover = t.a / u_gaussians;
    vec3 diffused = cover > 0.01 ? t.rgb / cover : local;
    o_diffuse = vec4(u_albedo * (diffused / PI + u_ambient.rgb), 1.0);
    o_specular = vec4(specular, mu_o);
    o_depth = vec2(dot(v_position - u_eye.xyz, u_forward.xyz), u_material);
#if AOV
    o_aov_normal = vec4(n, v_curvature);
    o_aov_position = vec4(v_position, u_object);
    o_aov_light = vec4(vis0, 0.0, -1.0, 0.0);
#endif
}
