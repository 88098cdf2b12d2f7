/* The method table and one frame (Freude 4.2): the targets and shadow maps sized, the method's preparation (timed as
 * setup), the per-frame uniform block, the shadow maps, then the method's passes, each between two
 * timestamp queries. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/mat4.h"
#include "gl/methods/method.h"

/* ---- the methods: the table indexed by lucent_render_method, and the names and variants of
 * lucent/settings.h read from it ---- */

extern const gl_method gl_method_lambert, gl_method_cdrf, gl_method_cdrf_translucency, gl_method_ssss, gl_method_points,
    gl_method_tsd;
extern const gl_method gl_method_burley;

const gl_method *const gl_methods[LUCENT_METHOD_COUNT] = {
    [LUCENT_METHOD_LAMBERT] = &gl_method_lambert,
    [LUCENT_METHOD_CDRF] = &gl_method_cdrf,
    [LUCENT_METHOD_CDRF_TRANSLUCENCY] = &gl_method_cdrf_translucency,
    [LUCENT_METHOD_SSSS] = &gl_method_ssss,
    [LUCENT_METHOD_POINTS] = &gl_method_points,
    [LUCENT_METHOD_TSD] = &gl_method_tsd,
    [LUCENT_METHOD_BURLEY] = &gl_method_burley,
};

const char *lucent_render_method_name(lucent_render_method method)
{
    return method >= 0 && method < LUCENT_METHOD_COUNT ? gl_methods[method]->name : "unknown";
}

/* "lambert, cdrf, ..., ssss:<model>[rank]": the names and the variants' forms. */
static void method_list(char *dest, size_t size, bool variants_only)
{
    dest[0] = '\0';
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        if (!variants_only)
            snprintf(dest + strlen(dest), size - strlen(dest), "%s%s", m ? ", " : "", gl_methods[m]->name);
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        if (gl_methods[m]->variant)
            snprintf(dest + strlen(dest), size - strlen(dest), "%s%s:%s", dest[0] ? ", " : "", gl_methods[m]->name,
                     gl_methods[m]->variant_doc);
}

const char *lucent_render_method_setting(lucent_render_method method, int index)
{
    if (method < 0 || method >= LUCENT_METHOD_COUNT || index < 0) return NULL;
    const char *const *k = gl_methods[method]->settings;
    for (int i = 0; k[i]; i++)
        if (i == index) return k[i];
    return NULL;
}

void lucent_render_method_describe(const lucent_render_settings *s, char *dest, size_t size)
{
    dest[0] = '\0';
    const char *key;
    for (int i = 0; (key = lucent_render_method_setting(s->view.method, i)); i++) {
        char value[128];
        lucent_setting_format(s, lucent_setting_find(key, NULL), value, sizeof value);
        snprintf(dest + strlen(dest), size - strlen(dest), "%s%s %s", i ? ", " : "", key, value);
    }
    if (!dest[0]) snprintf(dest, size, "no settings");
}

lucent_status lucent_render_method_parse(const char *text, lucent_render_method *method, lucent_render_settings *s)
{
    if (!text) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render.method: no method given (NULL)");
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++) {
        const gl_method *g = gl_methods[m];
        if (strlen(g->name) != len || strncasecmp(text, g->name, len)) continue;
        if (colon && !g->variant) {
            char list[512];
            method_list(list, sizeof list, true);
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "method '%s': %s takes no variant (only %s)", text,
                                g->name, list);
        }
        lucent_render_settings scratch;
        if (colon && g->variant(colon + 1, s ? s : &scratch) != LUCENT_OK)
            return lucent_error_context(LUCENT_ERR_INVALID_ARGUMENT, "method '%s'", text);
        *method = (lucent_render_method)m;
        return LUCENT_OK;
    }
    char list[512];
    method_list(list, sizeof list, false);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown method '%s' (%s)", text, list);
}

unsigned lucent_renderer_bakes(const lucent_renderer *r, const lucent_render_settings *s)
{
    const gl_method *m =
        s->view.method >= 0 && s->view.method < LUCENT_METHOD_COUNT ? gl_methods[s->view.method] : NULL;
    (void)r;
    if (m && m->bakes) return m->bakes(r, s) | LUCENT_BAKE_BOUNDARY;
    return LUCENT_BAKE_PROFILE | LUCENT_BAKE_TAPS | LUCENT_BAKE_TRANSMITTANCE | LUCENT_BAKE_SIGMA0 | LUCENT_BAKE_SOG |
           LUCENT_BAKE_BOUNDARY;
}

