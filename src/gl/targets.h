/* The frame's render targets: the scene pass writes diffuse (rgb, a: blur strength), specular and
 * linear depth (x: mm, 0 = background; y: material) with a z-buffer (Freude 4.2, pass 1); the
 * final target holds the composed radiance (a: coverage). With aov, three more scene outputs for
 * the tests (normal + curvature, position + object, light 0's visibility and thickness). */
#ifndef LUCENT_SRC_GL_TARGETS_H
#define LUCENT_SRC_GL_TARGETS_H

#include "gl/core/gpu.h"

typedef struct gl_targets {
    int width, height;
    bool aov;
    GLuint diffuse, specular, depth, zbuffer, final, aov_tex[3];
    GLuint fbo_scene, fbo_final;
} gl_targets;

/* (Re)creates the targets for width x height (with the auxiliary outputs when aov); no-op when
 * nothing changed. */
lucent_status gl_targets_resize(gl_targets *t, int width, int height, bool aov);

/* Number of colour outputs of the scene pass (3, or 6 with the auxiliary outputs). */
int gl_targets_scene_outputs(const gl_targets *t);

void gl_targets_free(gl_targets *t);

#endif
