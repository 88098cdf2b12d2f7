/* The frame's render targets (targets.h). */
#include <string.h>

#include "gl/targets.h"

void gl_targets_free(gl_targets *t)
{
    GLuint tex[8] = {t->diffuse, t->specular,   t->depth,      t->zbuffer,
                     t->final,   t->aov_tex[0], t->aov_tex[1], t->aov_tex[2]};
    glDeleteTextures(8, tex);
    GLuint fbo[2] = {t->fbo_scene, t->fbo_final};
    glDeleteFramebuffers(2, fbo);
    memset(t, 0, sizeof *t);
}

int gl_targets_scene_outputs(const gl_targets *t) { return t->aov ? 6 : 3; }

lucent_status gl_targets_resize(gl_targets *t, int width, int height, bool aov)
{
    if (t->fbo_scene && t->width == width && t->height == height && t->aov == aov) return LUCENT_OK;
    gl_targets_free(t);
    t->width = width, t->height = height, t->aov = aov;
    t->diffuse = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    t->specular = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    t->depth = gl_texture(GL_RG32F, width, height, GL_NEAREST);
    t->zbuffer = gl_texture(GL_DEPTH_COMPONENT32F, width, height, GL_NEAREST);
    t->final = gl_texture(GL_RGBA32F, width, height, GL_LINEAR);
    for (int i = 0; aov && i < 3; i++) t->aov_tex[i] = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    GLuint colors[6] = {t->diffuse, t->specular, t->depth, t->aov_tex[0], t->aov_tex[1], t->aov_tex[2]};
    lucent_status s =
        gl_framebuffer(gl_targets_scene_outputs(t), colors, t->zbuffer, "the scene targets", &t->fbo_scene);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &t->final, 0, "the final target", &t->fbo_final);
    return s;
}
