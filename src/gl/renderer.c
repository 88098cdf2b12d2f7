/* lucent_renderer: a scene on a GL context, rendered with any method and settings, frame after
 * frame, preparing only what changed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/renderer_internal.h"

lucent_renderer_desc lucent_renderer_defaults(void)
{
    return (lucent_renderer_desc){.sigma0_photons = 40000, .profile_photons = 200000};
}

static lucent_status create_programs(lucent_renderer *r)
{
    lucent_status s = gl_program_build(gl_embedded_source, NULL, "shadow.vert.glsl", "shadow.frag.glsl", NULL,
                                       &r->shadow_program);
    if (s == LUCENT_OK)
        s = gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "compose.frag.glsl", NULL,
                             &r->compose_program);
    if (s == LUCENT_OK) s = gl_blur_init(&r->blur);
    glCreateVertexArrays(1, &r->empty_vao);
    glCreateBuffers(1, &r->frame_ubo);
    glNamedBufferData(r->frame_ubo, sizeof(gl_frame_block), NULL, GL_DYNAMIC_DRAW);
    r->dummy_tex = gl_texture(GL_RGBA32F, 1, 1, GL_NEAREST);
    glClearTexImage(r->dummy_tex, 0, GL_RGBA, GL_FLOAT, (const float[4]){0, 0, 0, 0});
    return s == LUCENT_OK ? gl_check("creating the renderer") : s;
}

static lucent_status create(lucent_renderer *r)
{
    lucent_status s = gl_meshes_upload(r);
    if (s == LUCENT_OK) s = gl_materials_collect(r);
    if (s == LUCENT_OK) s = gl_lights_setup(r);
    if (s == LUCENT_OK) s = create_programs(r);
    return s;
}

lucent_status lucent_renderer_create(lucent_gl_context *ctx, const lucent_scene *scene, const lucent_renderer_desc *desc,
                                     lucent_renderer **dest)
{
    *dest = NULL;
    lucent_status s = lucent_gl_make_current(ctx);
    if (s != LUCENT_OK) return s;
    lucent_renderer *r = calloc(1, sizeof *r);
    if (!r) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    r->ctx = ctx, r->scene = scene, r->lut_variant = -1;
    r->lut_sigma_max = lucent_cdrf_lut_defaults().sigma_max;
    r->desc = desc ? *desc : lucent_renderer_defaults();
    s = create(r);
    if (s != LUCENT_OK) {
        lucent_error_context(s, "%s", scene->path[0] ? scene->path : scene->name);
        lucent_renderer_destroy(r);
        return s;
    }
    *dest = r;
    return LUCENT_OK;
}

void lucent_renderer_destroy(lucent_renderer *r)
{
    if (!r) return;
    lucent_gl_make_current(r->ctx);
    gl_frame_free(r);
    gl_shadows_free(r);
    gl_blur_free(&r->blur);
    gl_timer_free(&r->timer);
    gl_meshes_free(r);
    gl_materials_free(r);
    GLuint tex[3] = {r->lut_tex, r->transmit_tex, r->dummy_tex};
    glDeleteTextures(3, tex);
    GLuint programs[3] = {r->compose_program, r->present_program, r->shadow_program};
    for (int i = 0; i < 3; i++)
        if (programs[i]) glDeleteProgram(programs[i]);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    if (r->frame_ubo) glDeleteBuffers(1, &r->frame_ubo);
    free(r);
}

static lucent_status frame(lucent_renderer *r, const lucent_render_settings *settings, lucent_frame_times *times)
{
    const lucent_render_settings *s = settings ? settings : &r->scene->render;
    lucent_status st = gl_settings_check(s);
    if (st == LUCENT_OK) st = lucent_gl_make_current(r->ctx);
    double t0 = lucent_clock_ms();
    if (st == LUCENT_OK) st = gl_prepare(r, s);
    double setup = lucent_clock_ms() - t0;
    if (st == LUCENT_OK) st = gl_frame_draw(r, s, times);
    times->setup_ms = setup;
    if (st != LUCENT_OK) return lucent_error_context(st, "%s", r->scene->path[0] ? r->scene->path : r->scene->name);
    r->last = *s;
    r->last_times = *times;
    r->have_frame = true;
    return LUCENT_OK;
}

lucent_status lucent_render_frame(lucent_renderer *r, const lucent_render_settings *settings, lucent_frame_times *dest)
{
    lucent_frame_times t;
    return frame(r, settings, dest ? dest : &t);
}

/* The final target's rgb as the image, its alpha (coverage) as the mask. */
static lucent_status read_back(lucent_renderer *r, lucent_render_result *res)
{
    lucent_image *rgba = NULL;
    lucent_status s = gl_read_image(r->fbo_final, 0, r->width, r->height, 4, true, &rgba);
    if (s == LUCENT_OK) s = lucent_image_convert_channels(rgba, 3, &res->image);
    if (s == LUCENT_OK) s = lucent_image_create(r->width, r->height, 1, &res->mask);
    size_t n = (size_t)r->width * (size_t)r->height;
    for (size_t i = 0; s == LUCENT_OK && i < n; i++) res->mask->data[i] = rgba->data[4 * i + 3] > 0.5f ? 1.0f : 0.0f;
    lucent_image_destroy(rgba);
    return s;
}

lucent_status lucent_render(lucent_renderer *r, const lucent_render_settings *settings, lucent_render_result *dest)
{
    memset(dest, 0, sizeof *dest);
    lucent_status s = frame(r, settings, &dest->times);
    double t0 = lucent_clock_ms();
    if (s == LUCENT_OK) s = read_back(r, dest);
    dest->readback_ms = lucent_clock_ms() - t0;
    if (s != LUCENT_OK) lucent_render_result_free(dest);
    return s;
}

void lucent_render_result_free(lucent_render_result *res)
{
    if (!res) return;
    lucent_image_destroy(res->image);
    lucent_image_destroy(res->mask);
    memset(res, 0, sizeof *res);
}

lucent_status lucent_renderer_object_info(const lucent_renderer *r, int index, lucent_render_object_info *dest)
{
    if (index < 0 || index >= r->scene->object_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "object %d of %d", index, r->scene->object_count);
    const gl_mesh *g = &r->meshes[index];
    const gl_material *m = &r->materials[g->material];
    memset(dest, 0, sizeof *dest);
    memcpy(dest->albedo, r->scene->objects[index].albedo, sizeof dest->albedo);
    memcpy(dest->sigma0, g->sigma0, sizeof dest->sigma0);
    dest->sigma0_from = g->sigma0_from;
    memcpy(dest->curvature_range, g->curvature_range, sizeof dest->curvature_range);
    dest->kernel_range = m->taps ? gl_taps_radius(m->taps, 1) : 0;
    dest->transmit_range = m->transmit_range;
    return LUCENT_OK;
}

/* ---- tests ---- */

void gl_renderer_set_aov(lucent_renderer *r, bool on)
{
    if (r->aov == on) return;
    lucent_gl_make_current(r->ctx);
    for (int i = 0; i < r->program_count; i++) glDeleteProgram(r->programs[i].program);
    r->program_count = 0; /* rebuilt with (or without) the auxiliary outputs */
    r->aov = on;
}

lucent_status gl_renderer_read_aov(lucent_renderer *r, int which, lucent_image **dest)
{
    if (!r->aov || which < 0 || which > 2 || !r->have_frame)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "no auxiliary output %d", which);
    return gl_read_image(r->fbo_scene, 3 + which, r->width, r->height, 4, true, dest);
}
