/* The renderer core's GL helpers: textures, framebuffers, read-back, GPU timer queries, a clock.
 * Internal: GL types stay inside src/gl. */
#ifndef LUCENT_SRC_GL_CORE_GPU_H
#define LUCENT_SRC_GL_CORE_GPU_H

#include <epoxy/gl.h>

#include "gl/core/context_internal.h"
#include "gl/core/shader.h"
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

#endif
