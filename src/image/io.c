/* Choosing the file format by extension, write defaults, and byte helpers shared by the formats. */
#include <string.h>
#include <strings.h>

#include "image/internal.h"

lucent_image_write_desc lucent_image_write_defaults(void)
{
    return (lucent_image_write_desc){
        .format = LUCENT_IMAGE_FORMAT_AUTO,
        .png_bits = 8,
        .png_linear = false,
        .exr_pixel = LUCENT_EXR_PIXEL_FLOAT,
        .exr_compression = LUCENT_EXR_COMPRESSION_ZIP,
    };
}

lucent_image_write_desc image_resolve_desc(const lucent_image_write_desc *desc)
{
    lucent_image_write_desc d = lucent_image_write_defaults();
    if (!desc) return d;
    lucent_image_write_desc r = *desc;
    if (!r.png_bits) r.png_bits = d.png_bits;
    if (!r.exr_pixel) r.exr_pixel = d.exr_pixel;
    if (!r.exr_compression) r.exr_compression = d.exr_compression;
    return r;
}

lucent_status lucent_image_format_from_path(const char *path, lucent_image_format *dest)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    *dest = LUCENT_IMAGE_FORMAT_AUTO;
    if (dot && (!slash || dot > slash)) {
        if (strcasecmp(dot, ".png") == 0) *dest = LUCENT_IMAGE_FORMAT_PNG;
        if (strcasecmp(dot, ".exr") == 0) *dest = LUCENT_IMAGE_FORMAT_EXR;
        if (strcasecmp(dot, ".pfm") == 0) *dest = LUCENT_IMAGE_FORMAT_PFM;
    }
    if (*dest != LUCENT_IMAGE_FORMAT_AUTO) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: unknown image format (expected a .png, .exr or .pfm file name)",
                        path);
}

lucent_status lucent_image_load(const char *path, lucent_image **dest)
{
    *dest = NULL;
    if (!path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "image: no file given (NULL path)");
    lucent_image_format f;
    lucent_status s = lucent_image_format_from_path(path, &f);
    if (s != LUCENT_OK) return s;
    if (f == LUCENT_IMAGE_FORMAT_PNG) return lucent_image_load_png(path, dest);
    if (f == LUCENT_IMAGE_FORMAT_EXR) return lucent_image_load_exr(path, dest);
    return lucent_image_load_pfm(path, dest);
}

lucent_status lucent_image_write(const char *path, const lucent_image *img, const lucent_image_write_desc *desc)
{
    lucent_image_format f = desc ? desc->format : LUCENT_IMAGE_FORMAT_AUTO;
    if (f == LUCENT_IMAGE_FORMAT_AUTO) {
        lucent_status s = lucent_image_format_from_path(path, &f);
        if (s != LUCENT_OK) return s;
    }
    if (f == LUCENT_IMAGE_FORMAT_PNG) return lucent_image_write_png(path, img, desc);
    if (f == LUCENT_IMAGE_FORMAT_EXR) return lucent_image_write_exr(path, img, desc);
    if (f == LUCENT_IMAGE_FORMAT_PFM) return lucent_image_write_pfm(path, img);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: unknown image format %d", path, (int)f);
}

void image_put_le32(unsigned char *p, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(u >> (8 * i));
}

float image_get_f32(const unsigned char *p, bool little_endian)
{
    uint32_t u = 0;
    for (int i = 0; i < 4; i++) u |= (uint32_t)p[little_endian ? i : 3 - i] << (8 * i);
    float v;
    memcpy(&v, &u, 4);
    return v;
}
