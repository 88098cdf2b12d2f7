/* The pack's shaders in each shading language (lucent/pack.h): the separable blur as a complete pass
 * (Jimenez et al.; Freude 2014 Algorithm 4.1, the follow-surface test of Eq. 4.12), the CDRF snippet
 * (Kubo et al. Eq. 1-4 through the LUT) and the translucency snippet (T(s), Jimenez et al. 2010). The
 * GLSL dialects differ only in the blur's declarations: GLSL 4.50 (bindings and default values), GLSL
 * ES 3.00 (precision, no bindings or defaults: WebGL2), Vulkan GLSL (a descriptor set and a push-constant
 * block, for SPIR-V). Every number is written with a decimal point, which GLSL ES needs for floats. */
#include "engine/internal.h"

static void triple(FILE *f, const char *type, const double v[3])
{
    fprintf(f, "%s(%#.9g, %#.9g, %#.9g)", type, v[0], v[1], v[2]);
}

/* ---- the blur ---- */

static const char k_blur_intro[] =
    "// Lucent engine pack, %s: one 1-D pass of the separable subsurface-scattering blur (Jimenez et\n"
    "// al., Freude 2014 Algorithm 4.1). Per kernel pass p (LUCENT_SSS_RANK of them): run it with\n"
    "// axis = (1, 0), vertical = 0 from the diffuse irradiance into a temporary, then with axis = (0, 1),\n"
    "// vertical = 1 from the temporary; add the passes' results (README.md, \"The passes\").\n"
    "// Kernel width: a tap at offset o (mm) lands o * pixels_per_mm_at_1mm / z pixels away at linear\n"
    "// depth z (mm), pixels_per_mm_at_1mm = height / (2 tan(fov_y / 2)) (pinhole camera, square pixels).\n"
    "// Follow-surface (Jimenez; Freude Eq. 4.12): a tap whose depth differs from the centre's by dz falls\n"
    "// back towards the centre by min(|dz| / R, 1), R = the kernel's half-width.\n";

static void glsl_blur_declarations(FILE *f, const pack_ctx *p)
{
    switch (p->d.engine) {
    case LUCENT_PACK_GLES:
        fprintf(f,
                "// GLSL ES 3.00 (WebGL2): no binding qualifiers and no default values; set the samplers' texture\n"
                "// units and every uniform from the application (README.md gives the values).\n"
                "uniform sampler2D u_irradiance; // rgb: diffuse irradiance (or the first pass)\n"
                "uniform sampler2D u_depth;      // r: linear view depth in scene units; 0: none\n"
                "uniform vec2 u_axis;            // (1, 0), then (0, 1)\n"
                "uniform int u_pass;             // kernel pass, 0 .. LUCENT_SSS_RANK - 1\n"
                "uniform int u_vertical;         // 1 on the second (vertical) pass: applies the pass's sign\n"
                "uniform float u_mm_per_unit;    // scene units to mm (1000: metres)\n"
                "uniform float u_pixels_per_mm_at_1mm; // %#.9g for %d px high, fov_y %.6g degrees\n"
                "uniform float u_width_scale;    // an artist's multiplier (1)\n\n",
                p->r.pixels_per_mm_at_1mm, p->d.screen_height, p->d.fov_y);
        break;
    case LUCENT_PACK_VULKAN:
        fprintf(f,
                "// Vulkan: set 0 binding 0 and 1 are combined image samplers; the rest is one push-constant range\n"
                "// of 28 bytes (offsets 0, 8, 12, 16, 20, 24).\n"
                "layout(set = 0, binding = 0) uniform sampler2D u_irradiance; // rgb: diffuse irradiance\n"
                "layout(set = 0, binding = 1) uniform sampler2D u_depth;      // r: linear view depth, scene units\n"
                "layout(push_constant) uniform LucentBlur {\n"
                "    vec2 u_axis;                  // (1, 0), then (0, 1)\n"
                "    int u_pass;                   // kernel pass, 0 .. LUCENT_SSS_RANK - 1\n"
                "    int u_vertical;               // 1 on the second (vertical) pass: applies the pass's sign\n"
                "    float u_mm_per_unit;          // scene units to mm (1000: metres)\n"
                "    float u_pixels_per_mm_at_1mm; // %#.9g for %d px high, fov_y %.6g degrees\n"
                "    float u_width_scale;          // an artist's multiplier (1)\n"
                "};\n\n",
                p->r.pixels_per_mm_at_1mm, p->d.screen_height, p->d.fov_y);
        break;
    default:
        fprintf(f,
                "layout(binding = 0) uniform sampler2D u_irradiance; // rgb: diffuse irradiance (or the first pass)\n"
                "layout(binding = 1) uniform sampler2D u_depth;      // r: linear view depth in scene units; 0: none\n"
                "uniform vec2 u_axis = vec2(1.0, 0.0);\n"
                "uniform int u_pass = 0;     // kernel pass, 0 .. LUCENT_SSS_RANK - 1\n"
                "uniform int u_vertical = 0; // 1 on the second (vertical) pass: applies the pass's sign\n"
                "uniform float u_mm_per_unit = 1000.0; // scene units to mm (1000: metres)\n"
                "uniform float u_pixels_per_mm_at_1mm = %#.9g; // %d px high, fov_y %.6g degrees\n"
                "uniform float u_width_scale = 1.0;   // an artist's multiplier (ssss.width_scale)\n\n",
                p->r.pixels_per_mm_at_1mm, p->d.screen_height, p->d.fov_y);
    }
}

