/* Headless OpenGL through EGL: Mesa's surfaceless platform (llvmpipe on machines without a GPU, or
 * a Mesa GPU driver) and the EGL device platform (NVIDIA's headless path). No window system, no
 * surface: the renderer draws into framebuffer objects. */
#include <epoxy/egl.h>
#include <pthread.h>
#include <string.h>

#include "gl/core/context_internal.h"

enum { MAX_DEVICES = 16 };

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
    }
}

static lucent_status egl_fail(const char *what)
{
    EGLint e = eglGetError();
    return lucent_error(LUCENT_ERR_GL, "no OpenGL context: %s (%s, 0x%04x)", what, egl_error_name(e), (unsigned)e);
}

static bool client_has(const char *ext) { return epoxy_has_egl_extension(EGL_NO_DISPLAY, ext); }

/* The EGL devices (EGL_EXT_device_enumeration); 0 when the extension is missing. */
static int egl_devices(EGLDeviceEXT *devices)
{
    EGLint n = 0;
    if (!client_has("EGL_EXT_device_enumeration") || !client_has("EGL_EXT_device_query")) return 0;
    if (!eglQueryDevicesEXT(MAX_DEVICES, devices, &n)) return 0;
    return n;
}

static const char *device_extensions(EGLDeviceEXT d)
{
    const char *e = eglQueryDeviceStringEXT(d, EGL_EXTENSIONS);
    return e ? e : "";
}

/* The first device that is not Mesa's software device, or -1. */
static int hardware_device(const EGLDeviceEXT *devices, int n)
{
    for (int i = 0; i < n; i++)
        if (!strstr(device_extensions(devices[i]), "EGL_MESA_device_software")) return i;
    return -1;
}

/* EGL hands out one display per platform and device, shared by every context of the process:
 * eglTerminate on it would end every context. Contexts count their uses; the last one terminates. */
enum { MAX_DISPLAYS = 16 };
static pthread_mutex_t g_display_lock = PTHREAD_MUTEX_INITIALIZER;
static struct {
    EGLDisplay display;
    int users;
} g_displays[MAX_DISPLAYS];

static int display_use(EGLDisplay d, int delta)
{
    int users = 0;
    pthread_mutex_lock(&g_display_lock);
    int i = 0, free_slot = -1;
    for (; i < MAX_DISPLAYS && g_displays[i].display != d; i++)
        if (!g_displays[i].display && free_slot < 0) free_slot = i;
    if (i == MAX_DISPLAYS && free_slot >= 0 && delta > 0) g_displays[i = free_slot].display = d;
    if (i < MAX_DISPLAYS) {
        users = g_displays[i].users += delta;
        if (users <= 0) g_displays[i].display = NULL, g_displays[i].users = 0;
    }
    pthread_mutex_unlock(&g_display_lock);
    return users;
}

static lucent_status open_display(lucent_gl_context *ctx, EGLenum platform, void *native)
{
    EGLDisplay d = eglGetPlatformDisplayEXT(platform, native, NULL);
    if (d == EGL_NO_DISPLAY) return egl_fail("eglGetPlatformDisplayEXT gave no display");
    EGLint major, minor;
    if (!eglInitialize(d, &major, &minor)) return egl_fail("eglInitialize failed");
    display_use(d, +1);
    ctx->egl_display = d;
    return LUCENT_OK;
}

/* A context without a config and without a surface (EGL_KHR_no_config_context,
 * EGL_KHR_surfaceless_context), else the first OpenGL-capable config. */
