/* points: subsurface scattering in point-based rendering (Kim, Bickel, Gross & Choi; seed 001,
 * Figure 1), on surfels (lucent/surfels.h) made from each object's vertices or read from a point
 * cloud. The passes:
 *   (1) shadow maps: the splats added to the core's maps (ray-cast disks seen from each light);
 *   (2) visibility splatting: the depth of every splat's ray-cast disk (not its prefilter), pushed
 *       back along the view ray by depth_epsilon radii;
 *   (3) attribute splatting: Gaussian-weighted position, normal, albedo, roughness and f0 added into
 *       float targets where a splat lies within the epsilon of the visible surface;
 *   (4) splat-based diffusion: the irradiance (N.L with the shadow test, plus the light through
 *       thin parts) resampled onto the surfels, averaged onto the coarser levels, and splatted again
 *       in object space once per Gaussian of the material's sum of Gaussians (d'Eon & Luebke 2007:
 *       the table for skin, or Lucent's fit of the material's profile, lucent/bake.h), each from the
 *       coarsest surfel level fine enough for it (the paper's observation: fewer surfels for the
 *       large radii), normalised and combined with the RGB weights;
 *   (5) shading: the normalised attributes, the diffused radiance and the Kelemen/Szirmay-Kalos
 *       specular.
 * Splats are ray-cast in the fragment shader (Botsch et al. 2005) with an EWA-style screen-space
 * prefilter and write their true depth, so they mix with meshes: objects that are not splatted (in
 * a scene where some objects are points, the others) are drawn as triangles into the same targets
 * and shaded with Lambert. A scene without point objects is splatted whole. The styles `brdf`
 * (high-quality splatting with a BRDF) and `disks` (flat opaque disks) are the plain point
 * renderings of the paper's Figure 2. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"
#include "base/mat4.h"
#include "base/optics.h"
#include "base/settings_table.h"
#include "gl/methods/surface.h"
#include "lucent/surfels.h"

/* ---- the settings group ---- */

SETTINGS_NAMES(style_names, "diffusion", "brdf", "disks")
SETTINGS_NAMES(sog_source_names, "fit", "deon")

static const lucent_setting k_points[] = {
    SETTING_CHOICE("splats", points.style, "diffusion", style_names,
                   "diffusion (Kim et al.), brdf (splatting with a BRDF), disks (flat opaque disks)"),
    SETTING_REAL("radius_scale", points.radius_scale, 1, 0.05, 20, "times every surfel's radius"),
    SETTING_REAL("depth_epsilon", points.depth_epsilon, 0.3, 0, 100,
                 "visibility splats pushed back along the view ray, in splat radii"),
    SETTING_REAL("cutoff", points.cutoff, 2, 0.5, 6, "a splat's radius in standard deviations of its Gaussian"),
    SETTING_INT("sog", points.sog, 6, 1, LUCENT_SOG_MAX, 0, "Gaussians of the sum-of-Gaussians fit (points:sog4)"),
    SETTING_CHOICE("sog_source", points.sog_source, "fit", sog_source_names,
                   "fit: Lucent's fit of the material's profile (render.profile); deon: d'Eon's skin table"),
    SETTING_REAL("sog_cutoff", points.sog_cutoff, 3.5, 1, 8, "a diffusion splat's support, standard deviations"),
    SETTING_REAL("decimation", points.decimation, 2, 1.2, 8, "spacing ratio of consecutive surfel levels"),
    SETTING_REAL("level_spacing", points.level_spacing, 0.5, 0.05, 4,
                 "a Gaussian uses the coarsest level whose spacing is at most this times its deviation"),
    SETTING_INT("neighbours", points.neighbours, LUCENT_SURFEL_DEFAULT_K, 2, 32, 0,
                "surfel radius: distance to the k-th nearest surfel"),
    SETTING_REAL("filter_px", points.filter_px, 1, 0, 8, "radius of the screen-space prefilter, pixels"),
    SETTING_INT("impulse", points.impulse, -1, -1, 2000000000, 0,
                "debug: only this surfel of each object is lit, radiance 1 (the diffusion's impulse response)"),
    SETTING_BOOL("weights", points.weights, false,
                 "debug: every channel is the splats' summed Gaussian weight before normalisation (0 uncovered)"),
};

