// Lights, shadow maps, shadow-map thickness and the specular lobe. Needs common.glsl.
#include "boundary.glsl"
#include "bounce.glsl"
layout(binding = 1) uniform sampler2DArrayShadow u_shadow_cmp; // depth compare (PCF)
layout(binding = 2) uniform sampler2DArray u_shadow_depth;     // the same depths, read raw
layout(binding = 4) uniform sampler2D u_transmit;              // T(s) per channel; a row per material
uniform float u_transmit_range; // mm: thickness where the table ends
uniform float u_transmit_v;     // the material's row, as a texture coordinate

// A shading normal seen from behind (interpolated across a silhouette, or on faces wound the other way
// round: on the dragon they reach n.v = -0.9) is bent toward the viewer until it faces it, n.v = 0.01:
// seen from behind, the boundary passes no light toward the viewer and such pixels were black (issue 31).
vec3 face_viewer(vec3 n, vec3 v)
{
    float c = dot(n, v);
    return c >= 0.01 ? n : normalize(n + (0.01 - c) * v);
}

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

// The surface light i (directional: an orthographic shadow map) enters first on its way to p, from the
// shadow map's depths one texel either side: its outward normal, facing the light (*ne), and what to take
// off the depth the nearest texel holds to have the surface's own at p, in mm (*fix): the shadow pass's
// slope-scaled offset (glPolygonOffset(1.5, 2), src/gl/shadows.c), 1.5 max(|dz/dx|, |dz/dy|) per texel,
// taken off, and the surface's slope across p's offset from the texel's centre. A slanted face lit at 40
// degrees, texels of 0.55 mm, stores depths 0.7 mm too deep and +-0.23 mm apart (the oblique sheets of
// tests/test_gl_sheet.c). false (ne = l, fix 0): a perspective map, none, or a neighbour that holds nothing.
bool shadow_entry(int i, vec3 p, vec3 l, out vec3 ne, out float fix)
{
    ne = l;
    fix = 0.0;
    float layer = u_light_shadow[i].x;
    if (layer < 0.0 || u_light_shadow[i].w < 0.5) return false;
    vec3 c = shadow_coord(i, p);
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_depth, 0).xy);
    if (any(lessThan(c.xy, texel)) || any(greaterThan(c.xy, 1.0 - texel))) return false;
    float x0 = texture(u_shadow_depth, vec3(c.xy - vec2(texel.x, 0.0), layer)).r;
    float x1 = texture(u_shadow_depth, vec3(c.xy + vec2(texel.x, 0.0), layer)).r;
    float y0 = texture(u_shadow_depth, vec3(c.xy - vec2(0.0, texel.y), layer)).r;
    float y1 = texture(u_shadow_depth, vec3(c.xy + vec2(0.0, texel.y), layer)).r;
    if (max(max(x0, x1), max(y0, y1)) >= 1.0) return false;
    mat4 m = u_light_matrix[i];
    vec3 rx = vec3(m[0][0], m[1][0], m[2][0]), ry = vec3(m[0][1], m[1][1], m[2][1]);
    float mx = 2.0 * texel.x / (0.5 * length(rx)), my = 2.0 * texel.y / (0.5 * length(ry)); // mm across two texels
    float dx = light_depth_mm(i, x1) - light_depth_mm(i, x0), dy = light_depth_mm(i, y1) - light_depth_mm(i, y0);
    vec3 t = -l;
    ne = normalize(cross(normalize(rx) + (dx / mx) * t, normalize(ry) + (dy / my) * t));
    if (dot(ne, l) < 0.0) ne = -ne;
    vec2 f = fract(c.xy / texel) - 0.5; // p's offset from its texel's centre, in texels
    fix = 1.5 * 0.5 * max(abs(dx), abs(dy)) - 0.5 * (f.x * dx + f.y * dy);
    return true;
}

