/* lucent_gl_context: one interface over EGL (headless) and GLFW (a window), with the platform chosen
 * by the caller or the environment, and a clear error when no OpenGL 4.5 core context can be made. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "gl/core/context_internal.h"

static const char *const k_platforms[] = {"auto", "surfaceless", "device", "window"};

const char *lucent_gl_platform_name(lucent_gl_platform platform)
{
    return platform >= LUCENT_GL_AUTO && platform <= LUCENT_GL_WINDOW ? k_platforms[platform] : "unknown";
}

lucent_status lucent_gl_platform_parse(const char *name, lucent_gl_platform *dest)
{
    for (int i = 0; i <= LUCENT_GL_WINDOW; i++)
        if (name && !strcasecmp(name, k_platforms[i])) return *dest = (lucent_gl_platform)i, LUCENT_OK;
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown GL platform '%s' (auto, surfaceless, device, window)",
                        name ? name : "");
}

/* LUCENT_GL_PLATFORM and LUCENT_GL_DEVICE fill what the desc leaves at zero. */
static lucent_status apply_env(lucent_gl_desc *d)
{
    const char *p = getenv("LUCENT_GL_PLATFORM"), *dev = getenv("LUCENT_GL_DEVICE");
    if (d->platform == LUCENT_GL_AUTO && p && *p && lucent_gl_platform_parse(p, &d->platform))
        return lucent_error_context(LUCENT_ERR_GL, "no OpenGL context: LUCENT_GL_PLATFORM");
    if (d->device == 0 && dev && *dev) {
        char *end;
        long v = strtol(dev, &end, 10);
        if (*end || v < 1 || v > 1000)
            return lucent_error(LUCENT_ERR_GL,
                                "no OpenGL context: LUCENT_GL_DEVICE: '%s' is not a device number "
                                "(1, 2, ...)",
                                dev);
        d->device = (int)v;
    }
    return LUCENT_OK;
}

static void copy_string(char *dest, size_t size, GLenum name)
{
    const GLubyte *s = glGetString(name);
    snprintf(dest, size, "%s", s ? (const char *)s : "");
}

static void fill_info(lucent_gl_context *ctx)
{
    lucent_gl_info *i = &ctx->info;
    snprintf(i->platform, sizeof i->platform, "%s", lucent_gl_platform_name(ctx->platform));
    copy_string(i->renderer, sizeof i->renderer, GL_RENDERER);
    copy_string(i->vendor, sizeof i->vendor, GL_VENDOR);
    copy_string(i->version, sizeof i->version, GL_VERSION);
    copy_string(i->glsl, sizeof i->glsl, GL_SHADING_LANGUAGE_VERSION);
    i->software = strstr(i->renderer, "llvmpipe") || strstr(i->renderer, "softpipe") || strstr(i->renderer, "swrast") ||
                  strstr(i->renderer, "SwiftShader");
}

/* The context must be 4.5 or later with the core profile (a driver may hand out more than asked). */
static lucent_status check_version(const lucent_gl_context *ctx)
{
    GLint major = 0, minor = 0, mask = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    if (major * 10 + minor < 45 || !(mask & GL_CONTEXT_CORE_PROFILE_BIT))
        return lucent_error(LUCENT_ERR_GL, "no OpenGL 4.5 core context: got \"%s\" from %s", ctx->info.version,
                            ctx->info.renderer);
    return LUCENT_OK;
}

static void GLAPIENTRY on_debug(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                const GLchar *message, const void *user)
{
    (void)source, (void)type, (void)id, (void)length, (void)user;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    lucent_log(severity == GL_DEBUG_SEVERITY_HIGH ? LUCENT_LOG_WARN : LUCENT_LOG_DEBUG, "GL: %s", message);
}

/* A software rasteriser allocates its per-frame bins and tiles with malloc, megabytes a frame; with
 * glibc's defaults they come from fresh mmaps (or a heap trimmed at every free), so every frame
 * faults its pages in again. On the development machines (virtual, about 15 us a fault) that was
 * half of Lambert's frame: 165 ms against 78 ms for the bunny at 512 x 512, and it made Lambert look
 * dearer than the CDRF, whose curvature pass happened to raise glibc's dynamic thresholds first.
 * Fixed thresholds keep the freed pages mapped for reuse, the same for every method. */
static void keep_driver_pages(void)
{
#ifdef __GLIBC__
    (void)mallopt(M_MMAP_THRESHOLD, 32 << 20);
    (void)mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

static lucent_status create(lucent_gl_context *ctx, lucent_gl_desc *d)
{
    lucent_status s = d->ignore_env ? LUCENT_OK : apply_env(d);
    if (s != LUCENT_OK) return s;
    s = d->platform == LUCENT_GL_WINDOW ? gl_window_create(ctx, d)
                                        : gl_egl_create(ctx, d->platform, d->device, d->debug);
    if (s != LUCENT_OK) return s;
    fill_info(ctx);
    if (ctx->info.software) keep_driver_pages();
    s = check_version(ctx);
    if (s == LUCENT_OK && d->debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glDebugMessageCallback(on_debug, NULL);
    }
    return s;
}

lucent_status lucent_gl_create(const lucent_gl_desc *desc, lucent_gl_context **dest)
{
    lucent_gl_desc d = desc ? *desc : (lucent_gl_desc){0};
    *dest = NULL;
    lucent_gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = create(ctx, &d);
    if (s != LUCENT_OK) {
        lucent_gl_destroy(ctx);
        return s;
    }
    *dest = ctx;
    return LUCENT_OK;
}

void lucent_gl_destroy(lucent_gl_context *ctx)
{
    if (!ctx) return;
    if (ctx->window || ctx->glfw_initialised)
        gl_window_destroy(ctx);
    else
        gl_egl_destroy(ctx);
    free(ctx);
}

lucent_status lucent_gl_make_current(lucent_gl_context *ctx)
{
    return ctx->window ? gl_window_make_current(ctx) : gl_egl_make_current(ctx);
}

void lucent_gl_get_info(const lucent_gl_context *ctx, lucent_gl_info *dest) { *dest = ctx->info; }

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error";
    }
}

lucent_status gl_check(const char *what)
{
    GLenum e = glGetError(), first = e;
    for (int i = 0; e != GL_NO_ERROR && i < 64; i++) e = glGetError();
    if (first == GL_NO_ERROR) return LUCENT_OK;
    if (first == GL_OUT_OF_MEMORY)
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: the GL driver is out of memory", what);
    return lucent_error(LUCENT_ERR_GL, "%s: %s (0x%04x)", what, gl_error_name(first), (unsigned)first);
}
