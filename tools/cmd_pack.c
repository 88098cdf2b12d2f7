/* `lucent pack`: everything an engine needs for one material, in one folder (issue 16 item 3): the
 * separable kernel's taps and a complete blur pass, the translucency table T(s), the CDRF's RGB
 * look-up table with sigma0 and k_d and a shading snippet, the constants as JSON, and a glTF
 * material with KHR_materials_volume. The parts come from the bake room (lucent/bake.h), with the
 * renderer's settings, so that a pack reproduces what `lucent render` draws. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/bake.h"
#include "lucent/cdrf.h"
#include "lucent/kernel.h"

static const char k_usage[] =
    "usage: lucent pack MATERIAL --engine glsl|hlsl|json [options]\n"
    "\n"
    "Writes into one folder (--out, default MATERIAL-ENGINE) what an engine needs to render\n"
    "MATERIAL as `lucent render` does, and prints the kernel's width in pixels on the screen:\n"
    "  taps.glsl|.hlsl|.json   the separable kernel's taps (offsets in mm; lucent kernel's export)\n"
    "  blur.frag.glsl|blur.hlsl  a complete 1-D blur pass: kernel width from depth and field of\n"
    "                          view, Jimenez's follow-surface depth test (glsl and hlsl engines)\n"
    "  cdrf.glsl|cdrf.hlsl     the CDRF shading snippet reading the LUT (glsl and hlsl engines)\n"
    "  translucency.glsl|.hlsl T(s) as a constant table and its lookup (glsl and hlsl engines)\n"
    "  cdrf-lut.exr            RGB float: columns cos theta in [-1, 1], rows curvature in\n"
    "                          [0, kappa_max] 1/mm from the top row; channel c is the CDRF of\n"
    "                          sigma = sigma0_c kappa (Kubo Eq. 1-4)\n"
    "  transmittance.csv       T(s) per channel, s in mm\n"
    "  constants.json          every number above, the material and the screen\n"
    "  material.gltf           a glTF 2.0 material with KHR_materials_volume and KHR_materials_ior\n"
    "MATERIAL is a preset name (see 'lucent materials'), FILE.json or FILE.json#NAME.\n"
    "\n"
    "options:\n"
    "  --engine E          glsl, hlsl or json (data only)\n"
    "  --screen WxH        the screen in pixels (default 1920x1080)\n"
    "  --fov DEG           vertical field of view in degrees (default 45)\n"
    "  --object-height H   the object's height (default 1.8m; m, cm or mm, bare: m); the printed\n"
    "                      width is for the object filling the screen's height\n"
    "  --distance D        instead: the object's depth from the camera (m, cm or mm, bare: m)\n"
    "  --set KEY=VALUE     a render setting (docs/scenes.md): kernel, taps, profile,\n"
    "                      transmittance, cdrf_variant, ... (default: the renderer's)\n"
    "  --kappa-max K       the LUT's largest curvature, 1/mm (default 1: a sphere of 1 mm)\n"
    "  --lut-size WxH      the LUT's size (default 64x64)\n"
    "  --sigma0-photons N  photons per channel and sphere of the sigma0 fit (default 40000)\n"
    "  --transmit-photons N  photons per channel and thickness of T(s) (default 20000)\n"
    "  --out DIR           the folder (created; default MATERIAL-ENGINE)\n"
    "  --cache DIR         where sigma0 fits and slab tables are kept (as lucent render)\n"
    "  --no-cache          do not read or write that cache\n"
    "\n"
    "example:\n"
    "  lucent pack marble --engine glsl --screen 1920x1080 --fov 45 --object-height 0.3m --out out/marble-pack\n";

enum { MAX_SETS = 32 };
enum { ENGINE_GLSL, ENGINE_HLSL, ENGINE_JSON };

typedef struct options {
    const char *spec, *out, *cache;
    const char *sets[MAX_SETS];
    int set_count, engine, lut_w, lut_h;
    cli_view view;
    double kappa_max;
    int sigma0_photons, transmit_photons; /* 0: the bake's defaults (the renderer's) */
    bool no_cache, have_engine;
} options;

static int usage(const char *fmt, const char *v) { return cli_usage_error("pack", fmt, v ? v : ""); }

