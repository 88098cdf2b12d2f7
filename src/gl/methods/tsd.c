/* tsd: texture-space diffusion (d'Eon, Luebke & Enderton 2007; GPU Gems 3 ch. 14, "Advanced
 * techniques for realistic real-time skin rendering"), the baseline of Kubo et al. (Table 1) and
 * Kim et al. (Figure 3). Per object, in its texture atlas (its own coordinates, or Lucent's,
 * lucent_mesh_uv_atlas):
 *   irradiance  the mesh rasterised at its texture coordinates: sum over lights of E max(n.l, 0)
 *               times the shadow map's visibility (GPU Gems 3, 14.4.1), plus with translucency the
 *               light through thin parts (the house's shadow-map thickness and T(s), in place of the
 *               paper's translucent shadow maps, 14.5.2), a: coverage
 *   stretch     per frame, the texels per mm along u and v: 1 / |dP/dx|, 1 / |dP/dy| in texture
 *               space (14.4.2, "stretch correction")
 *   dilate      texels outside every chart take the mean of the covered ones within 2 texels
 *               (the gutters of the atlas, 14.4.3: seams)
 *   blur        for each Gaussian i of the sum of Gaussians R(r) = sum_i w_i G(v_i, r), a horizontal
 *               and a vertical pass of G(v_i - v_{i-1}) applied to the previous result (the chain,
 *               14.4.2: G(v_i) = G(v_i - v_{i-1}) * G(v_{i-1})), taps 3 sigma wide scaled by the
 *               stretch; a tap past the chart's edge follows the seam into the chart across
 *               (lucent_mesh_uv_seams: the first texel outside holds the same surface point there and
 *               the map's derivative), so light crosses seams; taps past the mesh's boundary keep
 *               only texels of the centre's chart (a normalised convolution: no light from the
 *               unrelated charts packed beside it); the vertical pass also adds w_i G_i into the sum
 *   geometry    the mesh from the camera: diffuse albedo (sum / pi + ambient) from the sum at the
 *               fragment's texture coordinates (a face smaller than a texel, never rasterised into
 *               the texture, keeps its own irradiance), the boundary's GGX reflection and
 *               F_t(w_o) of the others
 *   compose     the house's compose pass
 * The variances and RGB weights: d'Eon's skin table (lucent_sog_deon_skin) or the bake room's fit
 * of the material's profile (LUCENT_BAKE_SOG), the weights normalised per channel (the albedo
 * carries the total, as for the other methods). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/json.h"
#include "base/settings_table.h"
#include "gl/methods/surface.h"
#include "lucent/mesh.h"

/* ---- the settings group ---- */

SETTINGS_NAMES(sog_names, "auto", "deon", "fit")

static const lucent_setting k_tsd[] = {
    SETTING_INT("tsd_size", tsd.size, 1024, 64, 8192, 0, "texels along a side of each object's texture"),
    SETTING_INT("tsd_gaussians", tsd.gaussians, 6, 1, LUCENT_SOG_MAX, 0,
                "Gaussians of the fitted sum (d'Eon's skin table has six)"),
    SETTING_INT("tsd_taps", tsd.taps, 7, 3, 63, LUCENT_SETTING_ODD, "taps per 1-D pass, 3 sigma either side"),
    SETTING_CHOICE("tsd_sog", tsd.sog, "auto", sog_names,
                   "the sum of Gaussians: d'Eon's skin table, the fit of the profile, or auto (the table for "
                   "skin materials)"),
    SETTING_BOOL("tsd_seams", tsd.seams, true,
                 "the blur's taps follow texture seams into the chart across (off: each "
                 "chart blurs alone, as before seams were handled)"),
};

const lucent_settings_group gl_tsd_settings = SETTINGS_GROUP("tsd", "texture-space diffusion", k_tsd);

/* ---- the method ---- */

enum { TSD_DILATE = 2 }; /* texels the dilation reaches into the gutters */

