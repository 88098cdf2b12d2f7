/* Light between surfaces: the reflective shadow maps (bounce.h). */
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "gl/bounce.h"

static void free_maps(gl_bounce *b)
{
    GLuint tex[4] = {b->position, b->normal, b->flux, b->depth};
    glDeleteTextures(4, tex);
    if (b->fbo) glDeleteFramebuffers(1, &b->fbo);
    if (b->surfels) glDeleteBuffers(1, &b->surfels);
    free(b->texels);
    free(b->list);
    b->texels = b->list = NULL;
    b->position = b->normal = b->flux = b->depth = b->fbo = b->surfels = 0;
    b->size = b->layers = b->count = 0;
}

static GLuint layers_texture(GLenum format, int size, int layers)
{
    GLuint t;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
    glTextureStorage3D(t, 1, format, size, size, layers);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

lucent_status gl_bounce_resize(gl_bounce *b, int layers, int size)
{
    if (size <= 0 || layers <= 0) {
        free_maps(b);
        return LUCENT_OK;
    }
    if (b->fbo && b->size == size && b->layers == layers) return LUCENT_OK;
    free_maps(b);
    if (!b->program) {
        lucent_status s =
            gl_program_build(gl_embedded_source, NULL, "shadow.vert.glsl", "bounce.frag.glsl", NULL, &b->program);
        if (s != LUCENT_OK) return s;
    }
    size_t floats = (size_t)size * size * layers * 12;
    b->texels = malloc(floats * sizeof *b->texels);
    b->list = malloc(floats * sizeof *b->list);
    if (!b->texels || !b->list) {
        free_maps(b);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "render.bounce %d: out of memory for %d maps", size, layers);
    }
    glCreateBuffers(1, &b->surfels);
    glNamedBufferData(b->surfels, (GLsizeiptr)(floats * sizeof *b->list), NULL, GL_DYNAMIC_DRAW);
    b->position = layers_texture(GL_RGBA32F, size, layers);
    b->normal = layers_texture(GL_RGBA32F, size, layers);
    b->flux = layers_texture(GL_RGBA32F, size, layers);
    b->depth = layers_texture(GL_DEPTH_COMPONENT32F, size, layers);
    glCreateFramebuffers(1, &b->fbo);
    static const GLenum outputs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(b->fbo, 3, outputs);
    b->size = size, b->layers = layers;
    return gl_check("creating the bounce maps");
}

bool gl_bounce_begin(gl_bounce *b, const gl_bounce_light *light)
{
    if (!b->fbo || light->layer < 0) return false;
    GLuint tex[3] = {b->position, b->normal, b->flux};
    for (int k = 0; k < 3; k++)
        glNamedFramebufferTextureLayer(b->fbo, GL_COLOR_ATTACHMENT0 + k, tex[k], 0, light->layer);
    glNamedFramebufferTextureLayer(b->fbo, GL_DEPTH_ATTACHMENT, b->depth, 0, light->layer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->fbo);
    glViewport(0, 0, b->size, b->size);
    for (int k = 0; k < 3; k++) glClearNamedFramebufferfv(b->fbo, GL_COLOR, k, (const float[4]){0});
    glClearNamedFramebufferfv(b->fbo, GL_DEPTH, 0, (const float[1]){1});
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glUseProgram(b->program);
    float m[16];
    lucent_mat4_to_float(light->matrix, m);
    glUniformMatrix4fv(glGetUniformLocation(b->program, "u_light_mvp"), 1, GL_FALSE, m);
    glUniform1i(glGetUniformLocation(b->program, "u_light"), light->index);
    glUniform1f(glGetUniformLocation(b->program, "u_texel"), (float)(light->texel / b->size));
    glUniform1f(glGetUniformLocation(b->program, "u_centre_distance"), (float)light->distance);
    return true;
}

void gl_bounce_object(const gl_bounce *b, const double albedo[3])
{
    glUniform3f(glGetUniformLocation(b->program, "u_albedo"), (float)albedo[0], (float)albedo[1], (float)albedo[2]);
}

lucent_status gl_bounce_end(gl_bounce *b)
{
    glDisable(GL_DEPTH_TEST);
    size_t texels = (size_t)b->size * b->size * b->layers, bytes = texels * 4 * sizeof(float);
    GLuint tex[3] = {b->position, b->normal, b->flux};
    for (int k = 0; k < 3; k++)
        glGetTextureImage(tex[k], 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, b->texels + k * texels * 4);
    b->count = 0;
    for (size_t t = 0; t < texels; t++) {
        const float *p = b->texels + t * 4, *f = b->texels + (2 * texels + t) * 4;
        if (!(p[3] > 0) || !(f[0] + f[1] + f[2] > 0)) continue; /* no surface, or one that sends nothing */
        float *d = b->list + (size_t)b->count++ * 12;
        for (int k = 0; k < 3; k++) memcpy(d + 4 * k, b->texels + (k * texels + t) * 4, 4 * sizeof *d);
    }
    if (b->count) glNamedBufferSubData(b->surfels, 0, (GLsizeiptr)((size_t)b->count * 12 * sizeof *b->list), b->list);
    return gl_check("listing the bounce surfels");
}

void gl_bounce_bind(const gl_bounce *b)
{
    if (b->surfels) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GL_BOUNCE_BINDING, b->surfels);
}

void gl_bounce_free(gl_bounce *b)
{
    free_maps(b);
    if (b->program) glDeleteProgram(b->program);
    memset(b, 0, sizeof *b);
}
