/* Textures, framebuffers, read-back and GPU timer queries. */
#include <stdlib.h>
#include <string.h>

#include "gl/core/gpu.h"

/* ---- textures and framebuffers ---- */

GLuint gl_texture(GLenum internal_format, int width, int height, GLenum filter)
{
    GLuint t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, internal_format, width, height);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

lucent_status gl_texture_from_image(const lucent_image *img, GLenum filter, GLuint *dest)
{
    static const GLenum internal[] = {0, GL_R32F, 0, GL_RGB32F, GL_RGBA32F};
    static const GLenum format[] = {0, GL_RED, 0, GL_RGB, GL_RGBA};
    int c = img->channels;
    GLuint t = gl_texture(internal[c], img->width, img->height, filter);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(t, 0, 0, 0, img->width, img->height, format[c], GL_FLOAT, img->data);
    lucent_status s = gl_check("uploading a texture");
    if (s != LUCENT_OK) glDeleteTextures(1, &t), t = 0;
    *dest = t;
    return s;
}

/* Why a framebuffer is incomplete, in the driver's own terms: the GL error its textures' allocation left
 * (GL_OUT_OF_MEMORY for a 16384 x 16384 float target on llvmpipe), the size of its first attachment and the
 * driver's limits, so that the message says what to lower. */
static lucent_status framebuffer_error(const char *what, GLenum status, GLuint texture)
{
    GLenum error = glGetError();
    while (glGetError() != GL_NO_ERROR) {
    }
    GLint w = 0, h = 0, max_texture = 0, max_w = 0, max_h = 0;
    if (texture) {
        glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &h);
    }
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
    while (glGetError() != GL_NO_ERROR) {
    }
    char size[64] = "";
    if (w > 0 && h > 0) snprintf(size, sizeof size, " of %d x %d", w, h);
    const char *cause = error == GL_OUT_OF_MEMORY ? "the driver ran out of memory for its targets (GL_OUT_OF_MEMORY)"
                        : status == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT ? "an attachment could not be made"
                        : status == GL_FRAMEBUFFER_UNSUPPORTED           ? "the formats are not supported together"
                                                                         : "the driver refused it";
    return lucent_error(LUCENT_ERR_GL,
                        "%s: the GL driver cannot make the framebuffer%s (status 0x%04x: %s; its limits: textures of "
                        "%d texels a side, framebuffers of %d x %d); lower render.width and render.height",
                        what, size, (unsigned)status, cause, max_texture, max_w, max_h);
}

lucent_status gl_framebuffer(int count, const GLuint *colors, GLuint depth, const char *what, GLuint *dest)
{
    GLuint f;
    GLenum buffers[8];
    glCreateFramebuffers(1, &f);
    for (int i = 0; i < count && i < 8; i++) {
        glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0 + (GLenum)i, colors[i], 0);
        buffers[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
    }
    glNamedFramebufferDrawBuffers(f, count, buffers);
    if (depth) glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, depth, 0);
    GLenum st = glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &f);
        *dest = 0;
        return framebuffer_error(what, st, count ? colors[0] : depth);
    }
    *dest = f;
    return gl_check(what);
}

lucent_status gl_read_image(GLuint fbo, int attachment, int width, int height, int channels, bool flip,
                            lucent_image **dest)
{
    float *rgba = malloc((size_t)width * (size_t)height * 4 * sizeof *rgba);
    lucent_status s = rgba ? lucent_image_create(width, height, channels, dest)
                           : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory reading an image back");
    if (s != LUCENT_OK) return free(rgba), s;
    glNamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0 + (GLenum)attachment);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    float *out = (*dest)->data;
    for (int y = 0; y < height; y++) {
        const float *row = rgba + (size_t)(flip ? height - 1 - y : y) * (size_t)width * 4;
        for (int x = 0; x < width; x++)
            for (int c = 0; c < channels; c++) *out++ = row[4 * x + c];
    }
    free(rgba);
    s = gl_check("reading an image back");
    if (s != LUCENT_OK) lucent_image_destroy(*dest), *dest = NULL;
    return s;
}

/* ---- timer queries ---- */

void gl_timer_begin(gl_timer *t)
{
    if (!t->created) glGenQueries(LUCENT_RENDER_MAX_PASSES + 1, t->queries);
    t->created = true;
    t->count = 0;
    t->cpu_start = lucent_clock_ms();
    glQueryCounter(t->queries[0], GL_TIMESTAMP);
}

void gl_timer_mark(gl_timer *t, const char *name)
{
    if (t->count == LUCENT_RENDER_MAX_PASSES) t->count--; /* merge into the last pass */
    snprintf(t->names[t->count], sizeof t->names[t->count], "%s", name);
    glQueryCounter(t->queries[++t->count], GL_TIMESTAMP);
}

void gl_timer_end(gl_timer *t, lucent_frame_times *dest)
{
    glFinish();
    double cpu = lucent_clock_ms() - t->cpu_start;
    memset(dest, 0, sizeof *dest);
    GLuint64 stamp[LUCENT_RENDER_MAX_PASSES + 1];
    for (int i = 0; i <= t->count; i++) glGetQueryObjectui64v(t->queries[i], GL_QUERY_RESULT, &stamp[i]);
    dest->pass_count = t->count;
    for (int i = 0; i < t->count; i++) {
        memcpy(dest->pass_name[i], t->names[i], sizeof dest->pass_name[i]);
        dest->pass_ms[i] = stamp[i + 1] > stamp[i] ? (double)(stamp[i + 1] - stamp[i]) * 1e-6 : 0;
        if (!strncmp(t->names[i], "blur", 4)) dest->blur_ms += dest->pass_ms[i];
    }
    dest->gpu_ms = t->count && stamp[t->count] > stamp[0] ? (double)(stamp[t->count] - stamp[0]) * 1e-6 : 0;
    dest->cpu_ms = cpu;
}

void gl_timer_free(gl_timer *t)
{
    if (t->created) glDeleteQueries(LUCENT_RENDER_MAX_PASSES + 1, t->queries);
    t->created = false;
}