typedef struct tsd_object {
    GLuint vao, vertices, indices;
    GLsizei index_count;
    int size;                                  /* texels of the textures below; 0: none */
    GLuint irr, stretch, ping, pong, tmp, sum; /* RGBA16F; stretch RGBA32F: su, sv, chart + 1 */
    GLuint irr_fbo, stretch_fbo, dilate_fbo, ping_fbo, pong_fbo, tmp_fbo, v_fbo[2], sum_fbo;
    GLuint irr_dilated, stretch_dilated;
    GLuint seam, seam_j;  /* seam texels: the point across (RGBA32F: x, y, chart + 1, across + 1), J (RGBA16F) */
    size_t seam_texels;   /* texels mapped across a seam */
    bool own_uvs;         /* the mesh's coordinates (else Lucent's atlas) */
    lucent_uv_stats uv;   /* of the coordinates in use */
    lucent_sog sog;       /* variances and normalised weights in use */
    const char *sog_from; /* "deon", "fit" */
} tsd_object;

typedef struct tsd_state {
    GLuint irradiance, stretch, dilate, blur, final;
    tsd_object *objects;
    int object_count;
    int taps;
    bool seams;
} tsd_state;

static void free_textures(tsd_object *o)
{
    GLuint tex[10] = {o->irr,         o->stretch,         o->ping, o->pong,  o->tmp, o->sum,
                      o->irr_dilated, o->stretch_dilated, o->seam, o->seam_j};
    GLuint fbo[9] = {o->irr_fbo, o->stretch_fbo, o->dilate_fbo, o->ping_fbo, o->pong_fbo,
                     o->tmp_fbo, o->v_fbo[0],    o->v_fbo[1],   o->sum_fbo};
    for (int i = 0; i < 10; i++)
        if (tex[i]) glDeleteTextures(1, &tex[i]);
    for (int i = 0; i < 9; i++)
        if (fbo[i]) glDeleteFramebuffers(1, &fbo[i]);
    o->irr = o->stretch = o->ping = o->pong = o->tmp = o->sum = o->irr_dilated = o->stretch_dilated = 0;
    o->seam = o->seam_j = 0;
    o->irr_fbo = o->stretch_fbo = o->dilate_fbo = o->ping_fbo = o->pong_fbo = o->tmp_fbo = 0;
    o->v_fbo[0] = o->v_fbo[1] = o->sum_fbo = 0;
    o->size = 0;
}

static void free_mesh(tsd_object *o)
{
    GLuint b[2] = {o->vertices, o->indices};
    glDeleteBuffers(2, b);
    if (o->vao) glDeleteVertexArrays(1, &o->vao);
    o->vao = o->vertices = o->indices = 0;
}

/* The seam textures (lucent_mesh_uv_seams): for each texel within TSD_DILATE texels of a seam edge,
 * the same surface point across the seam and the map's derivative there; zero elsewhere. Uploaded
 * row by row, from the first to the last mapped texel of the row. */
static lucent_status upload_seams(const lucent_mesh *m, int size, tsd_object *o)
{
    lucent_uv_seams sm = {0};
    lucent_status s = lucent_mesh_uv_seams(m, size, TSD_DILATE, &sm);
    float *row = s == LUCENT_OK ? calloc(8 * (size_t)size, sizeof *row) : NULL;
    if (s == LUCENT_OK && !row) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) {
        glClearTexImage(o->seam, 0, GL_RGBA, GL_FLOAT, NULL);
        glClearTexImage(o->seam_j, 0, GL_RGBA, GL_FLOAT, NULL);
    }
    for (size_t i = 0; row && i < sm.count;) {
        size_t j = i;
        uint32_t y = sm.texels[i].y, x0 = sm.texels[i].x;
        for (; j < sm.count && sm.texels[j].y == y; j++) {
            const lucent_uv_seam_texel *t = &sm.texels[j];
            float *a = row + 4 * (t->x - x0), *b = row + 4 * ((size_t)size + t->x - x0);
            a[0] = t->target[0], a[1] = t->target[1], a[2] = (float)t->chart + 1, a[3] = (float)t->across + 1;
            memcpy(b, t->jacobian, sizeof t->jacobian);
        }
        GLsizei w = (GLsizei)(sm.texels[j - 1].x - x0 + 1);
        glTextureSubImage2D(o->seam, 0, (GLint)x0, (GLint)y, w, 1, GL_RGBA, GL_FLOAT, row);
        glTextureSubImage2D(o->seam_j, 0, (GLint)x0, (GLint)y, w, 1, GL_RGBA, GL_FLOAT, row + 4 * (size_t)size);
        memset(row, 0, 8 * (size_t)size * sizeof *row);
        i = j;
    }
    o->seam_texels = sm.count;
    free(row);
    lucent_uv_seams_free(&sm);
    return s;
}

