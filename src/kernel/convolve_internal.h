/* Internal helpers shared by the convolution files. */
#ifndef LUCENT_SRC_KERNEL_CONVOLVE_INTERNAL_H
#define LUCENT_SRC_KERNEL_CONVOLVE_INTERNAL_H

#include "lucent/image.h"

/* Checks src and dest: present, 1, 3 or 4 channels, the same size; fn names the caller. */
lucent_status conv_check_images(const char *fn, const lucent_image *src, const lucent_image *dest);

#endif