const lucent_settings_group gl_points_settings =
    SETTINGS_GROUP("points", "surfels, splatting and splat-based diffusion", k_points);

/* "sog4" (a fit of 4 Gaussians), "deon" (d'Eon's table), "brdf", "disks". */
static lucent_status variant(const char *text, lucent_render_settings *s)
{
    if (!strcmp(text, "deon")) return s->points.sog_source = LUCENT_SOG_DEON, LUCENT_OK;
    if (!strcmp(text, "brdf")) return s->points.style = LUCENT_POINTS_BRDF, LUCENT_OK;
    if (!strcmp(text, "disks")) return s->points.style = LUCENT_POINTS_DISKS, LUCENT_OK;
    char *end;
    long n = !strncmp(text, "sog", 3) ? strtol(text + 3, &end, 10) : 0;
    if (n >= 1 && n <= LUCENT_SOG_MAX && !*end) {
        s->points.sog = (int)n, s->points.sog_source = LUCENT_SOG_FIT;
        return LUCENT_OK;
    }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown points variant '%s' (sog<1..%d>, deon, brdf, disks)",
                        text, LUCENT_SOG_MAX);
}

/* ---- the state ---- */

enum { G_POSITION = 0, G_NORMAL, G_ALBEDO, G_OBJECT, G_COUNT };

typedef struct points_object {
    bool splat;
    size_t base; /* first surfel in the buffers */
    int level_count;
    lucent_surfel_level levels[LUCENT_SURFEL_MAX_LEVELS]; /* first relative to base */
} points_object;

typedef struct points_state {
    GLuint shadow, visibility, attributes, disks, irradiance, restrict_, diffuse, resolve, shade, mesh;
    GLuint surfels, radiance, child_start, children; /* storage buffers 0..3 */
    GLuint g_tex[G_COUNT], g_depth, fbo_g, level_tex, fbo_level, sum_tex[2], fbo_sum;
    int width, height;
    char surfel_key[96];
    int object_count;
    points_object *objects;
    size_t total;
    lucent_sog sog[GLR_MAX_MATERIALS];
    int gaussian_level[GLR_MAX_MATERIALS][LUCENT_SOG_MAX]; /* of the last object drawn with it */
} points_state;

static void free_targets(points_state *st)
{
    glDeleteTextures(G_COUNT, st->g_tex);
    GLuint t[4] = {st->g_depth, st->level_tex, st->sum_tex[0], st->sum_tex[1]};
    GLuint f[3] = {st->fbo_g, st->fbo_level, st->fbo_sum};
    glDeleteTextures(4, t);
    glDeleteFramebuffers(3, f);
    memset(st->g_tex, 0, sizeof st->g_tex);
    st->g_depth = st->level_tex = st->sum_tex[0] = st->sum_tex[1] = st->fbo_g = st->fbo_level = st->fbo_sum = 0;
    st->width = st->height = 0;
}

static void free_buffers(points_state *st)
{
    GLuint b[4] = {st->surfels, st->radiance, st->child_start, st->children};
    glDeleteBuffers(4, b);
    st->surfels = st->radiance = st->child_start = st->children = 0;
    free(st->objects);
    st->objects = NULL, st->object_count = 0, st->total = 0, st->surfel_key[0] = '\0';
}

static void release(void *state)
{
    points_state *st = state;
    free_targets(st);
    free_buffers(st);
}

