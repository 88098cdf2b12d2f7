/* The float image: creation, copies, channel conversion and pixel access. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "image/internal.h"

lucent_status image_check_size(const char *what, int64_t width, int64_t height, int channels, lucent_status bad)
{
    if (channels != 1 && channels != 3 && channels != 4)
        return lucent_error(bad, "%s: %d channels (expected 1, 3 or 4)", what, channels);
    if (width < 1 || height < 1)
        return lucent_error(bad, "%s: empty image (%lldx%lld)", what, (long long)width, (long long)height);
    if (width > LUCENT_IMAGE_MAX_SIDE || height > LUCENT_IMAGE_MAX_SIDE ||
        (uint64_t)width * (uint64_t)height > LUCENT_IMAGE_MAX_PIXELS)
        return lucent_error(bad, "%s: image too large (%lldx%lld; the limit is 2^28 pixels and 2^20 a side)", what,
                            (long long)width, (long long)height);
    return LUCENT_OK;
}

static _Atomic uint64_t g_read_limit;

void lucent_image_set_read_limit(uint64_t pixels)
{
    g_read_limit = pixels > LUCENT_IMAGE_MAX_PIXELS ? LUCENT_IMAGE_MAX_PIXELS : pixels;
}

uint64_t lucent_image_read_limit(void)
{
    uint64_t l = g_read_limit;
    if (l) return l;
    const char *env = getenv("LUCENT_IMAGE_MAX_PIXELS");
    char *end;
    unsigned long long v = env ? strtoull(env, &end, 10) : 0;
    if (env && *env && !*end && v > 0) return v > LUCENT_IMAGE_MAX_PIXELS ? LUCENT_IMAGE_MAX_PIXELS : v;
    return LUCENT_IMAGE_DEFAULT_READ_PIXELS;
}

lucent_status image_check_read(const char *path, int64_t width, int64_t height, int channels)
{
    lucent_status s = image_check_size(path, width, height, channels, LUCENT_ERR_PARSE);
    if (s != LUCENT_OK) return s;
    uint64_t limit = lucent_image_read_limit(), n = (uint64_t)width * (uint64_t)height;
    if (n > limit)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: declares %lldx%lld pixels (%.0f Mpixels), above the read limit of %.0f Mpixels (the "
                            "environment variable LUCENT_IMAGE_MAX_PIXELS raises it)",
                            path, (long long)width, (long long)height, (double)n / 1048576.0,
                            (double)limit / 1048576.0);
    return LUCENT_OK;
}

lucent_status lucent_image_create(int width, int height, int channels, lucent_image **dest)
{
    *dest = NULL;
    lucent_status s = image_check_size("image", width, height, channels, LUCENT_ERR_INVALID_ARGUMENT);
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)width * (size_t)height * (size_t)channels;
    lucent_image *img = malloc(sizeof *img);
    float *data = calloc(n, sizeof(float));
    if (!img || !data) {
        free(img);
        free(data);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory for a %dx%dx%d image", width, height, channels);
    }
    *img = (lucent_image){width, height, channels, data};
    *dest = img;
    return LUCENT_OK;
}

void lucent_image_destroy(lucent_image *img)
{
    if (!img) return;
    free(img->data);
    free(img);
}

size_t lucent_image_value_count(const lucent_image *img)
{
    return (size_t)img->width * (size_t)img->height * (size_t)img->channels;
}

lucent_status lucent_image_clone(const lucent_image *src, lucent_image **dest)
{
    lucent_status s = lucent_image_create(src->width, src->height, src->channels, dest);
    if (s == LUCENT_OK) memcpy((*dest)->data, src->data, lucent_image_value_count(src) * sizeof(float));
    return s;
}

/* One pixel from sc to dc channels (see lucent_image_convert_channels). */
static void convert_pixel(const float *in, int sc, float *out, int dc)
{
    if (sc == dc) {
        memcpy(out, in, (size_t)sc * sizeof(float));
    } else if (dc == 1) { /* Rec. 709 / sRGB luminance weights (ITU-R BT.709-6, item 3.2) */
        out[0] = 0.2126f * in[0] + 0.7152f * in[1] + 0.0722f * in[2];
    } else {
        for (int c = 0; c < 3; c++) out[c] = sc == 1 ? in[0] : in[c];
        if (dc == 4) out[3] = sc == 4 ? in[3] : 1.0f;
    }
}

lucent_status lucent_image_convert_channels(const lucent_image *src, int channels, lucent_image **dest)
{
    lucent_status s = lucent_image_create(src->width, src->height, channels, dest);
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++)
        convert_pixel(src->data + i * (size_t)src->channels, src->channels, (*dest)->data + i * (size_t)channels,
                      channels);
    return LUCENT_OK;
}

float *lucent_image_pixel(const lucent_image *img, int x, int y)
{
    assert(x >= 0 && x < img->width && y >= 0 && y < img->height);
    return img->data + ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels;
}

float lucent_image_get(const lucent_image *img, int x, int y, int c)
{
    assert(c >= 0 && c < img->channels);
    return lucent_image_pixel(img, x, y)[c];
}

void lucent_image_set(lucent_image *img, int x, int y, int c, float value)
{
    assert(c >= 0 && c < img->channels);
    lucent_image_pixel(img, x, y)[c] = value;
}

void lucent_image_fill(lucent_image *img, int c, float value)
{
    assert(c < img->channels);
    size_t n = lucent_image_value_count(img);
    for (size_t i = 0; i < n; i++)
        if (c < 0 || (int)(i % (size_t)img->channels) == c) img->data[i] = value;
}

lucent_status image_check_same(const lucent_image *a, const lucent_image *b)
{
    if (a->width == b->width && a->height == b->height && a->channels == b->channels) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "images differ in size: %dx%d with %d channels vs %dx%d with %d channels", a->width, a->height,
                        a->channels, b->width, b->height, b->channels);
}
