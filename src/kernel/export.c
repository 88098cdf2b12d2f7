/* Export of taps: GLSL and HLSL (declarations plus a one-pass blur function), a C header, JSON.
 * Every tap is (r, g, b weights, offset in mm), as Jimenez's shader stores its kernel. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/strbuf.h"
#include "kernel/internal.h"

static const char *const k_format_names[LUCENT_KERNEL_FORMAT_COUNT] = {"glsl", "hlsl", "c", "json"};

lucent_status lucent_kernel_format_parse(const char *name, lucent_kernel_format *dest)
{
    for (int f = 0; name && f < LUCENT_KERNEL_FORMAT_COUNT; f++)
        if (strcasecmp(name, k_format_names[f]) == 0) {
            *dest = (lucent_kernel_format)f;
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown export format '%s' (glsl, hlsl, c, json)",
                        name ? name : "");
}

/* A label safe inside comments and JSON strings. */
static void safe_label(const char *label, char *dest, size_t size)
{
    size_t i = 0;
    for (; label && label[i] && i + 1 < size; i++) {
        char ch = label[i];
        dest[i] = (ch < 32 || ch > 126 || strchr("*/\\\"", ch)) ? '_' : ch;
    }
    dest[i] = '\0';
}

static void header_comment(lucent_strbuf *b, const lucent_taps *t, const char *label, const char *lead)
{
    lucent_strbuf_printf(b,
                         "%s Lucent separable subsurface-scattering kernel: %s\n"
                         "%s %d taps per pass, %d pass(es); each tap is (r, g, b weight, offset in mm).\n"
                         "%s Apply each pass horizontally, then vertically; the result is the sum over\n"
                         "%s passes of sign * pass. Scale offsets by pixels per mm on screen.\n",
                         lead, label, lead, t->count, t->rank, lead, lead);
}

/* Writes the taps as "TYPE(r, g, b, o)" items, separated by commas. */
static void tap_items(lucent_strbuf *b, const lucent_taps *t, const char *type, const char *open, const char *close)
{
    for (int p = 0; p < t->rank; p++)
        for (int i = 0; i < t->count; i++) {
            int k = p * t->count + i;
            bool last = p == t->rank - 1 && i == t->count - 1;
            lucent_strbuf_printf(b, "    %s%s%.9g, %.9g, %.9g, %.9g%s%s\n", type, open, t->weight[0][k],
                                 t->weight[1][k], t->weight[2][k], t->offset[i], close, last ? "" : ",");
        }
}

static void sign_items(lucent_strbuf *b, const lucent_taps *t, const char *type, const char *open, const char *close)
{
    for (int p = 0; p < t->rank; p++)
        lucent_strbuf_printf(b, "%s%s%.1f, %.1f, %.1f%s%s", type, open, t->sign[0][p], t->sign[1][p], t->sign[2][p],
                             close, p == t->rank - 1 ? "" : ", ");
}

static void write_glsl(lucent_strbuf *b, const lucent_taps *t, const char *label)
{
    header_comment(b, t, label, "//");
    int n = t->count * t->rank;
    lucent_strbuf_printf(b,
                         "const int LUCENT_SSS_TAPS = %d;\nconst int LUCENT_SSS_RANK = %d;\n"
                         "const vec4 LUCENT_SSS_KERNEL[%d] = vec4[%d](\n",
                         t->count, t->rank, n, n);
    tap_items(b, t, "vec4", "(", ")");
    lucent_strbuf_printf(b, ");\nconst vec3 LUCENT_SSS_SIGN[%d] = vec3[%d](", t->rank, t->rank);
    sign_items(b, t, "vec3", "(", ")");
    lucent_strbuf_printf(b, ");\n\n// One 1-D pass of kernel pass `pass`; dir: texture-coordinate step per mm.\n"
                            "vec3 lucent_sss_pass(sampler2D tex, vec2 uv, vec2 dir, int pass)\n{\n"
                            "    vec3 sum = vec3(0.0);\n"
                            "    for (int i = 0; i < LUCENT_SSS_TAPS; i++) {\n"
                            "        vec4 k = LUCENT_SSS_KERNEL[pass * LUCENT_SSS_TAPS + i];\n"
                            "        sum += k.rgb * texture(tex, uv + k.a * dir).rgb;\n"
                            "    }\n    return sum;\n}\n");
}