static lucent_status resize(points_state *st, int w, int h)
{
    if (st->fbo_g && st->width == w && st->height == h) return LUCENT_OK;
    free_targets(st);
    st->width = w, st->height = h;
    for (int i = 0; i < G_COUNT; i++) st->g_tex[i] = gl_texture(GL_RGBA32F, w, h, GL_NEAREST);
    st->g_depth = gl_texture(GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
    st->level_tex = gl_texture(GL_RGBA32F, w, h, GL_NEAREST);
    for (int i = 0; i < 2; i++) st->sum_tex[i] = gl_texture(GL_RGBA32F, w, h, GL_NEAREST);
    lucent_status s = gl_framebuffer(G_COUNT, st->g_tex, st->g_depth, "the points attribute targets", &st->fbo_g);
    if (s == LUCENT_OK) s = gl_framebuffer(1, &st->level_tex, 0, "the points diffusion target", &st->fbo_level);
    if (s == LUCENT_OK) s = gl_framebuffer(2, st->sum_tex, 0, "the points diffusion sum", &st->fbo_sum);
    return s;
}

/* Whether object i is splatted: the point objects, or every object when the scene has none. */
static bool splatted(const lucent_scene *sc, int i)
{
    bool any = false;
    for (int k = 0; k < sc->object_count; k++) any = any || sc->objects[k].as_points;
    return sc->objects[i].visible && (!any || sc->objects[i].as_points);
}

/* Surfels of every splatted object, concatenated into the storage buffers (rebuilt when the
 * neighbour count or the decimation changes). */
static lucent_status build_surfels(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    char key[sizeof st->surfel_key];
    snprintf(key, sizeof key, "%d %.17g", s->points.neighbours, s->points.decimation);
    if (st->objects && !strcmp(key, st->surfel_key)) return LUCENT_OK;
    free_buffers(st);
    const lucent_scene *sc = r->scene;
    lucent_surfels **sf = calloc((size_t)sc->object_count, sizeof *sf);
    st->objects = calloc((size_t)sc->object_count, sizeof *st->objects);
    if (!sf || !st->objects) {
        free(sf);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    }
    st->object_count = sc->object_count;
    lucent_surfels_desc d = {
        .neighbours = s->points.neighbours, .decimation = s->points.decimation, .pool = r->desc.pool};
    lucent_status e = LUCENT_OK;
    size_t total = 0, child_total = 0;
    for (int i = 0; i < sc->object_count && e == LUCENT_OK; i++) {
        if (!splatted(sc, i)) continue;
        const lucent_surfels *cloud = sc->objects[i].points;
        if (cloud)
            e = lucent_surfels_from_points(cloud->levels[0].count, cloud->positions, cloud->normals,
                                           cloud->radii_given ? cloud->radii : NULL, cloud->colors, &d, &sf[i]);
        else
            e = lucent_surfels_from_mesh(sc->objects[i].mesh, &d, &sf[i]);
        if (e != LUCENT_OK) {
            e = lucent_error_context(e, "object \"%s\": surfels", sc->objects[i].name);
            break;
        }
        points_object *o = &st->objects[i];
        o->splat = true, o->base = total, o->level_count = sf[i]->level_count;
        memcpy(o->levels, sf[i]->levels, sizeof o->levels);
        total += sf[i]->count, child_total += sf[i]->child_start[sf[i]->count];
    }
    float *data = e == LUCENT_OK ? malloc((total ? total : 1) * 12 * sizeof *data) : NULL;
    uint32_t *start = data ? malloc((total + 1) * sizeof *start) : NULL;
    uint32_t *children = start ? malloc((child_total ? child_total : 1) * sizeof *children) : NULL;
    if (e == LUCENT_OK && !children) e = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory (%zu surfels)", total);
    size_t child_base = 0;
    for (int i = 0; i < sc->object_count && e == LUCENT_OK; i++) {
        const lucent_surfels *f = sf[i];
        if (!f) continue;
        double albedo[3];
        gl_renderer_object_albedo(r, i, albedo);
        size_t b = st->objects[i].base;
        for (size_t j = 0; j < f->count; j++) {
            float *q = data + 12 * (b + j);
            for (int c = 0; c < 3; c++) {
                q[c] = f->positions[3 * j + c], q[4 + c] = f->normals[3 * j + c];
                q[8 + c] = f->colors ? f->colors[3 * j + c] : (float)albedo[c];
            }
            q[3] = f->radii[j], q[7] = 0, q[11] = 0;
            start[b + j] = (uint32_t)(child_base + f->child_start[j]);
        }
        for (size_t k = 0; k < f->child_start[f->count]; k++) children[child_base + k] = (uint32_t)(b + f->children[k]);
        child_base += f->child_start[f->count];
    }
    if (e == LUCENT_OK) {
        start[total] = (uint32_t)child_base;
        GLuint bufs[4];
        glCreateBuffers(4, bufs);
        st->surfels = bufs[0], st->radiance = bufs[1], st->child_start = bufs[2], st->children = bufs[3];
        glNamedBufferData(st->surfels, (GLsizeiptr)((total ? total : 1) * 12 * sizeof *data), data, GL_STATIC_DRAW);
        glNamedBufferData(st->radiance, (GLsizeiptr)((total ? total : 1) * 4 * sizeof(float)), NULL, GL_DYNAMIC_COPY);
        glNamedBufferData(st->child_start, (GLsizeiptr)((total + 1) * sizeof *start), start, GL_STATIC_DRAW);
        glNamedBufferData(st->children, (GLsizeiptr)((child_total ? child_total : 1) * sizeof *children), children,
                          GL_STATIC_DRAW);
        st->total = total;
        snprintf(st->surfel_key, sizeof st->surfel_key, "%s", key);
        e = gl_check("uploading the surfels");
    }
    for (int i = 0; i < sc->object_count; i++) lucent_surfels_destroy(sf[i]);
    free(sf), free(data), free(start), free(children);
    return e;
}

static lucent_status programs(lucent_renderer *r, points_state *st)
{
    gl_programs *p = &r->programs;
    lucent_status e =
        gl_programs_get(p, "points_splat.vert.glsl", "points_splat.frag.glsl", "#define PASS 0\n", &st->visibility);
    st->shadow = st->visibility;
    if (e == LUCENT_OK)
        e = gl_programs_get(p, "points_splat.vert.glsl", "points_splat.frag.glsl", "#define PASS 1\n", &st->attributes);
    if (e == LUCENT_OK)
        e = gl_programs_get(p, "points_splat.vert.glsl", "points_splat.frag.glsl", "#define PASS 2\n", &st->disks);
    if (e == LUCENT_OK)
        e = gl_programs_get(p, "points_surfel.vert.glsl", "shadow.frag.glsl", "#define STAGE 0\n", &st->irradiance);
    if (e == LUCENT_OK)
        e = gl_programs_get(p, "points_surfel.vert.glsl", "shadow.frag.glsl", "#define STAGE 1\n", &st->restrict_);
    if (e == LUCENT_OK)
        e = gl_programs_get(p, "points_diffuse.vert.glsl", "points_diffuse.frag.glsl", NULL, &st->diffuse);
    if (e == LUCENT_OK) e = gl_programs_get(p, "fullscreen.vert.glsl", "points_resolve.frag.glsl", NULL, &st->resolve);
    if (e == LUCENT_OK) e = gl_programs_get(p, "fullscreen.vert.glsl", "points_shade.frag.glsl", NULL, &st->shade);
    if (e == LUCENT_OK) e = gl_programs_get(p, "scene.vert.glsl", "points_mesh.frag.glsl", NULL, &st->mesh);
    return e;
}

/* The sum of Gaussians of every material: d'Eon's table or the bake's fit. */
static lucent_status prepare_sog(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    if (s->points.sog_source == LUCENT_SOG_DEON) {
        for (int m = 0; m < r->tables.count; m++) lucent_sog_deon_skin(&st->sog[m]);
        return LUCENT_OK;
    }
    lucent_bake_desc d = gl_renderer_bake_desc(r, s, LUCENT_BAKE_SOG);
    d.sog_count = s->points.sog;
    lucent_status e = gl_tables_bake(&r->tables, &d, r->cache);
    for (int m = 0; e == LUCENT_OK && m < r->tables.count; m++) st->sog[m] = r->tables.baked[m].sog;
    return e;
}

static lucent_status prepare(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    points_state *st = state;
    lucent_status e = build_surfels(r, st, s);
    if (e == LUCENT_OK && s->points.style == LUCENT_POINTS_DIFFUSION) e = prepare_sog(r, st, s);
    if (e == LUCENT_OK && s->points.style == LUCENT_POINTS_DIFFUSION && s->translucency.enabled)
        e = gl_translucency_prepare(r, s);
    if (e == LUCENT_OK) e = resize(st, r->targets.width, r->targets.height);
    if (e == LUCENT_OK) e = programs(r, st);
    return e;
}

/* ---- the passes ---- */

static void set1f(GLuint p, const char *name, double v)
{
    glProgramUniform1f(p, glGetUniformLocation(p, name), (float)v);
}
static void set1i(GLuint p, const char *name, int v) { glProgramUniform1i(p, glGetUniformLocation(p, name), v); }

static void invert(const double m[16], double dest[16]);

static void set_view(GLuint p, const double vp[16], int w, int h)
{
    float f[16];
    double inv[16];
    lucent_mat4_to_float(vp, f);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, f);
    invert(vp, inv);
    lucent_mat4_to_float(inv, f);
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_inv_vp"), 1, GL_FALSE, f);
    glProgramUniform2f(p, glGetUniformLocation(p, "u_viewport"), (float)w, (float)h);
}

