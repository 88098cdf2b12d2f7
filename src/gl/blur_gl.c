/* lucent_ssss_blur_gl: the renderer's blur shader run on images given by the caller (the GPU side
 * of the blur test, and a tool for anyone who wants the blur alone). */
#include <stdlib.h>

#include "gl/blur.h"
#include "gl/reference/reference.h"

/* RG32F texture: x depth (mm), y material index; image row 0 at texture row 0. */
static lucent_status depth_texture(const lucent_image *depth, const uint8_t *material, GLuint *dest)
{
    size_t n = (size_t)depth->width * (size_t)depth->height;
    float *rg = malloc(2 * n * sizeof *rg);
    if (!rg) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; i < n; i++) rg[2 * i] = depth->data[i], rg[2 * i + 1] = material ? (float)material[i] : 0.0f;
    *dest = gl_texture(GL_RG32F, depth->width, depth->height, GL_NEAREST);
    glTextureSubImage2D(*dest, 0, 0, 0, depth->width, depth->height, GL_RG, GL_FLOAT, rg);
    free(rg);
    return gl_check("uploading the depth");
}

static void copy_rgb(const lucent_image *src, lucent_image *dest)
{
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            dest->data[i * (size_t)dest->channels + (size_t)c] = src->data[i * (size_t)src->channels + (size_t)c];
}

lucent_status lucent_ssss_blur_gl(lucent_gl_context *ctx, const lucent_image *irradiance, const lucent_image *depth,
                                  const uint8_t *material, const lucent_ssss_blur_desc *desc, lucent_image *dest)
{
    lucent_status s = gl_blur_check_args(irradiance, depth, material, desc, dest);
    if (s == LUCENT_OK) s = lucent_gl_make_current(ctx);
    if (s != LUCENT_OK) return s;
    gl_blur b;
    GLuint src = 0, z = 0;
    lucent_image *out = NULL;
    double ws = desc->width_scale > 0 ? desc->width_scale : 1;
    s = gl_blur_init(&b);
    if (s == LUCENT_OK) s = gl_blur_set_taps(&b, desc->taps, desc->material_count, ws);
    if (s == LUCENT_OK) s = gl_blur_resize(&b, irradiance->width, irradiance->height);
    if (s == LUCENT_OK) s = gl_texture_from_image(irradiance, GL_NEAREST, &src);
    if (s == LUCENT_OK) s = depth_texture(depth, material, &z);
    if (s == LUCENT_OK) {
        gl_blur_run(&b, src, z, desc->pixel_scale * ws, desc->filter, NULL);
        s = gl_read_image(b.sum_fbo, 0, b.width, b.height, 3, false, &out);
    }
    if (s == LUCENT_OK) copy_rgb(out, dest);
    lucent_image_destroy(out);
    glDeleteTextures(1, &src);
    glDeleteTextures(1, &z);
    gl_blur_free(&b);
    return s;
}