static lucent_status create_context(lucent_gl_context *ctx, bool debug)
{
    EGLDisplay d = ctx->egl_display;
    if (!eglBindAPI(EGL_OPENGL_API)) return egl_fail("the EGL display has no desktop OpenGL (eglBindAPI)");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!epoxy_has_egl_extension(d, "EGL_KHR_no_config_context")) {
        EGLint n = 0, want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
        if (!eglChooseConfig(d, want, &config, 1, &n) || n < 1) return egl_fail("no EGL config renders OpenGL");
    }
    if (!epoxy_has_egl_extension(d, "EGL_KHR_surfaceless_context"))
        return lucent_error(LUCENT_ERR_GL, "no OpenGL context: the EGL display lacks EGL_KHR_surfaceless_context");
    EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                        4,
                        EGL_CONTEXT_MINOR_VERSION,
                        5,
                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                        EGL_CONTEXT_OPENGL_DEBUG,
                        debug ? EGL_TRUE : EGL_FALSE,
                        EGL_NONE};
    EGLContext c = eglCreateContext(d, config, EGL_NO_CONTEXT, attribs);
    if (c == EGL_NO_CONTEXT) return egl_fail("the driver offers no OpenGL 4.5 core context");
    ctx->egl_context = c;
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) return egl_fail("eglMakeCurrent failed");
    return LUCENT_OK;
}

static lucent_status open_device(lucent_gl_context *ctx, int device, bool debug)
{
    EGLDeviceEXT devices[MAX_DEVICES];
    int n = egl_devices(devices);
    if (!client_has("EGL_EXT_platform_device") || n == 0)
        return lucent_error(LUCENT_ERR_GL, "no OpenGL context: EGL lists no devices (EGL_EXT_platform_device)");
    int i = device > 0 ? device - 1 : hardware_device(devices, n);
    if (i < 0) i = 0;
    if (i >= n)
        return lucent_error(LUCENT_ERR_GL,
                            "no OpenGL context: EGL device %d not found (%d device%s; LUCENT_GL_DEVICE "
                            "counts from 1)",
                            device, n, n == 1 ? "" : "s");
    snprintf(ctx->info.device, sizeof ctx->info.device, "EGL device %d: %s", i + 1, device_extensions(devices[i]));
    ctx->platform = LUCENT_GL_DEVICE;
    lucent_status s = open_display(ctx, EGL_PLATFORM_DEVICE_EXT, devices[i]);
    return s == LUCENT_OK ? create_context(ctx, debug) : s;
}

static lucent_status open_surfaceless(lucent_gl_context *ctx, bool debug)
{
    if (!client_has("EGL_MESA_platform_surfaceless"))
        return lucent_error(LUCENT_ERR_GL, "no OpenGL context: EGL lacks EGL_MESA_platform_surfaceless (not Mesa?)");
    ctx->platform = LUCENT_GL_SURFACELESS;
    snprintf(ctx->info.device, sizeof ctx->info.device, "Mesa surfaceless");
    lucent_status s = open_display(ctx, EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
    return s == LUCENT_OK ? create_context(ctx, debug) : s;
}

lucent_status gl_egl_create(lucent_gl_context *ctx, lucent_gl_platform platform, int device, bool debug)
{
    if (!client_has("EGL_EXT_platform_base"))
        return lucent_error(LUCENT_ERR_GL, "no OpenGL context: EGL lacks EGL_EXT_platform_base");
    if (platform == LUCENT_GL_SURFACELESS) return open_surfaceless(ctx, debug);
    if (platform == LUCENT_GL_DEVICE || device > 0) return open_device(ctx, device, debug);
    EGLDeviceEXT devices[MAX_DEVICES];
    int n = egl_devices(devices);
    if (client_has("EGL_EXT_platform_device") && hardware_device(devices, n) >= 0) {
        if (open_device(ctx, 0, debug) == LUCENT_OK) return LUCENT_OK;
        lucent_log(LUCENT_LOG_INFO, "GL: %s; trying Mesa's surfaceless platform", lucent_last_error());
        gl_egl_destroy(ctx); /* a hardware device that gives no 4.5 core context */
    }
    return open_surfaceless(ctx, debug);
}

void gl_egl_destroy(lucent_gl_context *ctx)
{
    if (ctx->egl_display) {
        if (ctx->egl_context && eglGetCurrentContext() == ctx->egl_context)
            eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ctx->egl_context) eglDestroyContext(ctx->egl_display, ctx->egl_context);
        if (display_use(ctx->egl_display, -1) == 0) eglTerminate(ctx->egl_display);
    }
    ctx->egl_display = ctx->egl_context = NULL;
}

lucent_status gl_egl_make_current(lucent_gl_context *ctx)
{
    if (!eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl_context))
        return egl_fail("eglMakeCurrent failed");
    return LUCENT_OK;
}