static int parse_valued(options *o, const char *name, const char *v)
{
    if (!v) return usage("%s needs a value", name);
    if (!strcmp(name, "--engine")) {
        o->have_engine = true;
        o->engine = !strcmp(v, "glsl")   ? ENGINE_GLSL
                    : !strcmp(v, "hlsl") ? ENGINE_HLSL
                    : !strcmp(v, "json") ? ENGINE_JSON
                                         : -1;
        return o->engine >= 0 ? CLI_OK : usage("unknown engine '%s' (glsl, hlsl, json)", v);
    }
    if (!strcmp(name, "--lut-size"))
        return cli_parse_size(v, &o->lut_w, &o->lut_h) && o->lut_w >= 2 && o->lut_h >= 2 && o->lut_w <= 4096 &&
                       o->lut_h <= 4096
                   ? CLI_OK
                   : usage("--lut-size needs WxH, 2..4096 each, got '%s'", v);
    if (!strcmp(name, "--kappa-max"))
        return cli_parse_double(v, &o->kappa_max) && o->kappa_max > 0
                   ? CLI_OK
                   : usage("--kappa-max needs a number > 0 (1/mm), got '%s'", v);
    if (!strcmp(name, "--sigma0-photons") || !strcmp(name, "--transmit-photons"))
        return cli_parse_int(v, name[2] == 's' ? &o->sigma0_photons : &o->transmit_photons) &&
                       (name[2] == 's' ? o->sigma0_photons : o->transmit_photons) > 0
                   ? CLI_OK
                   : usage("%s needs a whole number > 0", name);
    if (!strcmp(name, "--set")) {
        if (o->set_count == MAX_SETS) return usage("at most 32 --set%s", "");
        o->sets[o->set_count++] = v;
        return CLI_OK;
    }
    if (!strcmp(name, "--cache")) return (o->cache = v), CLI_OK;
    return (o->out = v), CLI_OK; /* --out */
}

static int parse_args(int argc, char **argv, options *o)
{
    static const char *const valued[] = {
        "--engine", "--lut-size", "--set", "--cache", "--out", "--kappa-max", "--sigma0-photons", "--transmit-photons"};
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int matched = -1;
        for (int n = 0; n < (int)(sizeof valued / sizeof valued[0]) && matched < 0; n++)
            if (cli_option(argc, argv, &i, valued[n], &v)) matched = n;
        int view = matched < 0 ? cli_view_option("pack", argc, argv, &i, &o->view) : -1;
        if (view == CLI_USAGE) return CLI_USAGE;
        if (view == CLI_OK) continue;
        if (matched >= 0) {
            int rc = parse_valued(o, valued[matched], v);
            if (rc != CLI_OK) return rc;
        } else if (!strcmp(argv[i], "--no-cache")) {
            o->no_cache = true;
        } else if (argv[i][0] == '-') {
            return usage("unknown option '%s'", argv[i]);
        } else if (o->spec) {
            return usage("expected one material, got '%s' too", argv[i]);
        } else {
            o->spec = argv[i];
        }
    }
    if (!o->spec) return usage("expected a material%s", "");
    if (!o->have_engine) return usage("--engine is required (glsl, hlsl or json)%s", "");
    return CLI_OK;
}

/* ---- text assembly ---- */

typedef struct text {
    char *data;
    size_t size;
    FILE *f;
} text;

static bool text_open(text *t) { return (t->f = open_memstream(&t->data, &t->size)) != NULL; }

static lucent_status text_write(text *t, const char *dir, const char *name, int *written)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    lucent_status s = fclose(t->f) == 0 ? lucent_write_file(path, t->data, t->size)
                                        : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    free(t->data);
    t->data = NULL, t->f = NULL;
    if (s == LUCENT_OK) ++*written;
    return s;
}

static void triple(FILE *f, const char *type, const double v[3])
{
    fprintf(f, "%s(%#.9g, %#.9g, %#.9g)", type, v[0], v[1], v[2]);
}

static void json_triple(FILE *f, const char *key, const double v[3], bool comma)
{
    fprintf(f, "  \"%s\": [%.9g, %.9g, %.9g]%s\n", key, v[0], v[1], v[2], comma ? "," : "");
}

