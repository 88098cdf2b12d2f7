/* False-colour heat maps of error images, for reports. */
#include <math.h>

#include "image/internal.h"

/* The ramp's stops, in display (sRGB-encoded) values: black, purple, red, orange, yellow, white.
 * Our own choice: dark is small, bright is large, and it stays readable in greyscale print. */
static const float k_ramp[6][3] = {
    {0.00f, 0.00f, 0.00f}, {0.35f, 0.05f, 0.55f}, {0.80f, 0.10f, 0.25f},
    {1.00f, 0.50f, 0.00f}, {1.00f, 0.90f, 0.10f}, {1.00f, 1.00f, 1.00f},
};

/* Maps t in [0, 1] to linear RGB. */
static void ramp(float t, float *rgb)
{
    float x = t * 5.0f;
    int i = (int)x;
    if (i > 4) i = 4;
    float f = x - (float)i;
    for (int c = 0; c < 3; c++) rgb[c] = lucent_srgb_decode(k_ramp[i][c] + f * (k_ramp[i + 1][c] - k_ramp[i][c]));
}

lucent_status lucent_image_heatmap(const lucent_image *values, float scale, lucent_image **dest)
{
    *dest = NULL;
    if (values->channels != 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "heat map of a %d-channel image (expected 1)",
                            values->channels);
    lucent_status s = LUCENT_OK;
    if (!(scale > 0.0f)) s = lucent_image_percentile(values, 0, 99.0, &scale);
    if (!(scale > 0.0f)) scale = 1.0f;
    if (s == LUCENT_OK) s = lucent_image_create(values->width, values->height, 3, dest);
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)values->width * (size_t)values->height;
    for (size_t i = 0; i < n; i++) {
        float t = values->data[i] / scale;
        if (isnan(t)) t = 1.0f; /* NaN errors are the worst ones: show them brightest */
        ramp(t > 0.0f ? (t < 1.0f ? t : 1.0f) : 0.0f, (*dest)->data + 3 * i);
    }
    return LUCENT_OK;
}
