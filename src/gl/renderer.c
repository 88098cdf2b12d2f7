/* lucent_renderer: a scene on a GL context, rendered with any method and settings, frame after
 * frame, preparing only what changed. The core: creates the parts, runs frames (frame.c), reads
 * them back. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "gl/methods/method.h"

lucent_renderer_desc lucent_renderer_defaults(void)
{
    return (lucent_renderer_desc){.sigma0_photons = LUCENT_BAKE_SIGMA0_PHOTONS,
                                  .transmit_photons = LUCENT_BAKE_TRANSMIT_PHOTONS,
                                  .boundary_photons = LUCENT_BAKE_BOUNDARY_PHOTONS,
                                  .sphere_photons = LUCENT_BAKE_SPHERE_PHOTONS,
                                  .sheet_photons = LUCENT_BAKE_SHEET_PHOTONS,
                                  .profile_photons = LUCENT_BAKE_PROFILE_PHOTONS};
}

lucent_bake_desc gl_renderer_bake_desc(const lucent_renderer *r, const lucent_render_settings *s, unsigned what)
{
    return (lucent_bake_desc){.what = what,
                              .settings = s,
                              .profile_photons = r->desc.profile_photons,
                              .transmit_photons = r->desc.transmit_photons,
                              .sigma0_photons = r->desc.sigma0_photons,
                              .boundary_photons = r->desc.boundary_photons,
                              .sphere_photons = r->desc.sphere_photons,
                              .sheet_photons = r->desc.sheet_photons,
                              .pool = r->desc.pool};
}

void gl_renderer_object_albedo(const lucent_renderer *r, int object, double dest[3])
{
    const lucent_scene_object *o = &r->scene->objects[object];
    const lucent_baked *b = gl_tables_of(&r->tables, object);
    bool mc = o->albedo_source == LUCENT_ALBEDO_FROM_MATERIAL && (b->have & LUCENT_BAKE_BOUNDARY);
    memcpy(dest, mc ? b->boundary_albedo : o->albedo, 3 * sizeof *dest);
}

void gl_renderer_view_proj(const lucent_renderer *r, double dest[16])
{
    const lucent_camera *cam = &r->scene->camera;
    double view[16], proj[16], w = r->targets.width, h = r->targets.height;
    lucent_camera_view(cam, view);
    lucent_camera_projection(cam, w / h, proj);
    for (int c = 0; c < 4; c++) { /* clip x += (2 jx / w) clip w: the image moves jx pixels */
        proj[4 * c] += 2 * r->jitter[0] / w * proj[4 * c + 3];
        proj[4 * c + 1] += 2 * r->jitter[1] / h * proj[4 * c + 3];
    }
    lucent_mat4_mul(proj, view, dest);
}

void gl_renderer_draw_objects(const lucent_renderer *r)
{
    for (int i = 0; i < r->scene->object_count; i++)
        if (r->scene->objects[i].visible) gl_meshes_draw(&r->meshes, i);
}

static lucent_status create_objects(lucent_renderer *r)
{
    glCreateVertexArrays(1, &r->empty_vao);
    glCreateBuffers(1, &r->frame_ubo);
    glNamedBufferData(r->frame_ubo, sizeof(gl_frame_block), NULL, GL_DYNAMIC_DRAW);
    r->dummy_tex = gl_texture(GL_RGBA32F, 1, 1, GL_NEAREST);
    glClearTexImage(r->dummy_tex, 0, GL_RGBA, GL_FLOAT, (const float[4]){0, 0, 0, 0});
    lucent_status s = gl_program_build(gl_embedded_source, NULL, "fullscreen.vert.glsl", "compose.frag.glsl", NULL,
                                       &r->compose_program);
    return s == LUCENT_OK ? gl_check("creating the renderer") : s;
}

static lucent_status create(lucent_renderer *r)
{
    lucent_status s =
        r->desc.cache_dir && r->desc.cache_dir[0] ? lucent_cache_create(r->desc.cache_dir, &r->cache) : LUCENT_OK;
    if (s == LUCENT_OK) s = gl_meshes_upload(&r->meshes, r->scene);
    if (s == LUCENT_OK) s = gl_tables_collect(&r->tables, r->scene);
    if (s == LUCENT_OK) s = gl_shadows_setup(&r->shadows, r->scene);
    if (s == LUCENT_OK) s = create_objects(r);
    return s;
}

/* The desc with its zeros resolved. */
static lucent_renderer_desc resolve(const lucent_renderer_desc *d)
{
    lucent_renderer_desc r = d ? *d : (lucent_renderer_desc){0}, def = lucent_renderer_defaults();
    if (!r.sigma0_photons) r.sigma0_photons = def.sigma0_photons;
    if (!r.transmit_photons) r.transmit_photons = def.transmit_photons;
    if (!r.boundary_photons) r.boundary_photons = def.boundary_photons;
    if (!r.sphere_photons) r.sphere_photons = def.sphere_photons;
    if (!r.sheet_photons) r.sheet_photons = def.sheet_photons;
    if (!r.profile_photons) r.profile_photons = def.profile_photons;
    return r;
}