/* The camera quantities of the printed width. */
typedef struct screen {
    double radius_mm;    /* the kernel's half-width */
    double depth_mm;     /* where the width is measured */
    double px_per_mm;    /* at that depth */
    double width_px;     /* 2 radius px_per_mm */
    double scale_at_1mm; /* pixels per mm at depth 1 mm: what the blur divides by the depth */
    int height;          /* pixels */
    double fov;          /* degrees */
} screen;

/* ---- the blur pass ---- */

static void blur_glsl(FILE *f, const char *taps, const lucent_material *m, const screen *sc)
{
    fprintf(f,
            "#version 450 core\n"
            "// Lucent engine pack, %s: one 1-D pass of the separable subsurface-scattering blur (Jimenez et\n"
            "// al., Freude 2014 Algorithm 4.1). Per kernel pass p (LUCENT_SSS_RANK of them): run it with\n"
            "// u_axis = (1, 0), u_vertical = 0 from the diffuse irradiance into a temporary, then with\n"
            "// u_axis = (0, 1), u_vertical = 1 from the temporary; add the passes' results.\n"
            "// Kernel width: a tap at offset o (mm) lands o * u_pixels_per_mm_at_1mm / z pixels away at linear\n"
            "// depth z (mm), u_pixels_per_mm_at_1mm = height / (2 tan(fov_y / 2)) (pinhole camera, square\n"
            "// pixels). Follow-surface (Jimenez, Freude Eq. 4.12): a tap whose depth differs from the centre's\n"
            "// by dz falls back towards the centre by min(|dz| / R, 1), R = the kernel's half-width.\n\n",
            m->name);
    fputs(taps, f);
    fprintf(f,
            "\nconst float LUCENT_SSS_RADIUS_MM = %#.9g; // the kernel's half-width, the depth test's range\n\n"
            "layout(binding = 0) uniform sampler2D u_irradiance; // rgb: diffuse irradiance (or the first pass)\n"
            "layout(binding = 1) uniform sampler2D u_depth;      // r: linear view depth in scene units; 0: none\n"
            "uniform vec2 u_axis = vec2(1.0, 0.0);\n"
            "uniform int u_pass = 0;     // kernel pass, 0 .. LUCENT_SSS_RANK - 1\n"
            "uniform int u_vertical = 0; // 1 on the second (vertical) pass: applies the pass's sign\n"
            "uniform float u_mm_per_unit = 1000.0; // scene units to mm (1000: metres)\n"
            "uniform float u_pixels_per_mm_at_1mm = %#.9g; // %d px high, fov_y %.6g degrees\n"
            "uniform float u_width_scale = 1.0;   // an artist's multiplier (ssss.width_scale)\n\n"
            "layout(location = 0) out vec4 o_color;\n\n"
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
            sc->radius_mm, sc->scale_at_1mm, sc->height, sc->fov);
}

static void blur_hlsl(FILE *f, const char *taps, const lucent_material *m, const screen *sc)
{
    fprintf(f,
            "// Lucent engine pack, %s: one 1-D pass of the separable subsurface-scattering blur (Jimenez et\n"
            "// al., Freude 2014 Algorithm 4.1), as a pixel shader (entry point main, ps_5_0). Per kernel pass p:\n"
            "// run it with axis = (1, 0), vertical = 0 from the diffuse irradiance into a temporary, then\n"
            "// axis = (0, 1), vertical = 1 from the temporary; add the passes' results. A tap at offset o (mm)\n"
            "// lands o * pixels_per_mm_at_1mm / z pixels away at linear depth z (mm); follow-surface: a tap whose\n"
            "// depth differs by dz falls back towards the centre by min(|dz| / R, 1) (Freude Eq. 4.12).\n\n",
            m->name);
    fputs(taps, f);
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
            "    float pixels_per_mm_at_1mm;    // height / (2 tan(fov_y / 2)); %.9g for the pack's screen\n"
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
            sc->radius_mm, sc->scale_at_1mm);
}

/* ---- the CDRF snippet and LUT ---- */

