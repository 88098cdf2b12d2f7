/* Small GL helpers shared by the renderer and the standalone blur: textures, framebuffers, timer
 * queries, and the separable blur passes. Internal: GL types stay inside src/gl. */
#ifndef LUCENT_SRC_GL_GPU_H
#define LUCENT_SRC_GL_GPU_H

#include <epoxy/gl.h>

#include "gl/context_internal.h"
#include "gl/shader.h"
#include "lucent/render.h"

/* ---- textures and framebuffers ---- */

/* A 2-D texture of the given format, clamped to the edge, with filter (GL_NEAREST, GL_LINEAR). */
GLuint gl_texture(GLenum internal_format, int width, int height, GLenum filter);

/* Uploads img (1, 3 or 4 channels) into a new float texture (R32F, RGB32F, RGBA32F); row 0 of the
 * image becomes texture row 0 (t = 0). */
lucent_status gl_texture_from_image(const lucent_image *img, GLenum filter, GLuint *dest);

/* A framebuffer with count colour attachments (draw buffers 0..count-1) and an optional depth
 * texture; fails (LUCENT_ERR_GL) naming `what` when incomplete. */
lucent_status gl_framebuffer(int count, const GLuint *colors, GLuint depth, const char *what, GLuint *dest);

/* Reads colour attachment `attachment` of fbo (RGBA float) into a new image of `channels` (1: the
 * first component, 3: rgb, 4: rgba); flip: GL's bottom row becomes the image's last (rendered
 * frames), else texture row 0 becomes image row 0 (textures uploaded from images). */
lucent_status gl_read_image(GLuint fbo, int attachment, int width, int height, int channels, bool flip,
                            lucent_image **dest);

/* ---- timer queries ---- */

typedef struct gl_timer {
    GLuint queries[LUCENT_RENDER_MAX_PASSES + 1];
    char names[LUCENT_RENDER_MAX_PASSES][LUCENT_RENDER_PASS_NAME_SIZE];
    int count;
    bool created;
    double cpu_start;
} gl_timer;

/* Starts a frame: a timestamp before the first pass. */
void gl_timer_begin(gl_timer *t);
/* Ends pass `name` (a timestamp after it). Passes beyond LUCENT_RENDER_MAX_PASSES are merged into
 * the last one. */
void gl_timer_mark(gl_timer *t, const char *name);
/* Waits for the frame (glFinish) and fills dest (blur_ms: passes named "blur ..."). */
void gl_timer_end(gl_timer *t, lucent_frame_times *dest);
void gl_timer_free(gl_timer *t);

/* ---- the separable blur (blur.frag.glsl) ---- */

typedef struct gl_blur {
    GLuint program, vao;
    GLint loc_axis, loc_pass, loc_rank, loc_count, loc_vertical, loc_scale, loc_filter;
    GLuint taps_tex;
    int count, rank;
    GLuint tmp_tex, tmp_fbo, sum_tex, sum_fbo; /* sum_tex: the result */
    int width, height;
} gl_blur;

/* Compiles the blur program (embedded sources). */
lucent_status gl_blur_init(gl_blur *b);

/* Uploads the tap sets of `count` materials (same count and rank) with each one's depth-filter
 * radius R = width_scale x max |offset|. */
lucent_status gl_blur_set_taps(gl_blur *b, const lucent_taps *const *taps, int count, double width_scale);

/* (Re)creates the RGBA32F intermediate and result targets for width x height. */
lucent_status gl_blur_resize(gl_blur *b, int width, int height);

/* Runs every kernel pass (horizontal then vertical) on source (rgb) with depth (x: mm, y: material);
 * the result is in b->sum_tex. scale: pixels per mm at 1 mm times width_scale. timer may be NULL. */
void gl_blur_run(gl_blur *b, GLuint source, GLuint depth, double scale, lucent_depth_filter filter, gl_timer *timer);

void gl_blur_free(gl_blur *b);

/* Checks the arguments of lucent_ssss_blur_cpu / _gl; messages name what is wrong. */
lucent_status gl_blur_check_args(const lucent_image *irradiance, const lucent_image *depth, const uint8_t *material,
                                 const lucent_ssss_blur_desc *desc, const lucent_image *dest);

/* The depth-filter radius R (mm) of a tap set: width_scale x its largest |offset|. */
double gl_taps_radius(const lucent_taps *t, double width_scale);

#endif
