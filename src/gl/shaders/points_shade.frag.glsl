// The last pass (Kim et al.'s fifth): the attributes normalised by the splats' summed weights, the
// diffused radiance of the splat-based diffusion (or, for the BRDF and disk baselines and for meshes,
// Lambert at the pixel) leaving through the boundary toward the eye as in the mesh methods (the exit
// curve, boundary.glsl), and the Kelemen/Szirmay-Kalos specular the paper uses, per light with
// the shadow test. Background where no splat landed.
#include "common.glsl"
#include "lights.glsl"

layout(binding = 5) uniform sampler2D u_g_position; // w Sum: position, w
layout(binding = 6) uniform sampler2D u_g_normal;   // w Sum: normal, f0
layout(binding = 7) uniform sampler2D u_g_object;   // object + 1, 1 for a mesh, material
layout(binding = 3) uniform sampler2D u_g_albedo;   // w Sum: albedo, roughness
layout(binding = 0) uniform sampler2D u_diffused;   // the sum of the Gaussians' images
layout(binding = 8) uniform sampler2D u_weights;    // the sum of their weights there

uniform int u_diffusion;   // 1: splat-based diffusion for splats
uniform int u_weights_out; // 1: the summed splat weight instead (the setting `weights`)
uniform vec3 u_background;
uniform float u_shadow_offset;

layout(location = 0) out vec4 o_color; // rgb: radiance; a: coverage

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 g = texelFetch(u_g_position, px, 0);
    if (u_weights_out != 0) {
        o_color = vec4(vec3(max(g.w, 0.0)), 1.0);
        return;
    }
    if (g.w <= 0.0) {
        o_color = vec4(u_background, 0.0);
        return;
    }
    vec4 gn = texelFetch(u_g_normal, px, 0), ga = texelFetch(u_g_albedo, px, 0);
    vec3 p = g.xyz / g.w, albedo = ga.rgb / g.w, v = normalize(u_eye.xyz - p), n = face_viewer(normalize(gn.xyz), v);
    float f0 = gn.w / g.w, roughness = ga.a / g.w;
    vec4 go = texelFetch(u_g_object, px, 0);
    bool mesh = go.y > 0.5;
    int m = clamp(int(go.z + 0.5), 0, 7);
    vec3 irradiance = vec3(0.0), specular = vec3(0.0);
    float mu_o = clamp(dot(n, v), 0.0, 1.0);
    for (int i = 0; i < u_counts.x; i++) {
        vec3 l, e = light_incident(i, p, l);
        float vis = shadow_visibility(i, p + n * (u_light_texel[i].x * u_shadow_offset));
        irradiance += e * max(dot(n, l), 0.0) * vis * boundary_entry(max(dot(n, l), 0.0), mu_o, float(m));
        specular += e * specular_ksk(n, v, l, roughness, f0) * vis;
    }
    irradiance += bounce_entering(p, n, mu_o, float(m)); // light between surfaces
    vec3 diffuse = albedo * (irradiance / PI + u_ambient.rgb), wsum = texelFetch(u_weights, px, 0).rgb;
    if (u_diffusion != 0 && !mesh && all(greaterThan(wsum, vec3(0.0))))
        diffuse = texelFetch(u_diffused, px, 0).rgb / max(wsum, vec3(1e-6));
    o_color = vec4(diffuse * boundary_exit(mu_o, float(m)) + specular, 1.0);
}
