/* Lucent render: the real-time renderer, OpenGL 4.5 core with GLSL shaders. Methods: Lambert with a
 * specular lobe, Kubo's curvature-dependent reflectance (CDRF, with its LUT or in closed form), the
 * CDRF with depth-based transmission (the CDRF blog), and Jimenez's screen-space separable
 * subsurface scattering (Freude 2014, chapter 4, Algorithm 4.1) with any kernel of lucent/kernel.h.
 * See docs/render.md for the formulas.
 *
 * GL stays inside the library: this header holds no GL type, only opaque handles (as Embree keeps
 * its types in). A renderer must be used on the thread that created its context.
 *
 * Images: linear float RGB radiance, top row first (lucent_image), before any tonemapping. */
#ifndef LUCENT_RENDER_H
#define LUCENT_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/bake.h"
#include "lucent/base.h"
#include "lucent/image.h"
#include "lucent/kernel.h"
#include "lucent/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- The OpenGL context ------------------------------------------------------------------------ */

typedef struct lucent_gl_context lucent_gl_context;

typedef enum lucent_gl_platform {
    LUCENT_GL_AUTO = 0,    /* headless: a hardware EGL device (NVIDIA) if there is one, else Mesa's
                              surfaceless platform (llvmpipe or a Mesa GPU driver) */
    LUCENT_GL_SURFACELESS, /* EGL_MESA_platform_surfaceless */
    LUCENT_GL_DEVICE,      /* EGL_EXT_platform_device: the chosen EGL device */
    LUCENT_GL_WINDOW       /* a GLFW window (needs a display) */
} lucent_gl_platform;

/* How to make a context; a zero field means the default. Unless ignore_env, the environment
 * variables LUCENT_GL_PLATFORM (auto, surfaceless, device, window) and LUCENT_GL_DEVICE (an EGL
 * device number counted from 1) replace platform and device when those are zero. */
typedef struct lucent_gl_desc {
    lucent_gl_platform platform;
    int device;        /* EGL device number counted from 1; 0: the first hardware device, else the
                           first device */
    int width, height; /* window: client size (0: 512 x 512) */
    const char *title; /* window: NULL: "Lucent" */
    bool debug;        /* a debug context: driver messages go to the log (lucent_log) */
    bool ignore_env;   /* do not read LUCENT_GL_PLATFORM and LUCENT_GL_DEVICE */
} lucent_gl_desc;

/* What the context runs on. */
typedef struct lucent_gl_info {
    char platform[32];  /* "surfaceless", "device", "window" */
    char device[128];   /* the EGL device's extensions or driver ("" when unknown) */
    char renderer[256]; /* GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" */
    char vendor[128];   /* GL_VENDOR */
    char version[128];  /* GL_VERSION */
    char glsl[64];      /* GL_SHADING_LANGUAGE_VERSION */
    bool software;      /* a CPU rasteriser (llvmpipe, softpipe, swrast) */
} lucent_gl_info;

/* Returns the name of a platform ("auto", "surfaceless", "device", "window"). */
const char *lucent_gl_platform_name(lucent_gl_platform platform);

/* Parses a platform name; LUCENT_ERR_INVALID_ARGUMENT listing the names otherwise. */
lucent_status lucent_gl_platform_parse(const char *name, lucent_gl_platform *dest);

/* Creates an OpenGL 4.5 core context and makes it current on this thread. Fails with
 * LUCENT_ERR_GL and a message naming the cause (no EGL display, no such device, no 4.5 core
 * context, no display for a window) when no such context can be made. desc may be NULL. */
lucent_status lucent_gl_create(const lucent_gl_desc *desc, lucent_gl_context **dest);

/* Destroys the context (NULL is fine). Destroy its renderers first. */
void lucent_gl_destroy(lucent_gl_context *ctx);

/* Makes the context current on the calling thread. */
lucent_status lucent_gl_make_current(lucent_gl_context *ctx);

/* Fills dest with the platform, device and GL strings. */
void lucent_gl_get_info(const lucent_gl_context *ctx, lucent_gl_info *dest);

/* Window contexts: processes window events and returns false once the user closed the window (or
 * pressed Escape or Q); headless contexts return false. */
bool lucent_gl_window_poll(lucent_gl_context *ctx);

/* Window contexts: sets the title (no-op when headless). */
void lucent_gl_window_set_title(lucent_gl_context *ctx, const char *title);

/* Window contexts: the GLFW window (a GLFWwindow *), for a user interface drawn over the frames in
 * the same context (the viewer's Dear ImGui); NULL when headless. */
void *lucent_gl_window_handle(lucent_gl_context *ctx);

/* Window contexts: shows what was drawn (after lucent_render_present_region calls that did not
 * swap); no-op when headless. */
void lucent_gl_window_swap(lucent_gl_context *ctx);

/* ---- The renderer ------------------------------------------------------------------------------ */

