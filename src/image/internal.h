/* Shared helpers of the image module (not public). */
#ifndef LUCENT_IMAGE_INTERNAL_H
#define LUCENT_IMAGE_INTERNAL_H

#include "lucent/image.h"

/* Checks a size read from a file or asked for by a caller against the limits in image.h.
 * what names the source in the message ("x.pfm", or "image"); bad is the status to fail with. */
lucent_status image_check_size(const char *what, int64_t width, int64_t height, int channels, lucent_status bad);
/* image_check_size, and the declared size against lucent_image_read_limit (a file being read). */
lucent_status image_check_read(const char *path, int64_t width, int64_t height, int channels);

/* Resolves the zero fields of desc (NULL: all defaults). */
lucent_image_write_desc image_resolve_desc(const lucent_image_write_desc *desc);

/* Checks that a and b have the same size and channel count (message names both). */
lucent_status image_check_same(const lucent_image *a, const lucent_image *b);

/* Writes the rows of a float32 value to 4 bytes little endian and back. */
void image_put_le32(unsigned char *p, float v);
float image_get_f32(const unsigned char *p, bool little_endian);

#endif
