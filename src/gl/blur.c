/* The separable subsurface-scattering blur on the GPU (blur.frag.glsl): a horizontal and a vertical
 * 1-D pass per kernel rank, summed into one target (Freude Eq. 4.3). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/blur.h"
#include "gl/reference/reference.h"

lucent_status gl_blur_init(gl_blur *b)
{
    memset(b, 0, sizeof *b);
    lucent_status s =
        gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "blur.frag.glsl", NULL, &b->program);
    if (s != LUCENT_OK) return s;
    b->loc_axis = glGetUniformLocation(b->program, "u_axis");
    b->loc_pass = glGetUniformLocation(b->program, "u_pass");
    b->loc_rank = glGetUniformLocation(b->program, "u_rank");
    b->loc_count = glGetUniformLocation(b->program, "u_count");
    b->loc_vertical = glGetUniformLocation(b->program, "u_vertical");
    b->loc_scale = glGetUniformLocation(b->program, "u_scale");
    b->loc_filter = glGetUniformLocation(b->program, "u_filter");
    glCreateVertexArrays(1, &b->vao);
    return gl_check("the blur program");
}

double gl_taps_radius(const lucent_taps *t, double width_scale)
{
    return (width_scale > 0 ? width_scale : 1) * fmax(lucent_taps_radius(t), 1e-6);
}

/* One texel row per (material, pass): count taps (rgb weight, offset mm), then (R, positive), then
 * the pass's signs. */
static void fill_row(const lucent_taps *t, int pass, double radius, float *row)
{
    bool positive = true;
    for (int k = 0; k < t->count; k++) {
        for (int c = 0; c < 3; c++) {
            row[4 * k + c] = (float)t->weight[c][pass * t->count + k];
            positive &= t->weight[c][pass * t->count + k] >= 0;
        }
        row[4 * k + 3] = (float)t->offset[k];
    }
    float *meta = row + 4 * t->count;
    meta[0] = (float)radius, meta[1] = positive ? 1.0f : 0.0f, meta[2] = meta[3] = 0;
    for (int c = 0; c < 3; c++) meta[4 + c] = (float)t->sign[c][pass];
    meta[7] = 0;
}

lucent_status gl_blur_set_taps(gl_blur *b, const lucent_taps *const *taps, int count, double width_scale)
{
    int n = taps[0]->count, rank = taps[0]->rank, w = n + 2, h = count * rank;
    for (int m = 1; m < count; m++)
        if (taps[m]->count != n || taps[m]->rank != rank)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "blur: tap set %d has %d taps x rank %d, set 0 %d x %d", m,
                                taps[m]->count, taps[m]->rank, n, rank);
    float *texels = calloc((size_t)w * (size_t)h * 4, sizeof *texels);
    if (!texels) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int m = 0; m < count; m++)
        for (int p = 0; p < rank; p++)
            fill_row(taps[m], p, gl_taps_radius(taps[m], width_scale), texels + (size_t)(m * rank + p) * (size_t)w * 4);
    if (b->taps_tex) glDeleteTextures(1, &b->taps_tex);
    b->taps_tex = gl_texture(GL_RGBA32F, w, h, GL_NEAREST);
    glTextureSubImage2D(b->taps_tex, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels);
    free(texels);
    b->count = n, b->rank = rank;
    return gl_check("uploading the blur taps");
}

static void free_targets(gl_blur *b)
{
    GLuint fbo[2] = {b->tmp_fbo, b->sum_fbo}, tex[2] = {b->tmp_tex, b->sum_tex};
    glDeleteFramebuffers(2, fbo);
    glDeleteTextures(2, tex);
    b->tmp_fbo = b->sum_fbo = b->tmp_tex = b->sum_tex = 0;
}

lucent_status gl_blur_resize(gl_blur *b, int width, int height)
{
    if (b->width == width && b->height == height && b->sum_fbo) return LUCENT_OK;
    free_targets(b);
    b->width = width, b->height = height;
    b->tmp_tex = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    b->sum_tex = gl_texture(GL_RGBA32F, width, height, GL_NEAREST);
    lucent_status s = gl_framebuffer(1, &b->tmp_tex, 0, "the blur's intermediate target", &b->tmp_fbo);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &b->sum_tex, 0, "the blur's result target", &b->sum_fbo);
    return s;
}