/* ---- the frame ---- */

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
    lucent_mat4_to_float(g->matrix, b->light_matrix[i]);
}

static void frame_block(const lucent_renderer *r, gl_frame_block *b)
{
    const lucent_camera *cam = &r->scene->camera;
    double vp[16], f[3], len = 0;
    memset(b, 0, sizeof *b);
    gl_renderer_view_proj(r, vp);
    lucent_mat4_to_float(vp, b->view_proj);
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

/* Light between surfaces: each light's surfels, every object with the albedo it sends light back with. */
static lucent_status draw_bounce(lucent_renderer *r)
{
    for (int i = 0; i < r->shadows.light_count; i++) {
        const gl_light *g = &r->shadows.lights[i];
        gl_bounce_light light = {.index = i,
                                 .layer = g->layer,
                                 .matrix = g->matrix,
                                 .texel = g->texel,
                                 .distance = g->ortho ? 0 : 0.5 * (g->near_plane + g->far_plane)};
        if (!gl_bounce_begin(&r->bounce, &light)) continue;
        for (int k = 0; k < r->scene->object_count; k++) {
            if (!r->scene->objects[k].visible) continue;
            double a[3];
            gl_renderer_object_albedo(r, k, a);
            gl_bounce_object(&r->bounce, a);
            gl_meshes_draw(&r->meshes, k);
        }
    }
    return gl_bounce_end(&r->bounce);
}

/* Everything the frame needs, rebuilt only when a setting it depends on changed. */
static lucent_status prepare(lucent_renderer *r, const gl_method *m, void **state, const lucent_render_settings *s)
{
    lucent_status st = gl_targets_resize(&r->targets, s->view.width, s->view.height, r->aov);
    if (st == LUCENT_OK) st = gl_shadows_resize(&r->shadows, s->view.shadow_map_size);
    if (st == LUCENT_OK) st = gl_bounce_resize(&r->bounce, r->shadows.layers, s->view.bounce);
    if (st == LUCENT_OK && !*state) {
        *state = calloc(1, m->state_size ? m->state_size : 1);
        if (!*state) st = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    if (st == LUCENT_OK) { /* the boundary's albedo and factors (gl_renderer_object_albedo, lights.glsl) */
        lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_BOUNDARY);
        st = gl_tables_bake(&r->tables, &d, r->cache);
        if (st == LUCENT_OK) st = gl_tables_upload_boundary(&r->tables);
    }
    if (st == LUCENT_OK && m->prepare) st = m->prepare(r, *state, s);
    return st;
}

lucent_status gl_frame(lucent_renderer *r, const lucent_render_settings *s, lucent_frame_times *times)
{
    const gl_method *m = gl_methods[s->view.method];
    double t0 = lucent_clock_ms();
    lucent_status st = prepare(r, m, &r->state[s->view.method], s);
    times->setup_ms = lucent_clock_ms() - t0;
    if (st != LUCENT_OK) return st;
    gl_frame_block b;
    frame_block(r, &b);
    glNamedBufferSubData(r->frame_ubo, 0, sizeof b, &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, r->frame_ubo);
    glBindTextureUnit(GL_BOUNDARY_UNIT, r->tables.boundary_tex); /* lights.glsl's u_boundary, every pass */
    gl_timer_begin(&r->timer);
    if (r->shadows.layers > 0) draw_shadows(r);
    gl_timer_mark(&r->timer, "shadow");
    if (r->bounce.fbo && (st = draw_bounce(r)) == LUCENT_OK) { /* the block's surfel count, once they are listed */
        b.counts[1] = r->bounce.count;
        glNamedBufferSubData(r->frame_ubo, offsetof(gl_frame_block, counts), sizeof b.counts, b.counts);
        gl_bounce_bind(&r->bounce); /* bounce.glsl's surfels, every pass */
        gl_timer_mark(&r->timer, "bounce");
    }
    if (st != LUCENT_OK) {
        gl_timer_end(&r->timer, times);
        return st;
    }
    st = m->draw(r, r->state[s->view.method], s);
    double setup = times->setup_ms;
    gl_timer_end(&r->timer, times);
    times->setup_ms = setup;
    return st == LUCENT_OK ? gl_check("drawing the frame") : st;
}