/* The object's vertices split at texture seams (position, normal, uv), from its own coordinates or
 * from an atlas made for texture size `size` (the gutter is 4 texels there), and its seam textures
 * (make_textures first). */
static lucent_status upload_mesh(const lucent_scene_object *so, int size, tsd_object *o)
{
    lucent_mesh m = *so->mesh; /* a shallow copy: only uvs is replaced */
    lucent_status s = LUCENT_OK;
    o->own_uvs = so->mesh->uvs != NULL;
    if (o->own_uvs) {
        s = lucent_mesh_uv_stats_compute(&m, &o->uv);
    } else {
        m.uvs = NULL;
        s = lucent_mesh_uv_atlas(&m, &(lucent_uv_atlas_desc){.texture_size = size}, &o->uv);
    }
    lucent_uv_split sp = {0};
    uint32_t *chart = malloc((m.face_count + 1) * sizeof *chart);
    size_t charts = 0;
    if (s == LUCENT_OK && !chart) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK) s = lucent_mesh_uv_split(&m, &sp);
    if (s == LUCENT_OK) s = lucent_mesh_uv_charts(&m, chart, &charts);
    if (s == LUCENT_OK && o->own_uvs) o->uv.chart_count = charts;
    if (s == LUCENT_OK) s = upload_seams(&m, size, o);
    float *v = s == LUCENT_OK ? malloc(sp.count * 9 * sizeof *v + 1) : NULL;
    if (s == LUCENT_OK && !v) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; v && i < sp.count; i++) {
        for (int c = 0; c < 3; c++) {
            v[9 * i + c] = (float)m.positions[3 * sp.vertex[i] + c];
            v[9 * i + 3 + c] = (float)m.normals[3 * sp.vertex[i] + c];
        }
        v[9 * i + 6] = (float)sp.uv[2 * i], v[9 * i + 7] = (float)sp.uv[2 * i + 1];
    }
    /* each split vertex's chart (its corners' faces share it: a vertex and a coordinate make one chart) */
    for (size_t f = 0; v && f < m.face_count; f++)
        for (int k = 0; k < 3; k++) v[9 * sp.faces[3 * f + (size_t)k] + 8] = (float)(chart[f] + 1);
    if (v) {
        free_mesh(o);
        glCreateBuffers(1, &o->vertices);
        glNamedBufferData(o->vertices, (GLsizeiptr)(sp.count * 9 * sizeof *v), v, GL_STATIC_DRAW);
        glCreateBuffers(1, &o->indices);
        glNamedBufferData(o->indices, (GLsizeiptr)(3 * m.face_count * sizeof *sp.faces), sp.faces, GL_STATIC_DRAW);
        o->index_count = (GLsizei)(3 * m.face_count);
        glCreateVertexArrays(1, &o->vao);
        glVertexArrayVertexBuffer(o->vao, 0, o->vertices, 0, 9 * sizeof(float));
        glVertexArrayElementBuffer(o->vao, o->indices);
        /* location 4: the chart (+1), read by tsd_texture.vert.glsl only */
        static const GLuint attr[4] = {GL_ATTR_POSITION, GL_ATTR_NORMAL, GL_ATTR_UV, 4};
        static const int comps[4] = {3, 3, 2, 1}, offs[4] = {0, 3, 6, 8};
        for (int a = 0; a < 4; a++) {
            glEnableVertexArrayAttrib(o->vao, attr[a]);
            glVertexArrayAttribFormat(o->vao, attr[a], comps[a], GL_FLOAT, GL_FALSE, (GLuint)(offs[a] * sizeof(float)));
            glVertexArrayAttribBinding(o->vao, attr[a], 0);
        }
    }
    free(v), free(chart);
    lucent_uv_split_free(&sp);
    if (!o->own_uvs) free(m.uvs);
    return s == LUCENT_OK ? gl_check("uploading the texture-space mesh") : s;
}