/* The general 4x4 inverse (cofactors); the camera and light matrices are invertible. */
static void invert(const double m[16], double d[16])
{
    double a[16];
    a[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
           m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    a[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
           m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    a[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
           m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    a[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
            m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    a[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
           m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    a[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
           m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    a[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
           m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    a[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
            m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    a[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] -
           m[13] * m[3] * m[6];
    a[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
           m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    a[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
            m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    a[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
            m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    a[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] +
           m[9] * m[3] * m[6];
    a[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] -
           m[8] * m[3] * m[6];
    a[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] +
            m[8] * m[3] * m[5];
    a[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] -
            m[8] * m[2] * m[5];
    double det = m[0] * a[0] + m[1] * a[4] + m[2] * a[8] + m[3] * a[12];
    for (int i = 0; i < 16; i++) d[i] = a[i] / det;
}

static void bind_buffers(const points_state *st)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, st->surfels);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, st->radiance);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, st->child_start);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, st->children);
}

/* Draws the level-0 splats of every splatted object with program p (for the shadow maps, only the
 * objects without triangles: the core has drawn the others' faces into the maps). */
static void draw_splats(const lucent_renderer *r, const points_state *st, GLuint p, bool camera)
{
    glUseProgram(p);
    glBindVertexArray(r->empty_vao);
    for (int i = 0; i < st->object_count; i++) {
        const points_object *o = &st->objects[i];
        if (!o->splat || (!camera && r->scene->objects[i].mesh->face_count > 0)) continue;
        const lucent_scene_object *so = &r->scene->objects[i];
        set1i(p, "u_first", (int)o->base);
        set1i(p, "u_cull", camera);
        set1f(p, "u_f0", so->specular_f0);
        set1f(p, "u_roughness", so->roughness);
        set1f(p, "u_object", i);
        set1f(p, "u_material", r->tables.object_material[i]);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)o->levels[0].count);
    }
}

static void splat_uniforms(GLuint p, const lucent_render_settings *s)
{
    set1f(p, "u_radius_scale", s->points.radius_scale);
    set1f(p, "u_filter_px", s->points.filter_px);
    set1f(p, "u_epsilon", s->points.depth_epsilon);
    set1f(p, "u_cutoff", s->points.cutoff);
}

/* (1) The splats of point clouds into each light's shadow layer, over the triangles the core drew
 * (objects made from a mesh cast their faces' shadow, the same surface). */
static void pass_shadow(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    gl_shadows *sh = &r->shadows;
    splat_uniforms(st->shadow, s);
    for (int i = 0; i < sh->light_count; i++) {
        const gl_light *g = &sh->lights[i];
        if (g->layer < 0) continue;
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, sh->fbo);
        glNamedFramebufferTextureLayer(sh->fbo, GL_DEPTH_ATTACHMENT, sh->tex, 0, g->layer);
        glViewport(0, 0, sh->size, sh->size);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        set_view(st->shadow, g->matrix, sh->size, sh->size);
        draw_splats(r, st, st->shadow, false);
    }
    glDisable(GL_DEPTH_TEST);
    gl_timer_mark(&r->timer, "splat shadow");
}

/* The meshes that are not splatted, with the points' attribute outputs. */
static void draw_meshes(const lucent_renderer *r, const points_state *st)
{
    GLuint p = st->mesh;
    glUseProgram(p);
    for (int i = 0; i < r->scene->object_count; i++) {
        const lucent_scene_object *o = &r->scene->objects[i];
        if (!o->visible || st->objects[i].splat) continue;
        double a[3];
        gl_renderer_object_albedo(r, i, a);
        glProgramUniform3f(p, glGetUniformLocation(p, "u_albedo"), (float)a[0], (float)a[1], (float)a[2]);
        set1f(p, "u_f0", o->specular_f0);
        set1f(p, "u_roughness", o->roughness);
        set1f(p, "u_object", i);
        set1f(p, "u_material", r->tables.object_material[i]);
        gl_meshes_draw(&r->meshes, i);
    }
}

/* (2) + (3): visibility and attribute splatting into the attribute targets. */
static void pass_splat(lucent_renderer *r, points_state *st, const lucent_render_settings *s, const double vp[16])
{
    int w = st->width, h = st->height;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st->fbo_g);
    glViewport(0, 0, w, h);
    for (int i = 0; i < G_COUNT; i++) glClearNamedFramebufferfv(st->fbo_g, GL_COLOR, i, (const float[4]){0});
    glClearNamedFramebufferfv(st->fbo_g, GL_DEPTH, 0, (const float[1]){1});
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    bool disks = s->points.style == LUCENT_POINTS_DISKS;
    if (!disks) {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthFunc(GL_LESS);
        splat_uniforms(st->visibility, s);
        set_view(st->visibility, vp, w, h);
        draw_splats(r, st, st->visibility, true);
        draw_meshes(r, st);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl_timer_mark(&r->timer, "visibility");
        glDepthMask(GL_FALSE);
        glDepthFunc(GL_LEQUAL);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glDisablei(GL_BLEND, G_OBJECT);
    } else
        glDepthFunc(GL_LESS);
    GLuint p = disks ? st->disks : st->attributes;
    splat_uniforms(p, s);
    set_view(p, vp, w, h);
    draw_splats(r, st, p, true);
    draw_meshes(r, st);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    gl_timer_mark(&r->timer, "attributes");
}

/* (4a) The radiance of every surfel: level 0 from the lights, the coarser levels averaged. */
static void pass_irradiance(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    glEnable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(r->empty_vao);
    gl_shadows_bind(&r->shadows);
    glBindTextureUnit(4, r->tables.transmit_tex ? r->tables.transmit_tex : r->dummy_tex);
    if (r->tables.sheet_tex) glBindTextureUnit(GL_SHEET_UNIT, r->tables.sheet_tex);
    GLuint p = st->irradiance;
    glUseProgram(p);
    set1i(p, "u_impulse", s->points.impulse);
    set1f(p, "u_shadow_offset", 1.5);
    for (int i = 0; i < st->object_count; i++) {
        const points_object *o = &st->objects[i];
        if (!o->splat) continue;
        gl_translucency_uniforms(r, s, i, p, s->translucency.enabled);
        set1i(p, "u_first", (int)o->base);
        set1f(p, "u_material", r->tables.object_material[i]);
        glDrawArrays(GL_POINTS, 0, (GLsizei)o->levels[0].count);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(st->restrict_);
    for (int l = 1; l < LUCENT_SURFEL_MAX_LEVELS; l++) {
        bool any = false;
        for (int i = 0; i < st->object_count; i++) {
            const points_object *o = &st->objects[i];
            if (!o->splat || l >= o->level_count) continue;
            set1i(st->restrict_, "u_first", (int)(o->base + o->levels[l].first));
            glDrawArrays(GL_POINTS, 0, (GLsizei)o->levels[l].count);
            any = true;
        }
        if (!any) break;
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    gl_shadows_unbind();
    glDisable(GL_RASTERIZER_DISCARD);
    gl_timer_mark(&r->timer, "irradiance");
}

/* The coarsest level of o whose spacing is at most level_spacing standard deviations. */
static int level_for(const points_object *o, double variance, double level_spacing)
{
    int l = 0;
    while (l + 1 < o->level_count && o->levels[l + 1].spacing <= level_spacing * sqrt(variance)) l++;
    return l;
}

/* (4b) One splatting per Gaussian of each object's material, normalised, weighted and summed. */
static void pass_diffusion(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    int w = st->width, h = st->height;
    for (int i = 0; i < 2; i++) glClearNamedFramebufferfv(st->fbo_sum, GL_COLOR, i, (const float[4]){0});
    glBindVertexArray(r->empty_vao);
    glBindTextureUnit(5, st->g_tex[G_POSITION]);
    glBindTextureUnit(6, st->g_tex[G_NORMAL]);
    glBindTextureUnit(7, st->g_tex[G_OBJECT]);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    GLuint d = st->diffuse, rs = st->resolve;
    set1f(d, "u_radius_scale", s->points.radius_scale);
    set1f(d, "u_cutoff", s->points.cutoff);
    set1f(d, "u_support", s->points.sog_cutoff);
    glProgramUniform2f(d, glGetUniformLocation(d, "u_viewport"), (float)w, (float)h);
    for (int i = 0; i < st->object_count; i++) {
        const points_object *o = &st->objects[i];
        if (!o->splat) continue;
        int m = r->tables.object_material[i];
        const lucent_sog *g = &st->sog[m];
        double sum[3] = {0, 0, 0};
        for (int k = 0; k < g->count; k++)
            for (int c = 0; c < 3; c++) sum[c] += g->weight[c][k];
        for (int k = 0; k < g->count; k++) {
            double v = g->variance[0][k];
            int l = level_for(o, v, s->points.level_spacing);
            st->gaussian_level[m][k] = l;
            glClearNamedFramebufferfv(st->fbo_level, GL_COLOR, 0, (const float[4]){0});
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st->fbo_level);
            glViewport(0, 0, w, h);
            glUseProgram(d);
            set1i(d, "u_first", (int)(o->base + o->levels[l].first));
            set1f(d, "u_variance", v);
            set1f(d, "u_object", i);
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)o->levels[l].count);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, st->fbo_sum);
            glUseProgram(rs);
            glBindTextureUnit(5, st->level_tex);
            glProgramUniform3f(
                rs, glGetUniformLocation(rs, "u_weight"), (float)(sum[0] > 0 ? g->weight[0][k] / sum[0] : 0),
                (float)(sum[1] > 0 ? g->weight[1][k] / sum[1] : 0), (float)(sum[2] > 0 ? g->weight[2][k] / sum[2] : 0));
            set1f(rs, "u_object", i);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindTextureUnit(5, st->g_tex[G_POSITION]);
        }
    }
    glDisable(GL_BLEND);
    gl_timer_mark(&r->timer, "diffusion");
}

