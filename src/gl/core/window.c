/* A GLFW window with an OpenGL 4.5 core context: the interactive side of the same renderer. */
#include "gl/core/context_internal.h" /* epoxy before GLFW */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <string.h>

static _Thread_local char t_glfw_error[512];

static void on_glfw_error(int code, const char *text)
{
    snprintf(t_glfw_error, sizeof t_glfw_error, "%s (GLFW error 0x%x)", text ? text : "unknown", (unsigned)code);
}

static lucent_status glfw_fail(const char *what)
{
    return lucent_error(LUCENT_ERR_GL, "no OpenGL window: %s: %s", what,
                        t_glfw_error[0] ? t_glfw_error : "no reason given");
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    if (action == GLFW_PRESS && (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q)) glfwSetWindowShouldClose(w, GLFW_TRUE);
}

lucent_status gl_window_create(lucent_gl_context *ctx, const lucent_gl_desc *desc)
{
    t_glfw_error[0] = '\0';
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) return glfw_fail("cannot initialise GLFW (is there a display? DISPLAY or WAYLAND_DISPLAY)");
    ctx->glfw_initialised = true;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc->debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
    int w = desc->width > 0 ? desc->width : 512, h = desc->height > 0 ? desc->height : 512;
    ctx->window = glfwCreateWindow(w, h, desc->title ? desc->title : "Lucent", NULL, NULL);
    if (!ctx->window) return glfw_fail("cannot open a window with an OpenGL 4.5 core context");
    glfwSetKeyCallback(ctx->window, on_key);
    glfwMakeContextCurrent(ctx->window);
    glfwSwapInterval(0);
    ctx->platform = LUCENT_GL_WINDOW;
    snprintf(ctx->info.device, sizeof ctx->info.device, "GLFW %s", glfwGetVersionString());
    return LUCENT_OK;
}

void gl_window_destroy(lucent_gl_context *ctx)
{
    if (ctx->window) glfwDestroyWindow(ctx->window);
    if (ctx->glfw_initialised) glfwTerminate();
    ctx->window = NULL;
    ctx->glfw_initialised = false;
}

lucent_status gl_window_make_current(lucent_gl_context *ctx)
{
    glfwMakeContextCurrent(ctx->window);
    return LUCENT_OK;
}

void gl_window_swap(lucent_gl_context *ctx) { glfwSwapBuffers(ctx->window); }

void gl_window_size(const lucent_gl_context *ctx, int *width, int *height)
{
    glfwGetFramebufferSize(ctx->window, width, height);
}

bool lucent_gl_window_poll(lucent_gl_context *ctx)
{
    if (!ctx || !ctx->window) return false;
    glfwPollEvents();
    return !glfwWindowShouldClose(ctx->window);
}

void lucent_gl_window_set_title(lucent_gl_context *ctx, const char *title)
{
    if (ctx && ctx->window && title) glfwSetWindowTitle(ctx->window, title);
}

void *lucent_gl_window_handle(lucent_gl_context *ctx) { return ctx ? ctx->window : NULL; }

void lucent_gl_window_swap(lucent_gl_context *ctx)
{
    if (ctx && ctx->window) gl_window_swap(ctx);
}