static void one_pass(gl_blur *b, GLuint source, int pass, bool vertical)
{
    glBindTextureUnit(0, source);
    glUniform2i(b->loc_axis, vertical ? 0 : 1, vertical ? 1 : 0);
    glUniform1i(b->loc_pass, pass);
    glUniform1i(b->loc_vertical, vertical ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void gl_blur_run(gl_blur *b, GLuint source, GLuint depth, double scale, lucent_depth_filter filter, gl_timer *timer)
{
    glUseProgram(b->program);
    glBindVertexArray(b->vao);
    glBindTextureUnit(1, depth);
    glBindTextureUnit(2, b->taps_tex);
    glUniform1i(b->loc_rank, b->rank);
    glUniform1i(b->loc_count, b->count);
    glUniform1f(b->loc_scale, (float)scale);
    glUniform1i(b->loc_filter, (int)filter);
    glViewport(0, 0, b->width, b->height);
    glDisable(GL_DEPTH_TEST);
    glClearNamedFramebufferfv(b->sum_fbo, GL_COLOR, 0, (const float[4]){0, 0, 0, 0});
    glBlendFunc(GL_ONE, GL_ONE);
    for (int p = 0; p < b->rank; p++) {
        char name[LUCENT_RENDER_PASS_NAME_SIZE];
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->tmp_fbo);
        one_pass(b, source, p, false);
        snprintf(name, sizeof name, "blur h%d", p + 1);
        if (timer) gl_timer_mark(timer, name);
        glEnable(GL_BLEND); /* passes add up (rank-N models) */
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, b->sum_fbo);
        one_pass(b, b->tmp_tex, p, true);
        snprintf(name, sizeof name, "blur v%d", p + 1);
        if (timer) gl_timer_mark(timer, name);
    }
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

void gl_blur_free(gl_blur *b)
{
    free_targets(b);
    if (b->taps_tex) glDeleteTextures(1, &b->taps_tex);
    if (b->vao) glDeleteVertexArrays(1, &b->vao);
    if (b->program) glDeleteProgram(b->program);
    memset(b, 0, sizeof *b);
}

/* ---- lucent_ssss_blur_gl: the blur shader run on images given by the caller (the GPU side of the
 * blur test, and a tool for anyone who wants the blur alone) ---- */

/* RG32F texture: x depth (mm), y material index; image row 0 at texture row 0. */
static lucent_status depth_texture(const lucent_image *depth, const uint8_t *material, GLuint *dest)
{
    size_t n = (size_t)depth->width * (size_t)depth->height;
    float *rg = malloc(2 * n * sizeof *rg);
    if (!rg) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; i < n; i++) rg[2 * i] = depth->data[i], rg[2 * i + 1] = material ? (float)material[i] : 0.0f;
    *dest = gl_texture(GL_RG32F, depth->width, depth->height, GL_NEAREST);
    glTextureSubImage2D(*dest, 0, 0, 0, depth->width, depth->height, GL_RG, GL_FLOAT, rg);
    free(rg);
    return gl_check("uploading the depth");
}

static void copy_rgb(const lucent_image *src, lucent_image *dest)
{
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            dest->data[i * (size_t)dest->channels + (size_t)c] = src->data[i * (size_t)src->channels + (size_t)c];
}

lucent_status lucent_ssss_blur_gl(lucent_gl_context *ctx, const lucent_image *irradiance, const lucent_image *depth,
                                  const uint8_t *material, const lucent_ssss_blur_desc *desc, lucent_image *dest)
{
    lucent_status s = gl_blur_check_args(irradiance, depth, material, desc, dest);
    if (s == LUCENT_OK) s = lucent_gl_make_current(ctx);
    if (s != LUCENT_OK) return s;
    gl_blur b;
    GLuint src = 0, z = 0;
    lucent_image *out = NULL;
    double ws = desc->width_scale > 0 ? desc->width_scale : 1;
    s = gl_blur_init(&b);
    if (s == LUCENT_OK) s = gl_blur_set_taps(&b, desc->taps, desc->material_count, ws);
    if (s == LUCENT_OK) s = gl_blur_resize(&b, irradiance->width, irradiance->height);
    if (s == LUCENT_OK) s = gl_texture_from_image(irradiance, GL_NEAREST, &src);
    if (s == LUCENT_OK) s = depth_texture(depth, material, &z);
    if (s == LUCENT_OK) {
        gl_blur_run(&b, src, z, desc->pixel_scale * ws, desc->filter, NULL);
        s = gl_read_image(b.sum_fbo, 0, b.width, b.height, 3, false, &out);
    }
    if (s == LUCENT_OK) copy_rgb(out, dest);
    lucent_image_destroy(out);
    glDeleteTextures(1, &src);
    glDeleteTextures(1, &z);
    gl_blur_free(&b);
    return s;
}
