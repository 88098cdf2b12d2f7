/* False-colour heat maps of error images, for reports. */
#include <math.h>
#include <stdio.h>

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

lucent_status lucent_image_heatmap_scale(const lucent_image *values, float scale, float *dest)
{
    *dest = 1.0f;
    if (values->channels != 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "heat map of a %d-channel image (expected 1)",
                            values->channels);
    lucent_status s = LUCENT_OK;
    if (!(scale > 0.0f) || !isfinite(scale)) s = lucent_image_percentile(values, 0, 99.0, &scale);
    *dest = scale > 0.0f && isfinite(scale) ? scale : 1.0f;
    return s;
}

lucent_status lucent_image_heatmap(const lucent_image *values, float scale, lucent_image **dest)
{
    *dest = NULL;
    lucent_status s = lucent_image_heatmap_scale(values, scale, &scale);
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

/* Height of the colour bar's strip under the map: a gap, the 12-pixel bar, a gap, the numbers, a gap,
 * the label. */
enum { BAR_STRIP = 6 + 12 + 4 + 8 + 3 + 8 + 4, BAR_MIN_WIDTH = 200 };

lucent_status lucent_image_heatmap_with_bar(const lucent_image *values, float scale, const char *label,
                                            lucent_image **dest, float *used)
{
    *dest = NULL;
    lucent_image *map = NULL;
    lucent_status s = lucent_image_heatmap_scale(values, scale, &scale);
    if (used) *used = scale;
    if (s == LUCENT_OK) s = lucent_image_heatmap(values, scale, &map);
    int w = values->width > BAR_MIN_WIDTH ? values->width : BAR_MIN_WIDTH, h = values->height + BAR_STRIP;
    if (s == LUCENT_OK) s = lucent_image_create(w, h, 3, dest);
    if (s != LUCENT_OK) {
        lucent_image_destroy(map);
        return s;
    }
    for (int y = 0; y < values->height; y++)
        for (int x = 0; x < values->width; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(*dest, x, y, c, lucent_image_get(map, x, y, c));
    lucent_image_destroy(map);
    int x0 = 8, x1 = w - 8, top = values->height + 6; /* the ramp from 0 at x0 to the scale at x1 - 1 */
    for (int x = x0; x < x1; x++) {
        float rgb[3];
        ramp((float)(x - x0) / (float)(x1 - 1 - x0), rgb);
        for (int y = top; y < top + 12; y++)
            for (int c = 0; c < 3; c++) lucent_image_set(*dest, x, y, c, rgb[c]);
    }
    static const float white[3] = {1, 1, 1};
    char lo[8] = "0", mid[32], hi[32];
    snprintf(mid, sizeof mid, "%.3g", 0.5 * scale);
    snprintf(hi, sizeof hi, "%.3g", (double)scale);
    int ty = top + 16;
    lucent_image_draw_text(*dest, x0, ty, 1, white, lo);
    lucent_image_draw_text(*dest, (x0 + x1) / 2 - lucent_image_text_width(mid, 1) / 2, ty, 1, white, mid);
    lucent_image_draw_text(*dest, x1 - lucent_image_text_width(hi, 1), ty, 1, white, hi);
    if (label)
        lucent_image_draw_text(*dest, (x0 + x1) / 2 - lucent_image_text_width(label, 1) / 2, ty + 11, 1, white, label);
    return LUCENT_OK;
}