// Distance light i travels inside matter to reach p, signed: p's depth from the light minus the depth of
// the first surface the light meets on its way (Jimenez 2010, from the shadow map), in *s, and that
// surface's outward normal in *ne (shadow_entry; 0 where the map does not give it). false: no shadow map
// here.
bool shadow_chord(int i, vec3 p, out float s, out vec3 ne)
{
    s = 0.0;
    ne = vec3(0.0);
    float layer = u_light_shadow[i].x;
    if (layer < 0.0) return false;
    vec3 c = shadow_coord(i, p);
    if (any(lessThan(c.xy, vec2(0.0))) || any(greaterThan(c.xy, vec2(1.0)))) return false;
    float first = texture(u_shadow_depth, vec3(c.xy, layer)).r;
    float dz = light_depth_mm(i, clamp(c.z, 0.0, 1.0)) - light_depth_mm(i, first);
    if (u_light_vec[i].w == 0.0) {
        float fix;
        if (!shadow_entry(i, p, -u_light_vec[i].xyz, ne, fix)) ne = vec3(0.0);
        s = dz + fix;
        return true;
    }
    float z = light_depth_mm(i, clamp(c.z, 0.0, 1.0)); // perspective: along the ray, not the axis
    s = dz * length(p - u_light_vec[i].xyz) / max(z, 1e-6);
    return true;
}

bool shadow_chord(int i, vec3 p, out float s)
{
    vec3 ne;
    return shadow_chord(i, p, s, ne);
}

// The same, not below 0; -1: no shadow map.
float shadow_thickness(int i, vec3 p)
{
    float s;
    return shadow_chord(i, p, s) ? max(s, 0.0) : -1.0;
}

// The transmittance through thickness s (table samples on the end points).
vec3 transmittance(float s)
{
    if (s < 0.0) return vec3(0.0);
    float size = float(textureSize(u_transmit, 0).x);
    float u = (0.5 + clamp(s / u_transmit_range, 0.0, 1.0) * (size - 1.0)) / size;
    return texture(u_transmit, vec2(u, u_transmit_v)).rgb;
}

// Thin parts (docs/render.md, "Thin parts"; lucent/bake.h, the sheet part): sheets of the material behind
// the tracer's boundary, lit from behind along their normal (lucent_sheet_run), pi f of the light through
// them per exit angle (45 bins of 2 degrees across) and thickness (down: sheet_range ((j + 1) / ROWS)^2,
// the lobe's rows, then as many of the diffuse rest), a layer per material. The lobe (unscattered and once
// scattered: the light keeps its direction through two rough faces, Walter et al. 2007) is read at the
// angle between the view and the light's direction of travel, the rest at the view's angle from the normal.
layout(binding = 11) uniform sampler2DArray u_sheet_table;
uniform int u_sheet;           // 1: thin parts read the sheet tables; 0: T(s) / pi
uniform float u_sheet_range;   // mm: the last row's thickness
const float SHEET_ROWS = 24.0; // LUCENT_BAKE_SHEET_ROWS

// Part 0 (the lobe) or 1 (the rest) of the sheet tables of material `layer` at thickness s and angle theta
// (radians): linear
// in theta between the bins' centres, geometric between the thickness rows (the unscattered light falls
// as e^(-sigma_t s)), fading to 0 from one to two table ranges.
vec3 sheet_part(float part, float s, float theta, float layer)
{
    float x = clamp(theta / (0.5 * PI), 0.0, 1.0), h = 2.0 * SHEET_ROWS;
    float j = clamp(sqrt(max(s, 0.0) / u_sheet_range) * SHEET_ROWS - 1.0, 0.0, SHEET_ROWS - 1.0);
    float j0 = min(floor(j), SHEET_ROWS - 2.0), f = j - j0, row = part * SHEET_ROWS + j0;
    vec3 a = texture(u_sheet_table, vec3(x, (row + 0.5) / h, layer)).rgb;
    vec3 b = texture(u_sheet_table, vec3(x, (row + 1.5) / h, layer)).rgb;
    vec3 lin = mix(a, b, f), geo = exp(mix(log(max(a, vec3(1e-30))), log(max(b, vec3(1e-30))), f));
    vec3 t = mix(lin, geo, step(vec3(1e-30), min(a, b)));
    return t * clamp(2.0 - s / u_sheet_range, 0.0, 1.0);
}

// The light through a thin part lit from behind (E max(-n.l, 0) / pi factors; docs/render.md, "Thin
// parts"): the sheet's diffuse rest toward the viewer over the exit curve E(mu_o) that the compose pass
// applies (returned), and its lobe toward v from light direction l (in *lobe). s: the shadow chord.
vec3 sheet_through(float s, vec3 v, vec3 l, float mu_o, float layer, out vec3 lobe)
{
    lobe = sheet_part(0.0, s, acos(clamp(dot(v, -l), -1.0, 1.0)), layer);
    return sheet_part(1.0, s, acos(mu_o), layer) / max(boundary_exit(mu_o, layer), vec3(1e-3));
}