static lucent_status make_textures(tsd_object *o, int size)
{
    free_textures(o);
    o->irr = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->irr_dilated = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->stretch = gl_texture(GL_RGBA32F, size, size, GL_NEAREST);
    o->stretch_dilated = gl_texture(GL_RGBA32F, size, size, GL_NEAREST);
    o->ping = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->pong = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->tmp = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->sum = gl_texture(GL_RGBA16F, size, size, GL_LINEAR);
    o->seam = gl_texture(GL_RGBA32F, size, size, GL_NEAREST);
    o->seam_j = gl_texture(GL_RGBA16F, size, size, GL_NEAREST);
    lucent_status s = gl_framebuffer(1, &o->irr, 0, "the irradiance texture", &o->irr_fbo);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &o->stretch, 0, "the stretch texture", &o->stretch_fbo);
    GLuint dil[2] = {o->irr_dilated, o->stretch_dilated}, v0[2] = {o->ping, o->sum}, v1[2] = {o->pong, o->sum};
    if (s == LUCENT_OK) s = gl_framebuffer(2, dil, 0, "the dilated textures", &o->dilate_fbo);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &o->tmp, 0, "the blur's intermediate", &o->tmp_fbo);
    if (s == LUCENT_OK) s = gl_framebuffer(2, v0, 0, "the blur chain", &o->v_fbo[0]);
    if (s == LUCENT_OK) s = gl_framebuffer(2, v1, 0, "the blur chain", &o->v_fbo[1]);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &o->sum, 0, "the sum of Gaussians", &o->sum_fbo);
    o->size = s == LUCENT_OK ? size : 0;
    return s;
}

static bool is_skin(const lucent_material *m) { return !strncasecmp(m->name, "skin", 4); }

/* The object's sum of Gaussians, weights normalised per channel (GPU Gems 3, Figure 14-13's table
 * sums to 1 per channel; a fit sums to the profile's total reflectance, which the albedo carries). */