lucent_status lucent_renderer_create(lucent_gl_context *ctx, const lucent_scene *scene,
                                     const lucent_renderer_desc *desc, lucent_renderer **dest)
{
    *dest = NULL;
    lucent_status s = lucent_gl_make_current(ctx);
    if (s != LUCENT_OK) return s;
    lucent_renderer *r = calloc(1, sizeof *r);
    if (!r) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    r->ctx = ctx, r->scene = scene, r->desc = resolve(desc);
    s = create(r);
    if (s != LUCENT_OK) {
        lucent_error_context(s, "%s", scene->path[0] ? scene->path : scene->name);
        lucent_renderer_destroy(r);
        return s;
    }
    *dest = r;
    return LUCENT_OK;
}

static void release_methods(lucent_renderer *r)
{
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++) {
        if (r->state[m] && gl_methods[m]->release) gl_methods[m]->release(r->state[m]);
        free(r->state[m]);
        r->state[m] = NULL;
    }
}

void lucent_renderer_destroy(lucent_renderer *r)
{
    if (!r) return;
    lucent_gl_make_current(r->ctx);
    release_methods(r);
    gl_programs_free(&r->programs);
    gl_targets_free(&r->targets);
    gl_shadows_free(&r->shadows);
    gl_bounce_free(&r->bounce);
    gl_timer_free(&r->timer);
    gl_meshes_free(&r->meshes);
    gl_tables_free(&r->tables);
    if (r->dummy_tex) glDeleteTextures(1, &r->dummy_tex);
    if (r->compose_program) glDeleteProgram(r->compose_program);
    if (r->present_program) glDeleteProgram(r->present_program);
    if (r->empty_vao) glDeleteVertexArrays(1, &r->empty_vao);
    if (r->frame_ubo) glDeleteBuffers(1, &r->frame_ubo);
    lucent_cache_destroy(r->cache);
    free(r);
}

static lucent_status frame(lucent_renderer *r, const lucent_render_settings *settings, lucent_frame_times *times)
{
    const lucent_render_settings *s = settings ? settings : &r->scene->render;
    lucent_status st = lucent_render_settings_check(s);
    if (st == LUCENT_OK) st = lucent_gl_make_current(r->ctx);
    if (st == LUCENT_OK) st = gl_frame(r, s, times);
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

/* The radical inverse of k in base b (Halton's sequence). */
static double halton(int k, int b)
{
    double f = 1, x = 0;
    for (; k > 0; k /= b) f /= b, x += f * (k % b);
    return x;
}

/* render.samples frames, each with the camera offset within the pixel by the Halton (2, 3) point k
 * (one sample: the centre), averaged as they are read back; the first frame's times. */
lucent_status lucent_render(lucent_renderer *r, const lucent_render_settings *settings, lucent_render_result *dest)
{
    memset(dest, 0, sizeof *dest);
    int n = (settings ? settings : &r->scene->render)->view.samples;
    n = n > 1 ? n : 1;
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < n && s == LUCENT_OK; k++) {
        r->jitter[0] = n > 1 ? halton(k + 1, 2) - 0.5 : 0;
        r->jitter[1] = n > 1 ? halton(k + 1, 3) - 0.5 : 0;
        lucent_frame_times t;
        s = frame(r, settings, k ? &t : &dest->times);
        double t0 = lucent_clock_ms();
        if (s == LUCENT_OK) s = gl_renderer_read_back(r, dest, k, n);
        dest->readback_ms += lucent_clock_ms() - t0;
    }
    r->jitter[0] = r->jitter[1] = 0;
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
    memset(dest, 0, sizeof *dest);
    gl_renderer_object_albedo(r, index, dest->albedo);
    dest->sigma0_from = "";
    memcpy(dest->curvature_range, r->meshes.mesh[index].curvature_range, sizeof dest->curvature_range);
    dest->transmit_range = gl_tables_of(&r->tables, index)->transmit_range;
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        if (r->state[m] && gl_methods[m]->object_info) gl_methods[m]->object_info(r, r->state[m], index, dest);
    return LUCENT_OK;
}

lucent_status lucent_renderer_scene_changed(lucent_renderer *r, unsigned what)
{
    lucent_status s = lucent_gl_make_current(r->ctx);
    if (s == LUCENT_OK && (what & LUCENT_RENDERER_LIGHTS)) gl_shadows_update(&r->shadows, r->scene);
    if (s == LUCENT_OK && (what & LUCENT_RENDERER_MATERIALS)) {
        /* The methods keep what they uploaded under the bakes' keys, which do not name the material:
         * they start again (their programs stay in r->programs). */
        release_methods(r);
        s = gl_tables_recollect(&r->tables, r->scene);
    }
    return s;
}

lucent_status lucent_renderer_adopt_baked(lucent_renderer *r, const lucent_material *m, const lucent_baked *baked)
{
    lucent_status s = gl_tables_adopt(&r->tables, m, baked);
    if (s != LUCENT_OK) return s;
    /* Uploads made from the old parts under the same keys (the taps of ssss) must be made again. */
    lucent_gl_make_current(r->ctx);
    release_methods(r);
    return LUCENT_OK;
}

/* ---- tests ---- */

void gl_renderer_set_aov(lucent_renderer *r, bool on)
{
    if (r->aov == on) return;
    lucent_gl_make_current(r->ctx);
    gl_programs_free(&r->programs); /* rebuilt with (or without) the auxiliary outputs */
    r->aov = on;
}

lucent_status gl_renderer_read_aov(lucent_renderer *r, int which, lucent_image **dest)
{
    const gl_targets *t = &r->targets;
    if (!r->aov || which < 0 || which > 2 || !r->have_frame || !t->aov)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "no auxiliary output %d", which);
    return gl_read_image(t->fbo_scene, 3 + which, t->width, t->height, 4, true, dest);
}