/* (5) Normalisation, the diffused radiance or Lambert, the specular. */
static void pass_shade(lucent_renderer *r, points_state *st, const lucent_render_settings *s)
{
    GLuint p = st->shade;
    const double *bg = s->view.background, *amb = r->shadows.ambient;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->targets.fbo_final);
    glViewport(0, 0, r->targets.width, r->targets.height);
    glUseProgram(p);
    glBindVertexArray(r->empty_vao);
    gl_shadows_bind(&r->shadows);
    glBindTextureUnit(0, st->sum_tex[0]);
    glBindTextureUnit(8, st->sum_tex[1]);
    glBindTextureUnit(3, st->g_tex[G_ALBEDO]);
    glBindTextureUnit(5, st->g_tex[G_POSITION]);
    glBindTextureUnit(6, st->g_tex[G_NORMAL]);
    glBindTextureUnit(7, st->g_tex[G_OBJECT]);
    set1i(p, "u_diffusion", s->points.style == LUCENT_POINTS_DIFFUSION);
    set1i(p, "u_weights_out", s->points.weights);
    set1f(p, "u_shadow_offset", 1.5);
    glProgramUniform3f(p, glGetUniformLocation(p, "u_background"), (float)(bg[0] + amb[0]), (float)(bg[1] + amb[1]),
                       (float)(bg[2] + amb[2]));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl_shadows_unbind();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl_timer_mark(&r->timer, "shade");
}