static void blur_glsl(FILE *f, const pack_ctx *p)
{
    static const char *const version[] = {
        "#version 450 core\n",
        "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n",
        "#version 450\n"};
    fputs(version[p->d.engine], f);
    fprintf(f, k_blur_intro, p->m->name);
    fputc('\n', f);
    fputs(p->taps_text, f);
    fprintf(f, "\nconst float LUCENT_SSS_RADIUS_MM = %#.9g; // the kernel's half-width, the depth test's range\n\n",
            p->r.radius_mm);
    glsl_blur_declarations(f, p);
    fputs("layout(location = 0) out vec4 o_color;\n\n"
          "void main()\n"
          "{\n"
          "    ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(u_irradiance, 0) - 1;\n"
          "    float z = texelFetch(u_depth, p, 0).r * u_mm_per_unit;\n"
          "    vec3 centre = texelFetch(u_irradiance, p, 0).rgb;\n"
          "    if (z <= 0.0) { // background: through once\n"
          "        o_color = vec4(u_pass == 0 || u_vertical == 0 ? centre : vec3(0.0), 1.0);\n"
          "        return;\n"
          "    }\n"
          "    float step = u_pixels_per_mm_at_1mm * u_width_scale / z; // pixels per mm here\n"
          "    float range = LUCENT_SSS_RADIUS_MM * u_width_scale;\n"
          "    vec3 sum = vec3(0.0);\n"
          "    for (int i = 0; i < LUCENT_SSS_TAPS; i++) {\n"
          "        vec4 k = LUCENT_SSS_KERNEL[u_pass * LUCENT_SSS_TAPS + i];\n"
          "        ivec2 q = clamp(p + ivec2(round(u_axis * k.a * step)), ivec2(0), last);\n"
          "        float zq = texelFetch(u_depth, q, 0).r * u_mm_per_unit;\n"
          "        float s = zq > 0.0 ? min(abs(zq - z) / range, 1.0) : 1.0;\n"
          "        sum += k.rgb * mix(texelFetch(u_irradiance, q, 0).rgb, centre, s);\n"
          "    }\n"
          "    if (u_vertical != 0) sum *= LUCENT_SSS_SIGN[u_pass];\n"
          "    o_color = vec4(sum, 1.0);\n"
          "}\n",
          f);
}

