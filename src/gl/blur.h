/* The separable subsurface-scattering blur on the GPU (blur.frag.glsl; Freude Algorithm 4.1): a
 * horizontal and a vertical 1-D pass per kernel rank, summed into one target (Freude Eq. 4.3). Used
 * by the ssss method and by lucent_ssss_blur_gl. Its CPU reference is reference/blur_cpu.c. */
#ifndef LUCENT_SRC_GL_BLUR_H
#define LUCENT_SRC_GL_BLUR_H

#include "gl/core/gpu.h"

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

/* The depth-filter radius R (mm) of a tap set: width_scale x its largest |offset|. */
double gl_taps_radius(const lucent_taps *t, double width_scale);

#endif