static lucent_status draw(lucent_renderer *r, void *state, const lucent_render_settings *s)
{
    points_state *st = state;
    double vp[16];
    gl_renderer_view_proj(r, vp);
    bind_buffers(st);
    bool clouds = false;
    for (int i = 0; i < st->object_count; i++)
        clouds = clouds || (st->objects[i].splat && r->scene->objects[i].mesh->face_count == 0);
    if (clouds) pass_shadow(r, st, s);
    pass_splat(r, st, s, vp);
    if (s->points.style == LUCENT_POINTS_DIFFUSION && st->total > 0) {
        pass_irradiance(r, st, s);
        pass_diffusion(r, st, s);
    }
    pass_shade(r, st, s);
    return LUCENT_OK;
}

/* ---- the sidecar ---- */

static void sidecar(const lucent_renderer *r, const void *state, const lucent_render_settings *s, cJSON *root)
{
    const points_state *st = state;
    cJSON *pts = cJSON_AddObjectToObject(root, "points");
    if (!pts) return;
    cJSON *objs = cJSON_AddArrayToObject(pts, "objects");
    for (int i = 0; objs && i < st->object_count; i++) {
        const points_object *o = &st->objects[i];
        cJSON *j = cJSON_CreateObject();
        if (!j) break;
        cJSON_AddStringToObject(j, "name", r->scene->objects[i].name);
        cJSON_AddBoolToObject(j, "splatted", o->splat);
        cJSON *lv = cJSON_AddArrayToObject(j, "levels");
        for (int l = 0; lv && l < o->level_count; l++) {
            cJSON *e = cJSON_CreateObject();
            if (!e) break;
            cJSON_AddNumberToObject(e, "surfels", (double)o->levels[l].count);
            cJSON_AddNumberToObject(e, "spacing_mm", o->levels[l].spacing);
            cJSON_AddItemToArray(lv, e);
        }
        cJSON_AddItemToArray(objs, j);
    }
    if (s->points.style != LUCENT_POINTS_DIFFUSION) return;
    cJSON *list = cJSON_AddArrayToObject(pts, "sog");
    for (int m = 0; list && m < r->tables.count; m++) {
        const lucent_sog *g = &st->sog[m];
        cJSON *k = cJSON_CreateObject();
        if (!k) break;
        cJSON_AddStringToObject(k, "material", r->tables.material[m].name);
        cJSON_AddStringToObject(k, "source", sog_source_names(s->points.sog_source));
        lucent_json_add_numbers(k, "variances_mm2", g->variance[0], g->count);
        lucent_json_add_numbers(k, "weights_r", g->weight[0], g->count);
        lucent_json_add_numbers(k, "weights_g", g->weight[1], g->count);
        lucent_json_add_numbers(k, "weights_b", g->weight[2], g->count);
        double lv[LUCENT_SOG_MAX];
        for (int i = 0; i < g->count; i++) lv[i] = st->gaussian_level[m][i];
        lucent_json_add_numbers(k, "levels", lv, g->count);
        cJSON_AddItemToArray(list, k);
    }
}

static unsigned bakes(const lucent_renderer *r, const lucent_render_settings *s)
{
    (void)r;
    if (s->points.style != LUCENT_POINTS_DIFFUSION) return 0;
    return (s->points.sog_source == LUCENT_SOG_FIT ? LUCENT_BAKE_SOG : 0u) |
           gl_translucency_bakes(s, s->translucency.enabled);
}

const gl_method gl_method_points = {
    .name = "points",
    .settings = (const char *const[]){"splats", "radius_scale", "depth_epsilon", "cutoff", "sog", "sog_source",
                                      "sog_cutoff", "decimation", "level_spacing", "neighbours", "filter_px", "profile",
                                      "translucency", "transmittance", NULL},
    .variant = variant,
    .variant_doc = "sog<N> (a fit of N Gaussians), deon (d'Eon's skin table), brdf, disks",
    .bakes = bakes,
    .state_size = sizeof(points_state),
    .prepare = prepare,
    .draw = draw,
    .sidecar = sidecar,
    .release = release,
};