static void cdrf_snippet(FILE *f, bool hlsl, const lucent_material *m, const lucent_baked *b, const options *o,
                         lucent_cdrf_variant v)
{
    const char *vec3 = hlsl ? "float3" : "vec3", *konst = hlsl ? "static const" : "const";
    fprintf(f,
            "// Lucent engine pack, %s: the curvature-dependent reflectance (Kubo, Dobashi & Morishima, %s\n"
            "// variant) in place of Lambert's max(dot(n, l), 0). Per channel c the reflected radiance is\n"
            "//   L_c = k_d,c * CDRF(theta; sigma = sigma0_c * kappa) * E_c\n"
            "// with E the light's irradiance (on a plane facing it), theta the angle between the normal and the\n"
            "// light, kappa the mean curvature (1/mm, > 0 convex). sigma0 and k_d are fitted to Monte Carlo spheres\n"
            "// of the material (lucent cdrf-fit). The LUT cdrf-lut.exr (%d x %d, RGB float) is read with linear\n"
            "// filtering: column i holds cos theta = -1 + 2 i / (width - 1) (left: light behind); row j,\n"
            "// counted from the TOP row of the EXR, holds kappa = kappa_max j / (height - 1). Upload the rows\n"
            "// in file order (top row first) so that t = 0 is kappa = 0; samples sit on the texel centres.\n\n",
            m->name, lucent_cdrf_variant_name(v), o->lut_w, o->lut_h);
    fprintf(f, "%s %s LUCENT_CDRF_SIGMA0_MM = ", konst, vec3);
    triple(f, vec3, b->sigma0);
    fprintf(f, ";\n%s %s LUCENT_CDRF_KD = ", konst, vec3);
    triple(f, vec3, b->kd);
    fprintf(f, ";\n%s float LUCENT_CDRF_KAPPA_MAX = %.9g; // 1/mm\n\n", konst, o->kappa_max);
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

static lucent_status cdrf_lut(const options *o, const lucent_baked *b, lucent_cdrf_variant v, lucent_image **dest)
{
    lucent_status s = lucent_image_create(o->lut_w, o->lut_h, 3, dest);
    for (int j = 0; s == LUCENT_OK && j < o->lut_h; j++) {
        double kappa = o->kappa_max * j / (o->lut_h - 1);
        for (int i = 0; i < o->lut_w; i++) {
            double theta = acos(fmin(fmax(-1 + 2.0 * i / (o->lut_w - 1), -1), 1));
            for (int c = 0; c < 3; c++)
                lucent_image_set(*dest, i, j, c,
                                 (float)lucent_cdrf_eval(v, theta, lucent_cdrf_sigma(b->sigma0[c], kappa)));
        }
    }
    return s;
}

/* ---- translucency ---- */

static void translucency_snippet(FILE *f, bool hlsl, const lucent_material *m, const lucent_baked *b,
                                 const lucent_render_settings *rs)
{
    const char *vec3 = hlsl ? "float3" : "vec3";
    int n = LUCENT_BAKE_TRANSMIT_SIZE;
    fprintf(f,
            "// Lucent engine pack, %s: the light through a thickness s (mm), T(s) per channel (%s model),\n"
            "// tabulated at s = %.9g j / %d mm, j = 0 .. %d (the last entry 0). Jimenez et al. 2010's translucency\n"
            "// multiplies the light reaching the back by T(thickness from the shadow map)%s.\n\n",
            m->name, lucent_transmittance_name(rs->translucency.transmittance), b->transmit_range, n - 1, n - 1,
            rs->translucency.transmittance == LUCENT_TRANSMIT_SLAB ? "" : " and the albedo");
    fprintf(f, "%s float LUCENT_T_RANGE_MM = %#.9g;\n", hlsl ? "static const" : "const", b->transmit_range);
    if (hlsl)
        fprintf(f, "static const float3 LUCENT_T[%d] = {\n", n);
    else
        fprintf(f, "const vec3 LUCENT_T[%d] = vec3[%d](\n", n, n);
    for (int j = 0; j < n; j++) {
        const float *t = b->transmittance + 3 * j;
        fprintf(f, "    %s(%.7g, %.7g, %.7g)%s\n", vec3, t[0], t[1], t[2], j + 1 < n ? "," : "");
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

/* ---- constants and glTF ---- */

static void constants_json(FILE *f, const options *o, const lucent_material *m, const lucent_material_derived *d,
                           const lucent_baked *b, const lucent_render_settings *rs, const screen *sc)
{
    static const char *const engines[] = {"glsl", "hlsl", "json"};
    const lucent_taps *t = b->taps;
    fprintf(f, "{\n  \"lucent\": \"%s\",\n  \"material\": \"%s\",\n  \"engine\": \"%s\",\n", LUCENT_VERSION_STRING,
            m->name, engines[o->engine]);
    json_triple(f, "sigma_a_per_mm", m->sigma_a, true);
    json_triple(f, "sigma_s_per_mm", m->sigma_s, true);
    json_triple(f, "sigma_t_per_mm", d->sigma_t, true);
    json_triple(f, "albedo", d->albedo, true);
    json_triple(f, "g", m->g, true);
    fprintf(f, "  \"eta\": %.9g,\n", m->eta);
    json_triple(f, "diffuse_rd", d->rd, true);
    fprintf(
        f, "  \"kernel\": {\"model\": \"%s\", \"rank\": %d, \"taps\": %d, \"profile\": \"%s\", \"radius_mm\": %.9g},\n",
        lucent_kernel_model_name((lucent_kernel_model)rs->ssss.kernel), t->rank, t->count, rs->ssss.profile,
        sc->radius_mm);
    fprintf(f,
            "  \"screen\": {\"width_px\": %d, \"height_px\": %d, \"fov_y_deg\": %.9g, \"depth_mm\": %.9g, "
            "\"pixels_per_mm_at_1mm\": %.9g, \"pixels_per_mm\": %.9g, \"kernel_width_px\": %.9g},\n",
            o->view.width, o->view.height, o->view.fov, sc->depth_mm, sc->scale_at_1mm, sc->px_per_mm, sc->width_px);
    fprintf(f,
            "  \"cdrf\": {\"variant\": \"%s\", \"sigma0_mm\": [%.9g, %.9g, %.9g], \"kd\": [%.9g, %.9g, %.9g], "
            "\"lut\": \"cdrf-lut.exr\", \"lut_width\": %d, \"lut_height\": %d, \"kappa_max_per_mm\": %.9g, "
            "\"columns\": \"cos theta from -1 to 1\", \"rows\": \"kappa from 0 (top row) to kappa_max\"},\n",
            lucent_cdrf_variant_name((lucent_cdrf_variant)rs->cdrf.variant), b->sigma0[0], b->sigma0[1], b->sigma0[2],
            b->kd[0], b->kd[1], b->kd[2], o->lut_w, o->lut_h, o->kappa_max);
    fprintf(f,
            "  \"translucency\": {\"model\": \"%s\", \"range_mm\": %.9g, \"samples\": %d, \"table\": "
            "\"transmittance.csv\"}\n}\n",
            lucent_transmittance_name(rs->translucency.transmittance), b->transmit_range, LUCENT_BAKE_TRANSMIT_SIZE);
}

/* KHR_materials_volume: light through a distance x is attenuationColor^(x / attenuationDistance)
 * (Beer-Lambert, x in metres). With extinction sigma_t: colour_c = exp(-sigma_t,c d) for the
 * distance d = 1 / min(sigma_t) (the longest mean free path), so that colour_c^(x/d) = exp(-sigma_t,c x). */
static void gltf(FILE *f, const lucent_material *m, const lucent_material_derived *d, double thickness_mm)
{
    double smin = fmin(d->sigma_t[0], fmin(d->sigma_t[1], d->sigma_t[2])), dist_mm = 1 / smin, col[3];
    for (int c = 0; c < 3; c++) col[c] = exp(-d->sigma_t[c] * dist_mm);
    fprintf(f,
            "{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"lucent pack %s\"},\n"
            "  \"extensionsUsed\": [\"KHR_materials_volume\", \"KHR_materials_ior\"],\n"
            "  \"materials\": [{\n    \"name\": \"%s\",\n"
            "    \"pbrMetallicRoughness\": {\"baseColorFactor\": [%.6g, %.6g, %.6g, 1.0], \"metallicFactor\": 0.0, "
            "\"roughnessFactor\": 0.5},\n"
            "    \"extensions\": {\n"
            "      \"KHR_materials_ior\": {\"ior\": %.6g},\n"
            "      \"KHR_materials_volume\": {\"thicknessFactor\": %.6g, \"attenuationDistance\": %.9g, "
            "\"attenuationColor\": [%.9g, %.9g, %.9g]}\n"
            "    },\n"
            "    \"extras\": {\"lucent\": {\"sigma_t_per_mm\": [%.9g, %.9g, %.9g], \"albedo\": [%.9g, %.9g, %.9g], "
            "\"baseColor\": \"the dipole's total diffuse reflectance Rd\", \"units\": \"metres\"}}\n"
            "  }]\n}\n",
            LUCENT_VERSION_STRING, m->name, d->rd[0], d->rd[1], d->rd[2], m->eta, thickness_mm / 1000, dist_mm / 1000,
            col[0], col[1], col[2], d->sigma_t[0], d->sigma_t[1], d->sigma_t[2], d->albedo[0], d->albedo[1],
            d->albedo[2]);
}

/* ---- the command ---- */

static lucent_status apply_sets(const options *o, lucent_render_settings *rs)
{
    for (int i = 0; i < o->set_count; i++) {
        char key[128];
        const char *eq = strchr(o->sets[i], '=');
        size_t n = eq ? (size_t)(eq - o->sets[i]) : 0;
        if (!eq || n == 0 || n >= sizeof key)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--set '%s': expected KEY=VALUE", o->sets[i]);
        memcpy(key, o->sets[i], n);
        key[n] = '\0';
        const lucent_setting *st = lucent_setting_find(key, NULL);
        if (!st)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--set: no render setting '%s' (docs/scenes.md)", key);
        lucent_status s = lucent_setting_set(rs, st, eq + 1);
        if (s != LUCENT_OK) return s;
    }
    return lucent_render_settings_check(rs);
}

static lucent_status write_pack(const options *o, const char *dir, const lucent_material *m, const lucent_baked *b,
                                const lucent_render_settings *rs, const screen *sc, int *written)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    lucent_cdrf_variant v = (lucent_cdrf_variant)rs->cdrf.variant;
    static const lucent_kernel_format formats[] = {LUCENT_KERNEL_GLSL, LUCENT_KERNEL_HLSL, LUCENT_KERNEL_JSON};
    static const char *const tap_names[] = {"taps.glsl", "taps.hlsl", "taps.json"};
    char label[160], *taps = NULL;
    snprintf(label, sizeof label, "%s, %s rank %d", m->name,
             lucent_kernel_model_name((lucent_kernel_model)rs->ssss.kernel), b->taps->rank);
    lucent_status s = lucent_taps_export(b->taps, formats[o->engine], label, &taps);
    if (s == LUCENT_OK) s = lucent_mkdir_p(dir);
    text t = {0};
    if (s == LUCENT_OK) s = text_open(&t) ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) fputs(taps, t.f), s = text_write(&t, dir, tap_names[o->engine], written);
    bool shader = o->engine != ENGINE_JSON, hlsl = o->engine == ENGINE_HLSL;
    if (s == LUCENT_OK && shader && text_open(&t)) {
        (hlsl ? blur_hlsl : blur_glsl)(t.f, taps, m, sc);
        s = text_write(&t, dir, hlsl ? "blur.hlsl" : "blur.frag.glsl", written);
    }
    if (s == LUCENT_OK && shader && text_open(&t)) {
        cdrf_snippet(t.f, hlsl, m, b, o, v);
        s = text_write(&t, dir, hlsl ? "cdrf.hlsl" : "cdrf.glsl", written);
    }
    if (s == LUCENT_OK && shader && text_open(&t)) {
        translucency_snippet(t.f, hlsl, m, b, rs);
        s = text_write(&t, dir, hlsl ? "translucency.hlsl" : "translucency.glsl", written);
    }
    if (s == LUCENT_OK && text_open(&t)) {
        fprintf(t.f, "s_mm,t_r,t_g,t_b\n");
        for (int j = 0; j < LUCENT_BAKE_TRANSMIT_SIZE; j++)
            fprintf(t.f, "%.9g,%.9g,%.9g,%.9g\n", b->transmit_range * j / (LUCENT_BAKE_TRANSMIT_SIZE - 1),
                    b->transmittance[3 * j], b->transmittance[3 * j + 1], b->transmittance[3 * j + 2]);
        s = text_write(&t, dir, "transmittance.csv", written);
    }
    if (s == LUCENT_OK && text_open(&t)) {
        constants_json(t.f, o, m, &d, b, rs, sc);
        s = text_write(&t, dir, "constants.json", written);
    }
    if (s == LUCENT_OK && text_open(&t)) {
        gltf(t.f, m, &d, o->view.object_height_mm);
        s = text_write(&t, dir, "material.gltf", written);
    }
    lucent_image *lut = NULL;
    if (s == LUCENT_OK) s = cdrf_lut(o, b, v, &lut);
    if (s == LUCENT_OK) {
        char path[4200];
        snprintf(path, sizeof path, "%s/cdrf-lut.exr", dir);
        s = lucent_image_write(path, lut, NULL);
        if (s == LUCENT_OK) ++*written;
    }
    lucent_image_destroy(lut);
    free(taps);
    return s;
}

static lucent_status run(const options *o)
{
    lucent_material m;
    lucent_render_settings rs = lucent_render_settings_defaults();
    lucent_status s = lucent_material_resolve(o->spec, &m);
    if (s == LUCENT_OK) s = lucent_skin_resolve(&m); /* a skin: its equivalent medium (docs/skin.md) */
    char dir[4096];
    if (o->out || s != LUCENT_OK)
        snprintf(dir, sizeof dir, "%s", o->out ? o->out : "");
    else
        snprintf(dir, sizeof dir, "%s-%s", m.name,
                 o->engine == ENGINE_GLSL   ? "glsl"
                 : o->engine == ENGINE_HLSL ? "hlsl"
                                            : "json");
    if (s == LUCENT_OK) s = lucent_output_check_folder(dir); /* before the bake */
    if (s == LUCENT_OK) s = apply_sets(o, &rs);
    lucent_cache *cache = NULL;
    char buf[4096];
    const char *cdir = cli_cache_dir(o->cache, o->no_cache, buf, sizeof buf);
    if (s == LUCENT_OK && cdir) s = lucent_cache_create(cdir, &cache);
    lucent_baked b = {0};
    lucent_bake_desc bd = {.what = LUCENT_BAKE_TAPS | LUCENT_BAKE_TRANSMITTANCE | LUCENT_BAKE_SIGMA0,
                           .settings = &rs,
                           .sigma0_photons = (uint64_t)o->sigma0_photons,
                           .transmit_photons = (uint64_t)o->transmit_photons,
                           .pool = cli_pool()};
    if (s == LUCENT_OK) s = lucent_material_bake(&m, &bd, cache, &b);
    if (s == LUCENT_OK) {
        const cli_view *w = &o->view;
        screen sc = {.radius_mm = lucent_taps_radius(b.taps), .height = w->height, .fov = w->fov};
        sc.scale_at_1mm = lucent_screen_pixels_per_mm(w->height, w->fov, 1);
        sc.depth_mm = cli_view_depth_mm(w);
        sc.px_per_mm = lucent_screen_pixels_per_mm(w->height, w->fov, sc.depth_mm);
        sc.width_px = 2 * sc.radius_mm * sc.px_per_mm;
        int written = 0;
        s = write_pack(o, dir, &m, &b, &rs, &sc, &written);
        if (s == LUCENT_OK) {
            cli_print_kernel_width(stdout, sc.radius_mm, &o->view);
            cli_wrote("wrote %s/ (%d files)", dir, written);
        }
    }
    lucent_baked_free(&b);
    lucent_cache_destroy(cache);
    return s;
}

int cmd_pack(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.engine = -1, .view = cli_view_defaults(), .kappa_max = 1, .lut_w = 64, .lut_h = 64};
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    return run(&o) == LUCENT_OK ? CLI_OK : cli_fail();
}