static lucent_status object_sog(lucent_renderer *r, const lucent_render_settings *s, int i, tsd_object *o)
{
    const lucent_material *mat = &r->tables.material[r->tables.object_material[i]];
    bool deon = s->tsd.sog == 1 || (s->tsd.sog == 0 && is_skin(mat));
    if (deon) {
        lucent_sog_deon_skin(&o->sog);
        o->sog_from = "deon";
    } else {
        o->sog = gl_tables_of(&r->tables, i)->sog;
        o->sog_from = "fit";
    }
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (int k = 0; k < o->sog.count; k++) sum += o->sog.weight[c][k];
        for (int k = 0; k < o->sog.count; k++) o->sog.weight[c][k] = sum > 0 ? o->sog.weight[c][k] / sum : 0;
        for (int k = 1; k < o->sog.count; k++)
            if (o->sog.variance[c][k] < o->sog.variance[c][k - 1] || o->sog.variance[c][k] != o->sog.variance[0][k])
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                    "material \"%s\": the sum of Gaussians needs shared, ascending variances",
                                    mat->name);
    }
    return LUCENT_OK;
}

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    tsd_state *st = state;
    const lucent_scene *sc = r->scene;
    if (!st->objects) {
        st->objects = calloc((size_t)sc->object_count, sizeof *st->objects);
        if (!st->objects) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        st->object_count = sc->object_count;
    }
    bool fit = false;
    for (int i = 0; i < sc->object_count; i++)
        fit |= sc->objects[i].visible &&
               (s->tsd.sog == 2 || (s->tsd.sog == 0 && !is_skin(&r->tables.material[r->tables.object_material[i]])));
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_SOG);
    d.sog_count = s->tsd.gaussians;
    lucent_status e = fit ? gl_tables_bake(&r->tables, &d, r->cache) : LUCENT_OK;
    if (e == LUCENT_OK && s->translucency.enabled) e = gl_translucency_prepare(r, s);
    for (int i = 0; e == LUCENT_OK && i < sc->object_count; i++) {
        tsd_object *o = &st->objects[i];
        if (!sc->objects[i].visible) continue;
        bool resized = o->size != s->tsd.size; /* the seam textures follow the size, the atlas its gutter */
        if (resized) e = make_textures(o, s->tsd.size);
        if (e == LUCENT_OK && (!o->vao || resized)) e = upload_mesh(&sc->objects[i], s->tsd.size, o);
        if (e != LUCENT_OK) e = lucent_error_context(e, "object \"%s\": texture coordinates", sc->objects[i].name);
        if (e == LUCENT_OK) e = object_sog(r, s, i, o);
    }
    st->taps = s->tsd.taps;
    st->seams = s->tsd.seams;
    if (e == LUCENT_OK)
        e = gl_programs_get(&r->programs, "tsd_texture.vert.glsl", "tsd_irradiance.frag.glsl", NULL, &st->irradiance);
    if (e == LUCENT_OK)
        e = gl_programs_get(&r->programs, "tsd_texture.vert.glsl", "tsd_stretch.frag.glsl", NULL, &st->stretch);
    if (e == LUCENT_OK)
        e = gl_programs_get(&r->programs, "fullscreen.vert.glsl", "tsd_dilate.frag.glsl", NULL, &st->dilate);
    if (e == LUCENT_OK)
        e = gl_programs_get(&r->programs, "fullscreen.vert.glsl", "tsd_blur.frag.glsl", NULL, &st->blur);
    if (e == LUCENT_OK) e = gl_surface_program(r, "tsd.frag.glsl", NULL, &st->final);
    return e;
}

/* What prepare bakes: the fitted sum of Gaussians (unless every material takes d'Eon's table) and,
 * with translucency, the transmittance. */
static unsigned bakes(const lucent_renderer *r, const lucent_render_settings *s)
{
    (void)r;
    return (s->tsd.sog != 1 ? LUCENT_BAKE_SOG : 0u) | gl_translucency_bakes(s, s->translucency.enabled);
}

/* ---- the passes ---- */

static void bind_target(GLuint fbo, int size)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, size, size);
}

static void texture_pass(lucent_renderer *r, tsd_state *st, const lucent_render_settings *s, GLuint program,
                         bool irradiance)
{
    glUseProgram(program);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (irradiance) gl_shadows_bind(&r->shadows);
    glBindTextureUnit(4, r->tables.transmit_tex ? r->tables.transmit_tex : r->dummy_tex);
    if (r->tables.sheet_tex) glBindTextureUnit(GL_SHEET_UNIT, r->tables.sheet_tex);
    for (int i = 0; i < st->object_count; i++) {
        tsd_object *o = &st->objects[i];
        const lucent_scene_object *so = &r->scene->objects[i];
        if (!so->visible) continue;
        bind_target(irradiance ? o->irr_fbo : o->stretch_fbo, o->size);
        glClearNamedFramebufferfv(irradiance ? o->irr_fbo : o->stretch_fbo, GL_COLOR, 0, (const float[4]){0});
        glUniform1f(glGetUniformLocation(program, "u_shadow_offset"), 1.5f);
        if (irradiance) {
            gl_translucency_uniforms(r, s, i, program, s->translucency.enabled);
            double a[3];
            gl_renderer_object_albedo(r, i, a);
            glUniform3f(glGetUniformLocation(program, "u_albedo"), (float)a[0], (float)a[1], (float)a[2]);
            glUniform1f(glGetUniformLocation(program, "u_material"), (float)r->tables.object_material[i]);
        }
        glBindVertexArray(o->vao);
        glDrawElements(GL_TRIANGLES, o->index_count, GL_UNSIGNED_INT, NULL);
    }
    if (irradiance) gl_shadows_unbind();
    gl_timer_mark(&r->timer, irradiance ? "irradiance" : "stretch");
}