static void blur_hlsl(FILE *f, const pack_ctx *p)
{
    fprintf(f, k_blur_intro, p->m->name);
    fputs("// A pixel shader (entry point main, ps_5_0); the constants in cbuffer b0.\n\n", f);
    fputs(p->taps_text, f);
    fprintf(f,
            "\nstatic const float LUCENT_SSS_RADIUS_MM = %#.9g; // the kernel's half-width, the depth test's range\n\n"
            "Texture2D<float4> irradiance : register(t0); // rgb: diffuse irradiance (or the first pass)\n"
            "Texture2D<float> depth : register(t1);       // linear view depth in scene units; 0: none\n"
            "cbuffer LucentBlur : register(b0)\n"
            "{\n"
            "    float2 axis;                   // (1, 0) or (0, 1)\n"
            "    int pass_index;                // kernel pass, 0 .. LUCENT_SSS_RANK - 1\n"
            "    int vertical;                  // 1 on the second pass: applies the pass's sign\n"
            "    float mm_per_unit;             // scene units to mm (1000: metres)\n"
            "    float pixels_per_mm_at_1mm;    // height / (2 tan(fov_y / 2)); %#.9g for the pack's screen\n"
            "    float width_scale;             // an artist's multiplier (1)\n"
            "};\n\n"
            "float4 main(float4 position : SV_Position) : SV_Target\n"
            "{\n"
            "    int2 p = int2(position.xy);\n"
            "    uint w, h;\n"
            "    irradiance.GetDimensions(w, h);\n"
            "    int2 last = int2(w, h) - 1;\n"
            "    float z = depth.Load(int3(p, 0)) * mm_per_unit;\n"
            "    float3 centre = irradiance.Load(int3(p, 0)).rgb;\n"
            "    if (z <= 0.0) return float4(pass_index == 0 || vertical == 0 ? centre : float3(0.0, 0.0, 0.0), 1.0);\n"
            "    float step = pixels_per_mm_at_1mm * width_scale / z;\n"
            "    float range = LUCENT_SSS_RADIUS_MM * width_scale;\n"
            "    float3 sum = float3(0.0, 0.0, 0.0);\n"
            "    for (int i = 0; i < LUCENT_SSS_TAPS; i++) {\n"
            "        float4 k = LUCENT_SSS_KERNEL[pass_index * LUCENT_SSS_TAPS + i];\n"
            "        int2 q = clamp(p + int2(round(axis * k.a * step)), int2(0, 0), last);\n"
            "        float zq = depth.Load(int3(q, 0)) * mm_per_unit;\n"
            "        float s = zq > 0.0 ? min(abs(zq - z) / range, 1.0) : 1.0;\n"
            "        sum += k.rgb * lerp(irradiance.Load(int3(q, 0)).rgb, centre, s);\n"
            "    }\n"
            "    if (vertical != 0) sum *= LUCENT_SSS_SIGN[pass_index];\n"
            "    return float4(sum, 1.0);\n"
            "}\n",
            p->r.radius_mm, p->r.pixels_per_mm_at_1mm);
}

void pack_blur(FILE *f, const pack_ctx *p) { (pack_is_glsl(p->d.engine) ? blur_glsl : blur_hlsl)(f, p); }

/* ---- the CDRF ---- */

