/* The GL context behind lucent_gl_context: EGL (surfaceless or device) or a GLFW window.
 * Internal: GL and EGL types stay inside src/gl. */
#ifndef LUCENT_SRC_GL_CONTEXT_INTERNAL_H
#define LUCENT_SRC_GL_CONTEXT_INTERNAL_H

#include <epoxy/gl.h>

#include "lucent/render.h"

struct GLFWwindow;

struct lucent_gl_context {
    lucent_gl_platform platform; /* the platform in use (never AUTO) */
    void *egl_display;           /* EGLDisplay */
    void *egl_context;           /* EGLContext */
    struct GLFWwindow *window;
    bool glfw_initialised;
    lucent_gl_info info;
};

/* EGL: creates a 4.5 core context on platform (AUTO, SURFACELESS or DEVICE) and makes it current;
 * device counts from 1 (0: automatic). Fills ctx->egl_*, ctx->platform and info.platform/device. */
lucent_status gl_egl_create(lucent_gl_context *ctx, lucent_gl_platform platform, int device, bool debug);
void gl_egl_destroy(lucent_gl_context *ctx);
lucent_status gl_egl_make_current(lucent_gl_context *ctx);

/* GLFW: opens a window with a 4.5 core context and makes it current. */
lucent_status gl_window_create(lucent_gl_context *ctx, const lucent_gl_desc *desc);
void gl_window_destroy(lucent_gl_context *ctx);
lucent_status gl_window_make_current(lucent_gl_context *ctx);
void gl_window_swap(lucent_gl_context *ctx);
void gl_window_size(const lucent_gl_context *ctx, int *width, int *height);

/* Fails with LUCENT_ERR_GL naming the first pending GL error and `what` (clears the error queue). */
lucent_status gl_check(const char *what);

#endif