// The chord through a thin part for light i at a point p with normal n (ndl = n.l < 0): the shadow map's,
// read offset mm inside along -n, plus what that offset took off it: a sheet between parallel faces is
// offset thinner there, its chord along l offset / |n.l| shorter (a 0.5 mm sheet 800 mm wide, with shadow
// texels of 0.55 mm, read 0 mm without it; |n.l| taken as at least 0.25, the chord of a sheet lit at
// grazing being no thin part's); *ne the entry face's normal, -n (a sheet between parallel faces) where
// the map does not give it. false: no shadow map.
bool thin_chord(int i, vec3 p, vec3 n, float ndl, float offset, out float s, out vec3 ne)
{
    bool ok = shadow_chord(i, p - n * offset, s, ne);
    s = max(s + offset / max(-ndl, 0.25), 0.0);
    if (dot(ne, ne) == 0.0) ne = -n;
    return ok;
}

bool thin_chord(int i, vec3 p, vec3 n, float ndl, float offset, out float s)
{
    vec3 ne;
    return thin_chord(i, p, n, ndl, offset, s, ne);
}

// The boundary's optics, as the path tracer has them (src/base/optics.h, src/trace/bsdf.c): the one
// GLSL copy, used by every method.
// Unpolarised Fresnel reflectance of a dielectric boundary for incidence cosine cos_i and eta = n_t /
// n_i (Born & Wolf 1.5.2 eqs. 20-21; lucent_fresnel_dielectric): 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta)
{
    float st2 = (1.0 - cos_i * cos_i) / (eta * eta);
    if (st2 >= 1.0) return 1.0;
    float ct = sqrt(1.0 - st2);
    float rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (ct - eta * cos_i) / (ct + eta * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

// GGX D(m) and Smith G1 (Walter et al. 2007 eqs. 33-34; lucent_ggx_d, lucent_ggx_g1).
float ggx_d(float cos_m, float alpha)
{
    if (cos_m <= 0.0) return 0.0;
    float a2 = alpha * alpha, k = cos_m * cos_m * (a2 - 1.0) + 1.0;
    return a2 / (PI * k * k);
}

float ggx_g1(float c, float alpha)
{
    c = abs(c);
    if (c >= 1.0) return 1.0;
    if (c <= 0.0) return 0.0;
    float tan2 = (1.0 - c * c) / (c * c);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

// The rough boundary's reflection (Walter et al. 2007 eq. 20, separable Smith G = G1(i) G1(o), eq. 23),
// f_r = F(o.m) D(m) G / (4 |n.i| |n.o|) with m the half vector, times cos_i: the factor of the light's
// irradiance. alpha: the object's roughness (the tracer's GGX alpha), eta: the material's index.
float boundary_reflection(vec3 n, vec3 v, vec3 l, float alpha, float eta)
{
    float ci = dot(n, l), co = dot(n, v);
    vec3 h = l + v;
    float hh = dot(h, h);
    if (ci <= 0.0 || co <= 0.0 || hh < 1e-12) return 0.0;
    vec3 m = h * inversesqrt(hh);
    float om = dot(v, m);
    if (om <= 0.0) return 0.0;
    float a = max(alpha, 1e-3); // the tracer's smooth limit is a delta: no highlight a pixel could see
    float f = fresnel_dielectric(om, eta) * ggx_d(dot(n, m), a) * ggx_g1(ci, a) * ggx_g1(co, a) / (4.0 * ci * co);
    return f * ci;
}

// The rough boundary's transmission (Walter et al. 2007 eq. 21 with the transmitted half vector of
// eq. 16, separable Smith G): f_t = |i.m| |o.m| / (|n.i| |n.o|) eta^2 (1 - F(i.m)) D(m) G / (i.m + eta
// o.m)^2, from i outside (n.i > 0) to o inside (n.o < 0), n outward, eta the medium's index over the
// outside's. By reciprocity (Walter's eq. 22, f_t(i, o) / eta_o^2 = f_t(o, i) / eta_i^2) the light
// leaving the medium along o toward i has f_t / eta^2.
float boundary_transmission(vec3 n, vec3 i, vec3 o, float alpha, float eta)
{
    float ci = dot(n, i), co = dot(n, o);
    if (ci <= 0.0 || co >= 0.0) return 0.0;
    vec3 m = -(i + eta * o);
    float mm = dot(m, m);
    if (mm < 1e-12) return 0.0;
    m *= inversesqrt(mm);
    if (dot(m, n) < 0.0) m = -m;
    float im = dot(i, m), om = dot(o, m), den = im + eta * om;
    if (im <= 0.0 || om >= 0.0 || abs(den) < 1e-6) return 0.0;
    float a = max(alpha, 1e-3);
    return im * -om / (ci * -co) * eta * eta * (1.0 - fresnel_dielectric(im, eta)) * ggx_d(dot(n, m), a) *
           ggx_g1(ci, a) * ggx_g1(co, a) / (den * den);
}

// Thin parts, the light that crosses them unscattered (docs/render.md, "Thin parts"), toward v at a
// point of normal n lit from behind (n.l < 0), s the chord along l, ne the normal of the face the light
// enters (shadow_entry; -n for a sheet between parallel faces). The entry face is rough: its microfacet
// normals m, drawn from GGX's D(m) cos(m) (tan^2 theta_m = alpha^2 u / (1 - u)) on a fixed 4 x 4 grid of
// u and phi, refract the light into directions t = refract(-l, m), each with the weight of Walter et al.
// 2007's refraction sampled that way, (1 - F(l.m)) (l.m) G1(l) / ((ne.l) (ne.m)); each crosses s (ne.l) /
// |ne.t| mm of medium (the chord along l turned to t's) and leaves through the visible face's rough
// boundary toward v, f_t(v -> -t) / eta^2 (reciprocity) times the beam's cosine there, |n.t|, over its
// cosine at entry, |ne.t|. Returns the factor of the light's irradiance E. Through a sheet the lobe is
// about the light's own direction; through a wedge (a thin part's tapering edge) it is bent aside,
// toward a camera that the light does not face.
vec3 thin_ballistic(vec3 n, vec3 v, vec3 l, vec3 ne, float s, float alpha, float eta, vec3 sigma_t)
{
    float ci = dot(ne, l);
    if (dot(n, l) >= 0.0 || ci <= 0.0) return vec3(0.0);
    float a = max(alpha, 1e-3);
    vec3 b1 = normalize(abs(ne.x) < 0.9 ? cross(ne, vec3(1.0, 0.0, 0.0)) : cross(ne, vec3(0.0, 1.0, 0.0)));
    vec3 b2 = cross(ne, b1), sum = vec3(0.0);
    for (int k = 0; k < 16; k++) {
        float u = (float(k / 4) + 0.5) / 4.0, phi = 2.0 * PI * (float(k % 4) + 0.5 * float((k / 4) % 2)) / 4.0;
        float tan_m = a * sqrt(u / (1.0 - u)), cm = inversesqrt(1.0 + tan_m * tan_m), sm = tan_m * cm;
        vec3 m = cm * ne + sm * (cos(phi) * b1 + sin(phi) * b2);
        float lm = dot(l, m);
        if (lm <= 0.0) continue;
        vec3 t = refract(-l, m, 1.0 / eta);
        float ce = -dot(ne, t), cx = dot(n, t);
        if (ce <= 1e-4 || cx <= 0.0 || dot(t, t) == 0.0) continue;
        float w = (1.0 - fresnel_dielectric(lm, eta)) * lm * ggx_g1(ci, a) / (ci * cm);
        float f = boundary_transmission(n, v, -t, a, eta) / (eta * eta);
        sum += w * f * ci * cx / ce * exp(-sigma_t * (s * ci / ce));
    }
    return sum / 16.0;
}

// The boundary's reflection for an object described by its normal-incidence reflectance f0: the same
// lobe, eta from f0 = ((eta - 1) / (eta + 1))^2 (kept under this name for the point methods' shaders).
float specular_ksk(vec3 n, vec3 v, vec3 l, float roughness, float f0)
{
    float r = sqrt(clamp(f0, 0.0, 0.99));
    return boundary_reflection(n, v, l, roughness, (1.0 + r) / (1.0 - r));
}