void pack_cdrf(FILE *f, const pack_ctx *p)
{
    bool hlsl = p->d.engine == LUCENT_PACK_HLSL;
    const char *vec3 = hlsl ? "float3" : "vec3", *konst = hlsl ? "static const" : "const";
    lucent_cdrf_variant v = (lucent_cdrf_variant)p->rs->cdrf.variant;
    fprintf(f,
            "// Lucent engine pack, %s: the curvature-dependent reflectance (Kubo, Dobashi & Morishima, %s\n"
            "// variant) in place of Lambert's max(dot(n, l), 0). Per channel c the reflected radiance is\n"
            "//   L_c = k_d,c * CDRF(theta; sigma = sigma0_c * kappa) * E_c\n"
            "// with E the light's irradiance (on a plane facing it), theta the angle between the normal and the\n"
            "// light, kappa the mean curvature (1/mm, > 0 convex). sigma0 and k_d are fitted to Monte Carlo spheres\n"
            "// of the material (lucent cdrf-fit). The LUT cdrf-lut.exr (%d x %d, RGB float; or cdrf-lut.png, 16-bit\n"
            "// linear, times %g) is read with linear filtering: column i holds cos theta = -1 + 2 i / (width - 1)\n"
            "// (left: light behind); row j, counted from the TOP row of the file, holds kappa = kappa_max j /\n"
            "// (height - 1). Upload the rows in file order (top row first) so that t = 0 is kappa = 0; samples sit\n"
            "// on the texel centres. A snippet: include it after your shader's #version (and precision) lines.\n\n",
            p->m->name, lucent_cdrf_variant_name(v), p->d.lut_width, p->d.lut_height, p->lut_png_scale);
    fprintf(f, "%s %s LUCENT_CDRF_SIGMA0_MM = ", konst, vec3);
    triple(f, vec3, p->b->sigma0);
    fprintf(f, ";\n%s %s LUCENT_CDRF_KD = ", konst, vec3);
    triple(f, vec3, p->b->kd);
    fprintf(f, ";\n%s float LUCENT_CDRF_KAPPA_MAX = %#.9g; // 1/mm\n", konst, p->d.kappa_max);
    fprintf(f, "%s float LUCENT_CDRF_LUT_PNG_SCALE = %#.9g; // cdrf-lut.png's values times this\n\n", konst,
            p->lut_png_scale);
    if (hlsl)
        fputs(
            "float3 lucent_cdrf(Texture2D<float4> lut, SamplerState linear_clamp, float n_dot_l, float kappa_per_mm)\n"
            "{\n"
            "    uint w, h;\n"
            "    lut.GetDimensions(w, h);\n"
            "    float2 size = float2(w, h);\n"
            "    float2 f = float2((clamp(n_dot_l, -1.0, 1.0) + 1.0) * 0.5, saturate(kappa_per_mm / "
            "LUCENT_CDRF_KAPPA_MAX));\n"
            "    return LUCENT_CDRF_KD * lut.SampleLevel(linear_clamp, (0.5 + f * (size - 1.0)) / size, 0).rgb;\n"
            "}\n",
            f);
    else
        fputs("vec3 lucent_cdrf(sampler2D lut, float n_dot_l, float kappa_per_mm)\n"
              "{\n"
              "    vec2 size = vec2(textureSize(lut, 0));\n"
              "    vec2 f = vec2((clamp(n_dot_l, -1.0, 1.0) + 1.0) * 0.5, clamp(kappa_per_mm / LUCENT_CDRF_KAPPA_MAX, "
              "0.0, 1.0));\n"
              "    return LUCENT_CDRF_KD * textureLod(lut, (0.5 + f * (size - 1.0)) / size, 0.0).rgb;\n"
              "}\n",
              f);
}

/* ---- translucency ---- */

void pack_translucency(FILE *f, const pack_ctx *p)
{
    bool hlsl = p->d.engine == LUCENT_PACK_HLSL;
    const char *vec3 = hlsl ? "float3" : "vec3";
    const lucent_baked *b = p->b;
    int n = LUCENT_BAKE_TRANSMIT_SIZE;
    lucent_transmittance_model t = p->rs->translucency.transmittance;
    fprintf(f,
            "// Lucent engine pack, %s: the light through a thickness s (mm), T(s) per channel (%s model),\n"
            "// tabulated at s = %.9g j / %d mm, j = 0 .. %d (the last entry 0; also transmittance.csv and\n"
            "// transmittance.png). Jimenez et al. 2010's translucency multiplies the light reaching the back by\n"
            "// T(thickness from the shadow map)%s (README.md, \"Thickness\"). A snippet: include it after your\n"
            "// shader's #version (and precision) lines.\n\n",
            p->m->name, lucent_transmittance_name(t), b->transmit_range, n - 1, n - 1,
            t == LUCENT_TRANSMIT_SLAB ? "" : " and the albedo");
    fprintf(f, "%s float LUCENT_T_RANGE_MM = %#.9g;\n", hlsl ? "static const" : "const", b->transmit_range);
    if (hlsl)
        fprintf(f, "static const float3 LUCENT_T[%d] = {\n", n);
    else
        fprintf(f, "const vec3 LUCENT_T[%d] = vec3[%d](\n", n, n);
    for (int j = 0; j < n; j++) {
        const float *v = b->transmittance + 3 * j;
        fprintf(f, "    %s(%#.7g, %#.7g, %#.7g)%s\n", vec3, v[0], v[1], v[2], j + 1 < n ? "," : "");
    }
    fputs(hlsl ? "};\n\n" : ");\n\n", f);
    fprintf(f,
            "%s lucent_transmittance(float s_mm)\n"
            "{\n"
            "    float x = clamp(s_mm / LUCENT_T_RANGE_MM, 0.0, 1.0) * %d.0;\n"
            "    int j = min(int(x), %d);\n"
            "    return %s(LUCENT_T[j], LUCENT_T[j + 1], x - float(j));\n"
            "}\n",
            vec3, n - 1, n - 2, hlsl ? "lerp" : "mix");
}