static void write_hlsl(lucent_strbuf *b, const lucent_taps *t, const char *label)
{
    header_comment(b, t, label, "//");
    int n = t->count * t->rank;
    lucent_strbuf_printf(b,
                         "static const int LUCENT_SSS_TAPS = %d;\nstatic const int LUCENT_SSS_RANK = %d;\n"
                         "static const float4 LUCENT_SSS_KERNEL[%d] = {\n",
                         t->count, t->rank, n);
    tap_items(b, t, "float4", "(", ")");
    lucent_strbuf_printf(b, "};\nstatic const float3 LUCENT_SSS_SIGN[%d] = {", t->rank);
    sign_items(b, t, "float3", "(", ")");
    lucent_strbuf_printf(b,
                         "};\n\n// One 1-D pass of kernel pass `pass`; dir: texture-coordinate step per mm.\n"
                         "float3 lucent_sss_pass(Texture2D tex, SamplerState smp, float2 uv, float2 dir, int pass)\n{\n"
                         "    float3 sum = float3(0.0, 0.0, 0.0);\n"
                         "    for (int i = 0; i < LUCENT_SSS_TAPS; i++) {\n"
                         "        float4 k = LUCENT_SSS_KERNEL[pass * LUCENT_SSS_TAPS + i];\n"
                         "        sum += k.rgb * tex.SampleLevel(smp, uv + k.a * dir, 0).rgb;\n"
                         "    }\n    return sum;\n}\n");
}

static void write_c(lucent_strbuf *b, const lucent_taps *t, const char *label)
{
    lucent_strbuf_printf(b,
                         "/* Lucent separable subsurface-scattering kernel: %s\n"
                         " * %d taps per pass, %d pass(es); each tap is {r, g, b weight, offset in mm}.\n"
                         " * Apply each pass horizontally, then vertically; sum sign * pass. */\n",
                         label, t->count, t->rank);
    lucent_strbuf_printf(b,
                         "#define LUCENT_SSS_TAPS %d\n#define LUCENT_SSS_RANK %d\n"
                         "static const float lucent_sss_kernel[%d][4] = {\n",
                         t->count, t->rank, t->count * t->rank);
    tap_items(b, t, "", "{", "}");
    lucent_strbuf_printf(b, "};\nstatic const float lucent_sss_sign[%d][3] = {", t->rank);
    sign_items(b, t, "", "{", "}");
    lucent_strbuf_printf(b, "};\n");
}

static void write_json(lucent_strbuf *b, const lucent_taps *t, const char *label)
{
    lucent_strbuf_printf(b,
                         "{\n  \"format\": \"lucent-kernel-taps\",\n  \"version\": 1,\n"
                         "  \"label\": \"%s\",\n  \"units\": \"mm\",\n  \"taps\": %d,\n  \"rank\": %d,\n"
                         "  \"offsets\": [",
                         label, t->count, t->rank);
    for (int i = 0; i < t->count; i++) lucent_strbuf_printf(b, "%.17g%s", t->offset[i], i + 1 < t->count ? ", " : "]");
    lucent_strbuf_printf(b, ",\n  \"passes\": [");
    for (int p = 0; p < t->rank; p++) {
        lucent_strbuf_printf(b, "%s\n    {\"sign\": [%g, %g, %g], \"weights\": [", p ? "," : "", t->sign[0][p],
                             t->sign[1][p], t->sign[2][p]);
        for (int i = 0; i < t->count; i++) {
            int k = p * t->count + i;
            lucent_strbuf_printf(b, "%s[%.17g, %.17g, %.17g]", i ? ", " : "", t->weight[0][k], t->weight[1][k],
                                 t->weight[2][k]);
        }
        lucent_strbuf_printf(b, "]}");
    }
    lucent_strbuf_printf(b, "\n  ]\n}\n");
}

lucent_status lucent_taps_export(const lucent_taps *t, lucent_kernel_format format, const char *label, char **dest)
{
    *dest = NULL;
    char safe[256];
    safe_label(label ? label : "kernel", safe, sizeof safe);
    lucent_strbuf b = {0};
    switch (format) {
    case LUCENT_KERNEL_GLSL: write_glsl(&b, t, safe); break;
    case LUCENT_KERNEL_HLSL: write_hlsl(&b, t, safe); break;
    case LUCENT_KERNEL_C: write_c(&b, t, safe); break;
    case LUCENT_KERNEL_JSON: write_json(&b, t, safe); break;
    default: return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "taps export: unknown format %d", (int)format);
    }
    return lucent_strbuf_finish(&b, dest);
}