typedef struct lucent_renderer lucent_renderer;

/* How to create a renderer; a zero field means the default. */
typedef struct lucent_renderer_desc {
    lucent_pool *pool;         /* CPU preparation: curvature, kernels, sigma0 fits (NULL: serial) */
    const char *cache_dir;     /* where sigma0 fits and slab transmittances are kept between runs
                                   (NULL: in memory only) */
    uint64_t sigma0_photons;   /* sigma0 fit: photons per channel and sphere (0: 40000) */
    uint64_t transmit_photons; /* render.transmittance "slab": photons per channel and thickness
                                   (0: 20000) */
    uint64_t profile_photons;  /* render.profile "mc": photons per channel (0: 200000) */
    uint64_t boundary_photons; /* the boundary's tables: photons per channel and incidence bin (0: 2000) */
    uint64_t sphere_photons;   /* curved parts: photons per channel and sphere (0: 20000) */
    uint64_t sheet_photons;    /* thin parts' sheets: photons per channel and thickness (0: 4000) */
} lucent_renderer_desc;

/* Returns the defaults a zero lucent_renderer_desc stands for. */
lucent_renderer_desc lucent_renderer_defaults(void);

/* Creates a renderer of scene on ctx: uploads the meshes and their normals; everything that depends
 * on the render settings (curvature, kernels and taps, the CDRF LUT, sigma0, transmittance tables,
 * render targets, shader variants) is prepared by the first render that needs it and kept until a
 * setting it depends on changes. The scene must outlive the renderer. */
lucent_status lucent_renderer_create(lucent_gl_context *ctx, const lucent_scene *scene,
                                     const lucent_renderer_desc *desc, lucent_renderer **dest);

/* Frees the renderer and its GL objects (NULL is fine); its context must be current. */
void lucent_renderer_destroy(lucent_renderer *r);

enum { LUCENT_RENDER_MAX_PASSES = 40, LUCENT_RENDER_PASS_NAME_SIZE = 24 };

/* GPU times of one frame, from GL timestamp queries between the passes. */
typedef struct lucent_frame_times {
    int pass_count;
    char pass_name[LUCENT_RENDER_MAX_PASSES][LUCENT_RENDER_PASS_NAME_SIZE]; /* "shadow", "geometry",
                                                  "blur h1", "blur v1", ..., "compose" */
    double pass_ms[LUCENT_RENDER_MAX_PASSES];                               /* GPU milliseconds per pass */
    double gpu_ms;   /* GPU milliseconds from the first pass's start to the last pass's end */
    double cpu_ms;   /* wall-clock milliseconds from the frame's first command to its completion */
    double blur_ms;  /* the blur passes together (ssss; 0 otherwise) */
    double setup_ms; /* CPU milliseconds spent preparing before the frame (curvature, kernels, sigma0
                        fits, tables, targets, shader variants); 0 when everything was cached */
} lucent_frame_times;

/* What lucent_render returns. */
typedef struct lucent_render_result {
    lucent_image *image;      /* RGB linear HDR radiance, settings->width x height */
    lucent_image *mask;       /* 1 channel: 1 where an object covers the pixel's centre (with
                                 render.samples > 1: at least half its samples), else 0 */
    lucent_frame_times times; /* the (first) frame that made the image, its setup included */
    double readback_ms;       /* CPU milliseconds reading the images back */
} lucent_render_result;

/* Renders one frame with settings (NULL: the scene's) and reads it back; with render.samples N > 1, N
 * frames with the camera jittered over the pixel, averaged (docs/render.md). Settings may differ from
 * call to call (method, kernel, taps, size...); only what changed is rebuilt. Free the result with
 * lucent_render_result_free. */
lucent_status lucent_render(lucent_renderer *r, const lucent_render_settings *settings, lucent_render_result *dest);

/* Renders one frame without reading it back (benchmarks, windows); dest may be NULL. */
lucent_status lucent_render_frame(lucent_renderer *r, const lucent_render_settings *settings, lucent_frame_times *dest);

/* Window contexts: shows the last frame, tonemapped with the settings' tonemap and exposure and
 * sRGB-encoded, and swaps buffers. Headless contexts: no-op. */
lucent_status lucent_render_present(lucent_renderer *r);

/* Where lucent_render_present_region puts the last frame. Rectangles are in framebuffer pixels from
 * the window's top-left corner. */
typedef struct lucent_present_desc {
    int x, y, width, height; /* the rectangle the frame fills, texel for pixel when its size is the
                                frame's (width 0: the whole window) */
    int clip[4];             /* x, y, width, height: only this part is drawn (clip[2] 0: all of it) */
    bool clear;              /* clear the whole window first (dark grey) */
    bool swap;               /* swap buffers after */
} lucent_present_desc;

