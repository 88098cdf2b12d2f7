/* The sRGB transfer curve and the tonemapping operators. */
#include <math.h>
#include <string.h>

#include "image/internal.h"

/* IEC 61966-2-1:1999, section 5.2 (encoding) and 5.3 (decoding). The breakpoints 0.0031308 and
 * 0.04045 make the two pieces meet (to within 1e-7) at both ends. */
float lucent_srgb_encode(float linear)
{
    if (!(linear > 0.0f)) return 0.0f;
    if (linear <= 0.0031308f) return 12.92f * linear;
    return (float)(1.055 * pow((double)linear, 1.0 / 2.4) - 0.055);
}

float lucent_srgb_decode(float encoded)
{
    if (!(encoded > 0.0f)) return 0.0f;
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return (float)pow((encoded + 0.055) / 1.055, 2.4);
}

static const char *const k_tonemap_names[] = {"none", "clamp", "reinhard", "filmic"};

const char *lucent_tonemap_op_name(lucent_tonemap_op op) { return op >= 0 && op < 4 ? k_tonemap_names[op] : "unknown"; }

lucent_status lucent_tonemap_op_parse(const char *name, lucent_tonemap_op *dest)
{
    for (int i = 0; i < 4; i++) {
        if (name && strcmp(name, k_tonemap_names[i]) == 0) {
            *dest = (lucent_tonemap_op)i;
            return LUCENT_OK;
        }
    }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown tonemap '%s' (none, clamp, reinhard, filmic)",
                        name ? name : "");
}

static float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */ }

float lucent_tonemap_value(lucent_tonemap_op op, float x)
{
    switch (op) {
    case LUCENT_TONEMAP_CLAMP: return clamp01(x);
    case LUCENT_TONEMAP_REINHARD: /* Reinhard, Stark, Shirley, Ferwerda 2002, eq. 3: L / (1 + L) */
        if (!(x > 0.0f)) return 0.0f;
        return isinf(x) ? 1.0f : x / (1.0f + x);
    case LUCENT_TONEMAP_FILMIC: { /* Narkowicz 2015, "ACES Filmic Tone Mapping Curve" */
        if (!(x > 0.0f)) return 0.0f;
        if (isinf(x)) return 1.0f;
        double d = x;
        return clamp01((float)((d * (2.51 * d + 0.03)) / (d * (2.43 * d + 0.59) + 0.14)));
    }
    default: return x;
    }
}

void lucent_image_tonemap(lucent_image *img, const lucent_tonemap_desc *desc)
{
    lucent_tonemap_desc d = desc ? *desc : (lucent_tonemap_desc){0};
    float scale = exp2f(d.exposure);
    int colour = img->channels == 4 ? 3 : img->channels;
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++) {
        float *p = img->data + i * (size_t)img->channels;
        for (int c = 0; c < colour; c++) p[c] = lucent_tonemap_value(d.op, p[c] * scale);
    }
}
