/* One frame (Freude 4.2): the targets and shadow maps sized, the method's preparation (timed as
 * setup), the per-frame uniform block, the shadow maps, then the method's passes, each between two
 * timestamp queries. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/methods/method.h"

static void light_block(const lucent_renderer *r, int i, gl_frame_block *b)
{
    const gl_light *g = &r->shadows.lights[i];
    const lucent_light *l = &r->scene->lights[g->scene_index];
    bool directional = l->type == LUCENT_LIGHT_DIRECTIONAL;
    for (int c = 0; c < 3; c++) {
        b->light_vec[i][c] = (float)(directional ? l->direction[c] : l->position[c]);
        b->light_rgb[i][c] = (float)(l->color[c] * l->intensity);
    }
    b->light_vec[i][3] = directional ? 0.0f : 1.0f;
    b->light_shadow[i][0] = (float)g->layer;
    b->light_shadow[i][1] = (float)g->near_plane, b->light_shadow[i][2] = (float)g->far_plane;
    b->light_shadow[i][3] = g->ortho ? 1.0f : 0.0f;
    b->light_texel[i][0] = (float)(g->texel / r->shadows.size);
    gl_mat4_to_float(g->matrix, b->light_matrix[i]);
}

static void frame_block(const lucent_renderer *r, gl_frame_block *b)
{
    const lucent_camera *cam = &r->scene->camera;
    double view[16], proj[16], vp[16], f[3], len = 0;
    memset(b, 0, sizeof *b);
    lucent_camera_view(cam, view);
    lucent_camera_projection(cam, (double)r->targets.width / r->targets.height, proj);
    gl_mat4_mul(proj, view, vp);
    gl_mat4_to_float(vp, b->view_proj);
    for (int i = 0; i < 3; i++) f[i] = cam->target[i] - cam->position[i], len += f[i] * f[i];
    for (int i = 0; i < 3; i++) {
        b->eye[i] = (float)cam->position[i];
        b->forward[i] = (float)(f[i] / sqrt(len));
        b->ambient[i] = (float)r->shadows.ambient[i];
    }
    b->counts[0] = r->shadows.light_count;
    for (int i = 0; i < r->shadows.light_count; i++) light_block(r, i, b);
}

static void draw_shadows(lucent_renderer *r)
{
    for (int i = 0; i < r->shadows.light_count; i++)
        if (gl_shadows_begin(&r->shadows, i)) gl_renderer_draw_objects(r);
    gl_shadows_end();
}

/* Everything the frame needs, rebuilt only when a setting it depends on changed. */
static lucent_status prepare(lucent_renderer *r, const gl_method *m, void **state, const lucent_render_settings *s)
{
    lucent_status st = gl_targets_resize(&r->targets, s->view.width, s->view.height, r->aov);
    if (st == LUCENT_OK) st = gl_shadows_resize(&r->shadows, s->view.shadow_map_size);
    if (st == LUCENT_OK && !*state) {
        *state = calloc(1, m->state_size ? m->state_size : 1);
        if (!*state) st = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    if (st == LUCENT_OK && m->prepare) st = m->prepare(r, *state, s);
    return st;
}

lucent_status gl_frame(lucent_renderer *r, const lucent_render_settings *s, lucent_frame_times *times)
{
    const gl_method *m = gl_methods[s->view.method];
    double t0 = gl_now_ms();
    lucent_status st = prepare(r, m, &r->state[s->view.method], s);
    times->setup_ms = gl_now_ms() - t0;
    if (st != LUCENT_OK) return st;
    gl_frame_block b;
    frame_block(r, &b);
    glNamedBufferSubData(r->frame_ubo, 0, sizeof b, &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, r->frame_ubo);
    gl_timer_begin(&r->timer);
    if (r->shadows.layers > 0) draw_shadows(r);
    gl_timer_mark(&r->timer, "shadow");
    st = m->draw(r, r->state[s->view.method], s);
    double setup = times->setup_ms;
    gl_timer_end(&r->timer, times);
    times->setup_ms = setup;
    return st == LUCENT_OK ? gl_check("drawing the frame") : st;
}