/* Window contexts: draws the last frame, tonemapped and sRGB-encoded as lucent_render_present does,
 * into a rectangle of the window (side by side or split-screen views of several frames, a user
 * interface around them); headless contexts: no-op. */
lucent_status lucent_render_present_region(lucent_renderer *r, const lucent_present_desc *desc);

/* Frees the images of a result and zeroes it. */
void lucent_render_result_free(lucent_render_result *res);

/* Per-object values the last render used. */
typedef struct lucent_render_object_info {
    double albedo[3];          /* the diffuse colour */
    double sigma0[3];          /* CDRF sigma0, mm (0 until a cdrf method was rendered) */
    const char *sigma0_from;   /* "scene", "fit", "fit (cache)", "diffuse" or "" (not yet used) */
    double curvature_range[2]; /* the 5th and 95th percentiles of the vertex mean curvature, mm^-1
                                 (0 until curvature was computed) */
    double kernel_range;       /* ssss: the taps' half-width, mm (0 until ssss was rendered) */
    double transmit_range;     /* translucency: thickness where the transmittance ends, mm */
} lucent_render_object_info;

/* Fills dest with object index's values (0 <= index < the scene's object_count). */
lucent_status lucent_renderer_object_info(const lucent_renderer *r, int index, lucent_render_object_info *dest);

/* ---- Changing the scene under a renderer (the viewer) -----------------------------------------
 * The camera and the objects' albedo, roughness, specular_f0, sss_strength and visible flag are read
 * by every frame. Lights and materials are copied when the renderer is created: after changing them
 * in the scene, say so. */
enum {
    LUCENT_RENDERER_LIGHTS = 1u << 0,   /* light directions, positions, colours, intensities (not their
                                           number or types) */
    LUCENT_RENDERER_MATERIALS = 1u << 1 /* the objects' materials: parts baked for materials that
                                           are still in the scene are kept */
};

/* Re-reads what `what` names from the scene. */
lucent_status lucent_renderer_scene_changed(lucent_renderer *r, unsigned what);

/* Hands the renderer parts baked elsewhere (on another thread) for material m: copied into the
 * renderer's bake of every object whose material equals m, so that frames needing only those parts
 * bake nothing. LUCENT_ERR_NOT_FOUND when no object has that material. */
lucent_status lucent_renderer_adopt_baked(lucent_renderer *r, const lucent_material *m, const lucent_baked *baked);

/* The parts (LUCENT_BAKE_*) a frame of r with settings s bakes for every material: those of
 * s->view.method (all parts for a method that does not say). */
unsigned lucent_renderer_bakes(const lucent_renderer *r, const lucent_render_settings *s);

/* The JSON sidecar of a render (docs/render.md): the scene after overrides, the settings, the GL
 * strings, the timings, each object's albedo, sigma0 and curvature, each kernel's taps. Free *dest
 * with free(). */
lucent_status lucent_render_sidecar(const lucent_renderer *r, const lucent_render_settings *settings,
                                    const lucent_render_result *res, char **dest);

/* ---- The screen-space blur on its own: GPU and CPU reference ----------------------------------
 * The ssss blur of an irradiance image with per-pixel linear depth, as the renderer runs it
 * (Freude Algorithm 4.1): per kernel pass, a horizontal then a vertical 1-D pass of the taps; tap
 * k of the material m under pixel p is read at p + o_k s / z_p pixels along the pass's axis (o_k in
 * mm, s = width_scale * pixel_scale, z_p the pixel's depth in mm) by linear interpolation between
 * the two nearest pixels; each of the two is weighted by the depth filter against the centre's
 * depth; passes are summed with their signs (rank-N models). Pixels of depth 0 are background:
 * they keep their input and give no samples. Borders clamp. */
typedef struct lucent_ssss_blur_desc {
    const lucent_taps *const *taps; /* material_count tap sets, same count and rank */
    int material_count;             /* 1..8 */
    double pixel_scale;             /* pixels per mm at 1 mm depth: height / (2 tan(fov_y / 2)) */
    double width_scale;             /* artist's multiplier (0: 1) */
    lucent_depth_filter filter;
} lucent_ssss_blur_desc;

/* CPU reference. irradiance: RGB or RGBA (alpha ignored); depth: 1 channel, mm; material: one index
 * per pixel (NULL: all 0); dest: RGB, same size (created by the caller). */
lucent_status lucent_ssss_blur_cpu(const lucent_image *irradiance, const lucent_image *depth, const uint8_t *material,
                                   const lucent_ssss_blur_desc *desc, lucent_pool *pool, lucent_image *dest);

/* The same with the renderer's blur shader on ctx (float32 targets). */
lucent_status lucent_ssss_blur_gl(lucent_gl_context *ctx, const lucent_image *irradiance, const lucent_image *depth,
                                  const uint8_t *material, const lucent_ssss_blur_desc *desc, lucent_image *dest);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_RENDER_H */