static void dilate_pass(lucent_renderer *r, tsd_state *st)
{
    glUseProgram(st->dilate);
    glBindVertexArray(r->empty_vao);
    glUniform1i(glGetUniformLocation(st->dilate, "u_reach"), TSD_DILATE);
    for (int i = 0; i < st->object_count; i++) {
        tsd_object *o = &st->objects[i];
        if (!r->scene->objects[i].visible) continue;
        bind_target(o->dilate_fbo, o->size);
        glBindTextureUnit(0, o->irr);
        glBindTextureUnit(1, o->stretch);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl_timer_mark(&r->timer, "dilate");
}

/* Gaussian k of every object: horizontal into tmp, vertical into the next link of the chain, with
 * w_k G_k / coverage blended into the sum. */
static void blur_passes(lucent_renderer *r, tsd_state *st, int k)
{
    GLuint p = st->blur;
    glUseProgram(p);
    glBindVertexArray(r->empty_vao);
    glUniform1i(glGetUniformLocation(p, "u_taps"), st->taps);
    glUniform1i(glGetUniformLocation(p, "u_seams"), st->seams);
    GLint loc_axis = glGetUniformLocation(p, "u_axis"), loc_sigma = glGetUniformLocation(p, "u_sigma");
    GLint loc_weight = glGetUniformLocation(p, "u_weight");
    for (int axis = 0; axis < 2; axis++) {
        glUniform2i(loc_axis, axis == 0, axis == 1);
        if (axis == 1) glEnablei(GL_BLEND, 1), glBlendFunci(1, GL_ONE, GL_ONE), glBlendEquationi(1, GL_FUNC_ADD);
        for (int i = 0; i < st->object_count; i++) {
            tsd_object *o = &st->objects[i];
            if (!r->scene->objects[i].visible || k >= o->sog.count) continue;
            double v = o->sog.variance[0][k] - (k ? o->sog.variance[0][k - 1] : 0); /* the chain's step */
            glUniform1f(loc_sigma, (float)sqrt(fmax(v, 0)));
            glUniform3f(loc_weight, (float)o->sog.weight[0][k], (float)o->sog.weight[1][k], (float)o->sog.weight[2][k]);
            GLuint source = k == 0 ? o->irr_dilated : (k % 2 ? o->ping : o->pong);
            bind_target(axis == 0 ? o->tmp_fbo : o->v_fbo[k % 2], o->size);
            if (k == 0 && axis == 0) glClearNamedFramebufferfv(o->sum_fbo, GL_COLOR, 0, (const float[4]){0});
            glBindTextureUnit(0, axis == 0 ? source : o->tmp);
            glBindTextureUnit(1, o->stretch_dilated);
            glBindTextureUnit(2, o->seam);
            glBindTextureUnit(3, o->seam_j);
            glBindTextureUnit(5, source);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        if (axis == 1) glDisablei(GL_BLEND, 1);
        char name[24];
        snprintf(name, sizeof name, "blur %c%d", axis ? 'v' : 'h', k + 1);
        gl_timer_mark(&r->timer, name);
    }
}

/* The mesh from the camera into the scene targets, reading each object's sum. */
static void final_pass(lucent_renderer *r, tsd_state *st, const lucent_render_settings *s)
{
    const gl_targets *t = &r->targets;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t->fbo_scene);
    glViewport(0, 0, t->width, t->height);
    for (int i = 0; i < gl_targets_scene_outputs(t); i++)
        glClearNamedFramebufferfv(t->fbo_scene, GL_COLOR, i, (const float[4]){0});
    glClearNamedFramebufferfv(t->fbo_scene, GL_DEPTH, 0, (const float[1]){1});
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(st->final);
    gl_shadows_bind(&r->shadows);
    if (r->tables.sheet_tex) glBindTextureUnit(GL_SHEET_UNIT, r->tables.sheet_tex);
    glVertexAttrib1f(GL_ATTR_CURVATURE, 0.0f);
    for (int i = 0; i < st->object_count; i++) {
        tsd_object *o = &st->objects[i];
        if (!r->scene->objects[i].visible) continue;
        gl_surface_material_uniforms(r, i, st->final);
        gl_translucency_uniforms(r, s, i, st->final, s->translucency.enabled); /* the thin parts' lobe */
        glUniform1f(glGetUniformLocation(st->final, "u_gaussians"), (float)o->sog.count);
        glBindTextureUnit(3, o->sum);
        glBindVertexArray(o->vao);
        glDrawElements(GL_TRIANGLES, o->index_count, GL_UNSIGNED_INT, NULL);
    }
    gl_shadows_unbind();
    glDisable(GL_DEPTH_TEST);
    gl_timer_mark(&r->timer, "geometry");
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    tsd_state *st = state;
    texture_pass(r, st, s, st->irradiance, true);
    texture_pass(r, st, s, st->stretch, false);
    dilate_pass(r, st);
    int n = 0;
    for (int i = 0; i < st->object_count; i++)
        if (r->scene->objects[i].visible && st->objects[i].sog.count > n) n = st->objects[i].sog.count;
    for (int k = 0; k < n; k++) blur_passes(r, st, k);
    final_pass(r, st, s);
    gl_compose(r, s, 0);
    return LUCENT_OK;
}

/* ---- what it reports ---- */

static void object_info(const lucent_renderer *r, const void *state, int i, lucent_render_object_info *dest)
{
    (void)r;
    const tsd_state *st = state;
    if (!st->objects || !st->objects[i].sog_from) return;
    const lucent_sog *g = &st->objects[i].sog;
    dest->kernel_range = 3 * sqrt(g->variance[0][g->count - 1]); /* the widest Gaussian's 3 sigma, mm */
}

static void sidecar(const lucent_renderer *r, const void *state, const lucent_render_settings *s, cJSON *root)
{
    (void)s;
    const tsd_state *st = state;
    cJSON *list = cJSON_AddArrayToObject(root, "tsd");
    for (int i = 0; list && st->objects && i < st->object_count; i++) {
        const tsd_object *o = &st->objects[i];
        if (!r->scene->objects[i].visible || !o->sog_from) continue;
        cJSON *j = cJSON_CreateObject();
        if (!j) return;
        cJSON_AddStringToObject(j, "object", r->scene->objects[i].name);
        cJSON_AddStringToObject(j, "coordinates", o->own_uvs ? "own" : "atlas");
        cJSON_AddNumberToObject(j, "charts", (double)o->uv.chart_count);
        cJSON_AddNumberToObject(j, "stretch_l2", o->uv.stretch_l2);
        cJSON_AddNumberToObject(j, "texture_size", o->size);
        cJSON_AddNumberToObject(j, "seam_texels", (double)o->seam_texels);
        cJSON_AddStringToObject(j, "sog", o->sog_from);
        lucent_json_add_numbers(j, "variances_mm2", o->sog.variance[0], o->sog.count);
        static const char *const names[3] = {"weights_r", "weights_g", "weights_b"};
        for (int c = 0; c < 3; c++) lucent_json_add_numbers(j, names[c], o->sog.weight[c], o->sog.count);
        cJSON_AddItemToArray(list, j);
    }
}

static void release(void *state)
{
    tsd_state *st = state;
    for (int i = 0; st->objects && i < st->object_count; i++)
        free_textures(&st->objects[i]), free_mesh(&st->objects[i]);
    free(st->objects);
}

const gl_method gl_method_tsd = {
    .name = "tsd",
    .settings = (const char *const[]){"tsd_size", "tsd_gaussians", "tsd_taps", "tsd_sog", "tsd_seams", "profile",
                                      "translucency", "transmittance", NULL},
    .state_size = sizeof(tsd_state),
    .bakes = bakes,
    .prepare = prepare,
    .draw = draw,
    .object_info = object_info,
    .sidecar = sidecar,
    .release = release,
};
