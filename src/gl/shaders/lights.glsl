// Lights, shadow maps, shadow-map thickness and the specular lobe. Needs common.glsl.
layout(binding = 1) uniform sampler2DArrayShadow u_shadow_cmp; // depth compare (PCF)
layout(binding = 2) uniform sampler2DArray u_shadow_depth;     // the same depths, read raw
layout(binding = 4) uniform sampler2D u_transmit;              // T(s) per channel; a row per material
uniform float u_transmit_range; // mm: thickness where the table ends
uniform float u_transmit_v;     // the material's row, as a texture coordinate

// The direction toward light i from p and the irradiance it gives a surface facing it
// (directional: colour x intensity; point: intensity / d^2).
vec3 light_incident(int i, vec3 p, out vec3 l)
{
    vec4 v = u_light_vec[i];
    if (v.w == 0.0) {
        l = -v.xyz;
        return u_light_rgb[i].rgb;
    }
    vec3 d = v.xyz - p;
    float d2 = max(dot(d, d), 1e-12);
    l = d * inversesqrt(d2);
    return u_light_rgb[i].rgb / d2;
}

// Position in light i's shadow map: xy texture coordinates, z depth in [0, 1].
vec3 shadow_coord(int i, vec3 p)
{
    vec4 c = u_light_matrix[i] * vec4(p, 1.0);
    return c.xyz / c.w * 0.5 + 0.5;
}

// The light's depth in mm (ortho: linear; perspective: eye z from the stored window depth).
float light_depth_mm(int i, float z01)
{
    float n = u_light_shadow[i].y, f = u_light_shadow[i].z;
    if (u_light_shadow[i].w > 0.5) return n + z01 * (f - n);
    float ndc = z01 * 2.0 - 1.0;
    return 2.0 * n * f / (f + n - ndc * (f - n));
}

// Fraction of light i reaching p (3 x 3 PCF over bilinear depth compares). p should be offset
// along the normal by the caller (normal-offset bias).
float shadow_visibility(int i, vec3 p)
{
    float layer = u_light_shadow[i].x;
    if (layer < 0.0) return 1.0;
    vec3 c = shadow_coord(i, p);
    if (any(lessThan(c, vec3(0.0))) || any(greaterThan(c, vec3(1.0)))) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_cmp, 0).xy);
    float sum = 0.0;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++) sum += texture(u_shadow_cmp, vec4(c.xy + vec2(x, y) * texel, layer, c.z));
    return sum / 9.0;
}

// Distance light i travels inside matter to reach p: p's depth from the light minus the depth of the
// first surface the light meets on its way (Jimenez 2010, from the shadow map). -1: no shadow map.
float shadow_thickness(int i, vec3 p)
{
    float layer = u_light_shadow[i].x;
    if (layer < 0.0) return -1.0;
    vec3 c = shadow_coord(i, p);
    if (any(lessThan(c.xy, vec2(0.0))) || any(greaterThan(c.xy, vec2(1.0)))) return -1.0;
    float first = texture(u_shadow_depth, vec3(c.xy, layer)).r;
    float dz = max(light_depth_mm(i, clamp(c.z, 0.0, 1.0)) - light_depth_mm(i, first), 0.0);
    if (u_light_vec[i].w == 0.0) return dz;
    float z = light_depth_mm(i, clamp(c.z, 0.0, 1.0)); // perspective: along the ray, not the axis
    return dz * length(p - u_light_vec[i].xyz) / max(z, 1e-6);
}

// The transmittance through thickness s (table samples on the end points).
vec3 transmittance(float s)
{
    if (s < 0.0) return vec3(0.0);
    float size = float(textureSize(u_transmit, 0).x);
    float u = (0.5 + clamp(s / u_transmit_range, 0.0, 1.0) * (size - 1.0)) / size;
    return texture(u_transmit, vec2(u, u_transmit_v)).rgb;
}

// Kelemen & Szirmay-Kalos specular (d'Eon & Luebke 2007, GPU Gems 3 ch. 14): Beckmann D with alpha =
// roughness, Schlick's Fresnel with f0, and KSK's visibility 1 / |l + v|^2 in place of
// G / (4 cos_i cos_o); returns f_s cos_i, the factor of the light's irradiance.
float specular_ksk(vec3 n, vec3 v, vec3 l, float roughness, float f0)
{
    float ndl = dot(n, l);
    vec3 h = l + v;
    float hh = dot(h, h);
    if (ndl <= 0.0 || dot(n, v) <= 0.0 || hh < 1e-8) return 0.0;
    vec3 hn = h * inversesqrt(hh);
    float c = max(dot(n, hn), 1e-4), c2 = c * c, a2 = max(roughness * roughness, 1e-6);
    float d = exp((c2 - 1.0) / (c2 * a2)) / (PI * a2 * c2 * c2);
    float f = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(hn, v), 0.0, 1.0), 5.0);
    return d * f / hh * ndl;
}
