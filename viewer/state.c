/* The viewer's state: the scene and its renderer, the camera and lights moved by the mouse, the
 * settings and materials the panel edits, and the bakes those need, run on a thread of their own
 * while the window keeps drawing what was baked before (viewer.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "viewer.h"

void viewer_status(viewer *v, bool error, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->status, sizeof v->status, fmt, ap);
    va_end(ap);
    v->status_error = error;
    if (!v->opt.quiet || error) fprintf(error ? stderr : stdout, "%s%s\n", error ? "lucent: " : "", v->status);
    fflush(stdout);
}

/* ---- small vector helpers (directions only) ---- */

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double d[3])
{
    double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(d, t, sizeof t);
}

static bool normalize3(double a[3])
{
    double n = sqrt(dot3(a, a));
    if (!(n > 0)) return false;
    for (int i = 0; i < 3; i++) a[i] /= n;
    return true;
}

/* Rotates v about the unit axis by angle radians (Rodrigues' formula). */
static void rotate3(double v[3], const double axis[3], double angle)
{
    double c = cos(angle), s = sin(angle), k[3], d = dot3(axis, v), r[3];
    cross3(axis, v, k);
    for (int i = 0; i < 3; i++) r[i] = v[i] * c + k[i] * s + axis[i] * d * (1 - c);
    memcpy(v, r, sizeof r);
}

/* The camera's right and up axes. */
static void camera_axes(const lucent_camera *c, double right[3], double up[3])
{
    double f[3];
    for (int i = 0; i < 3; i++) f[i] = c->target[i] - c->position[i];
    normalize3(f);
    cross3(f, c->up, right);
    if (!normalize3(right)) right[0] = 1, right[1] = right[2] = 0;
    cross3(right, f, up);
    normalize3(up);
}

/* Near and far planes around the scene's bounding sphere from where the camera stands. */
static void fit_planes(const viewer *v, lucent_camera *cam)
{
    double lo[3], hi[3], c[3], rr = 0, d = 0;
    lucent_scene_bounds(v->scene, lo, hi);
    if (!(lo[0] <= hi[0])) return;
    for (int i = 0; i < 3; i++) {
        c[i] = 0.5 * (lo[i] + hi[i]);
        rr += 0.25 * (hi[i] - lo[i]) * (hi[i] - lo[i]);
        d += (cam->position[i] - c[i]) * (cam->position[i] - c[i]);
    }
    double R = sqrt(rr), dist = sqrt(d);
    cam->near_plane = fmax(0.9 * (dist - R), 1e-3 * fmax(R, dist));
    cam->far_plane = 1.1 * (dist + R);
}

/* Takes a moved camera when every number of it is finite and it stands off its target (issue 32
 * item 14: a NaN camera was drawn, and saved as null); else keeps the camera and says why. */
static lucent_status camera_take(viewer *v, const char *what, lucent_camera *c)
{
    fit_planes(v, c);
    double d = 0;
    bool finite = isfinite(c->fov_y) && isfinite(c->near_plane) && isfinite(c->far_plane);
    for (int i = 0; i < 3; i++) {
        finite = finite && isfinite(c->position[i]) && isfinite(c->target[i]) && isfinite(c->up[i]);
        d += (c->position[i] - c->target[i]) * (c->position[i] - c->target[i]);
    }
    if (!finite || !isfinite(d))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: the camera would not be finite (it stays where it is)",
                            what);
    if (!(d > 0) || !(c->near_plane > 0) || !(c->far_plane > c->near_plane))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: the camera would stand on its target (it stays where it is)", what);
    v->scene->camera = *c;
    v->gen++;
    return LUCENT_OK;
}

void viewer_shown_camera(const viewer *v, lucent_camera *dest)
{
    *dest = v->scene->camera;
    /* A frame narrower than the scene's image (its aspect) widens the vertical field of view so that
     * the scene's horizontal field still fits: side by side halves, a tall window (issue 35:
     * keeping the vertical field of view cropped the object in both halves). */
    int rect[4];
    viewer_view_rect(v, rect);
    int w = v->layout == VIEWER_SIDE ? rect[2] / 2 : rect[2], h = rect[3];
    if (v->reference && v->match_reference) w = v->reference->width, h = v->reference->height;
    double view = (double)(w > 0 ? w : 1) / (h > 0 ? h : 1);
    double scene = (double)v->scene->render.view.width / v->scene->render.view.height;
    if (view < scene) {
        double t = tan(0.5 * dest->fov_y * M_PI / 180) * scene / view;
        dest->fov_y = fmin(2 * atan(t) * 180 / M_PI, 170.0);
    }
}

/* ---- camera and lights ---- */

lucent_status viewer_orbit(viewer *v, double yaw_deg, double pitch_deg)
{
    lucent_camera cam = v->scene->camera, *c = &cam;
    double off[3], up[3], right[3], cam_up[3];
    memcpy(up, c->up, sizeof up);
    if (!normalize3(up)) up[0] = 0, up[1] = 1, up[2] = 0;
    for (int i = 0; i < 3; i++) off[i] = c->position[i] - c->target[i];
    rotate3(off, up, -yaw_deg * M_PI / 180);
    camera_axes(
        &(lucent_camera){.target = {0, 0, 0}, .position = {off[0], off[1], off[2]}, .up = {up[0], up[1], up[2]}}, right,
        cam_up);
    double len = sqrt(dot3(off, off)), elev = acos(fmax(-1, fmin(1, dot3(off, up) / len))) * 180 / M_PI;
    double p = fmax(fmin(pitch_deg, elev - 2), elev - 178); /* never over the pole */
    rotate3(off, right, p * M_PI / 180);
    for (int i = 0; i < 3; i++) c->position[i] = c->target[i] + off[i];
    return camera_take(v, "orbit", c);
}

lucent_status viewer_pan(viewer *v, double dx, double dy)
{
    lucent_camera cam = v->scene->camera, *c = &cam, shown;
    viewer_shown_camera(v, &shown);
    int rect[4];
    viewer_view_rect(v, rect);
    double right[3], up[3], dist = 0;
    camera_axes(c, right, up);
    for (int i = 0; i < 3; i++) dist += (c->position[i] - c->target[i]) * (c->position[i] - c->target[i]);
    double mm = 2 * sqrt(dist) * tan(0.5 * shown.fov_y * M_PI / 180) / (rect[3] > 0 ? rect[3] : 1);
    for (int i = 0; i < 3; i++) {
        double m = (-dx * right[i] + dy * up[i]) * mm;
        c->position[i] += m, c->target[i] += m;
    }
    return camera_take(v, "pan", c);
}

lucent_status viewer_zoom(viewer *v, double factor)
{
    lucent_camera cam = v->scene->camera, *c = &cam;
    for (int i = 0; i < 3; i++) c->position[i] = c->target[i] + (c->position[i] - c->target[i]) * factor;
    return camera_take(v, "zoom", c);
}

void viewer_reset_camera(viewer *v)
{
    v->scene->camera = v->home;
    v->gen++;
}

lucent_status viewer_light_rotate(viewer *v, int light, double yaw_deg, double pitch_deg)
{
    if (light < 0 || light >= v->scene->light_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "light: no light %d (the scene has %d)", light,
                            v->scene->light_count);
    lucent_light *l = &v->scene->lights[light];
    double right[3], up[3];
    camera_axes(&v->scene->camera, right, up);
    if (l->type == LUCENT_LIGHT_ENVIRONMENT) return LUCENT_OK;
    bool dir = l->type == LUCENT_LIGHT_DIRECTIONAL;
    double d[3]; /* a point light turns about the camera's target */
    for (int i = 0; i < 3; i++) d[i] = dir ? l->direction[i] : l->position[i] - v->scene->camera.target[i];
    rotate3(d, up, yaw_deg * M_PI / 180);
    rotate3(d, right, pitch_deg * M_PI / 180);
    if (dir && !normalize3(d)) d[0] = NAN;
    for (int i = 0; i < 3; i++)
        if (!isfinite(d[i]) || !isfinite(d[i] + v->scene->camera.target[i]))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "light: the light would not be finite (it stays where it is)");
    for (int i = 0; i < 3; i++) {
        if (dir)
            l->direction[i] = d[i];
        else
            l->position[i] = d[i] + v->scene->camera.target[i];
    }
    v->changed |= LUCENT_RENDERER_LIGHTS; /* the render thread reads them again with the next frame */
    v->gen++;
    return LUCENT_OK;
}

/* ---- settings and materials: what is wanted ---- */

lucent_status viewer_set(viewer *v, const char *key, const char *value)
{
    const lucent_setting *s = lucent_setting_find(key, NULL);
    if (!s) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render.%s: no such setting", key);
    if (!strcmp(s->key, "method")) return viewer_method(v, value, false);
    lucent_render_settings t = v->wanted;
    lucent_status st = lucent_setting_set(&t, s, value);
    if (st == LUCENT_OK) st = lucent_render_settings_check(&t);
    if (st == LUCENT_OK) v->wanted = t;
    return st;
}

lucent_status viewer_method(viewer *v, const char *name, bool b)
{
    lucent_render_settings t = v->wanted;
    lucent_render_method m;
    lucent_status st = lucent_render_method_parse(name, &m, &t);
    if (st != LUCENT_OK) return st;
    if (b)
        v->method_b = m;
    else
        t.view.method = m;
    v->wanted = t; /* a variant ("ssss:svd3") sets the method's settings for both */
    return LUCENT_OK;
}

lucent_status viewer_material_preset(viewer *v, int object, const char *name)
{
    lucent_material m;
    lucent_status st = lucent_material_resolve(name, &m);
    if (st == LUCENT_OK) st = lucent_skin_resolve(&m); /* a spectral skin: its equivalent medium */
    if (st != LUCENT_OK) return st;
    v->wanted_material[object] = m;
    return LUCENT_OK;
}

void viewer_material_edited(viewer *v, int object)
{
    lucent_material *m = &v->wanted_material[object];
    if (strncmp(m->name, "custom", 6) != 0) {
        char name[LUCENT_MATERIAL_NAME_SIZE];
        snprintf(name, sizeof name, "custom (%.40s)", m->name);
        snprintf(m->name, sizeof m->name, "%s", name);
    }
}

lucent_render_settings viewer_frame_settings(const viewer *v, bool b, int width, int height)
{
    lucent_render_settings s = v->applied;
    if (b) s.view.method = v->applied_b;
    s.view.width = width > 0 ? width : 1, s.view.height = height > 0 ? height : 1;
    return s;
}

/* ---- the bakes ---- */

static bool same_material(const lucent_material *a, const lucent_material *b)
{
    return !strcmp(a->name, b->name) && !memcmp(a->sigma_a, b->sigma_a, sizeof a->sigma_a) &&
           !memcmp(a->sigma_s, b->sigma_s, sizeof a->sigma_s) && !memcmp(a->g, b->g, sizeof a->g) && a->eta == b->eta;
}

static bool same_baked(const lucent_baked *a, const lucent_baked *b)
{
    return a->have == b->have && !strcmp(a->profile_key, b->profile_key) && !strcmp(a->taps_key, b->taps_key) &&
           !strcmp(a->transmit_key, b->transmit_key) && !strcmp(a->sigma0_key, b->sigma0_key) &&
           !strcmp(a->sog_key, b->sog_key);
}

static bool settings_differ(const lucent_render_settings *a, const lucent_render_settings *b)
{
    lucent_render_settings x = *a, y = *b;
    x.view.width = y.view.width = 1, x.view.height = y.view.height = 1;
    char ta[256], tb[256];
    for (int g = 0; g < lucent_settings_group_count(); g++) {
        const lucent_settings_group *grp = lucent_settings_group_get(g);
        for (int i = 0; i < grp->count; i++) {
            lucent_setting_format(&x, &grp->settings[i], ta, sizeof ta);
            lucent_setting_format(&y, &grp->settings[i], tb, sizeof tb);
            if (strcmp(ta, tb)) return true;
        }
    }
    return false;
}

static bool materials_differ(const viewer *v)
{
    for (int i = 0; i < v->scene->object_count; i++)
        if (!same_material(&v->wanted_material[i], &v->scene->objects[i].material)) return true;
    return false;
}

static const unsigned k_parts[] = {LUCENT_BAKE_PROFILE, LUCENT_BAKE_TAPS, LUCENT_BAKE_TRANSMITTANCE, LUCENT_BAKE_SIGMA0,
                                   LUCENT_BAKE_SOG};
enum { PART_COUNT = sizeof k_parts / sizeof k_parts[0] };

static void *job_main(void *arg)
{
    viewer_job *j = arg;
    lucent_renderer_desc rd = lucent_renderer_defaults();
    lucent_status st = LUCENT_OK;
    for (int k = 0; k < j->count && st == LUCENT_OK; k++) {
        atomic_store(&j->at, k);
        for (int p = 0; p < PART_COUNT && st == LUCENT_OK; p++) {
            if (!(j->what & k_parts[p])) continue;
            atomic_store(&j->part, k_parts[p]);
            lucent_bake_desc d = {.what = k_parts[p],
                                  .settings = &j->settings,
                                  .profile_photons = rd.profile_photons,
                                  .transmit_photons = rd.transmit_photons,
                                  .sigma0_photons = rd.sigma0_photons,
                                  .pool = j->pool};
            st = lucent_material_bake(&j->material[k], &d, j->cache, &j->baked[k]);
            atomic_fetch_add(&j->step, 1);
        }
    }
    j->status = st;
    if (st != LUCENT_OK) snprintf(j->error, sizeof j->error, "%s", lucent_last_error());
    atomic_store(&j->done, true);
    return NULL;
}

/* The distinct materials of the wanted objects, each starting from what is baked for it already. */
static lucent_status job_start(viewer *v)
{
    viewer_job *j = &v->job;
    for (int k = 0; k < j->count; k++) lucent_baked_free(&j->baked[k]);
    j->count = 0;
    for (int i = 0; i < v->scene->object_count; i++) {
        const lucent_material *m = &v->wanted_material[i];
        int k = 0;
        while (k < j->count && !same_material(&j->material[k], m)) k++;
        if (k < j->count) continue;
        if (k == VIEWER_MAX_MATERIALS) return lucent_error(LUCENT_ERR_UNSUPPORTED, "more than 8 distinct materials");
        j->material[j->count] = *m;
        memset(&j->baked[j->count], 0, sizeof j->baked[0]);
        for (int b = 0; b < v->baked_count; b++)
            if (same_material(&v->baked_material[b], m)) {
                lucent_status st = lucent_baked_copy(&v->baked[b], &j->baked[j->count]);
                if (st != LUCENT_OK) return st;
            }
        j->count++;
    }
    memcpy(j->objects, v->wanted_material, (size_t)v->scene->object_count * sizeof *j->objects);
    j->settings = v->wanted;
    j->method_b = v->method_b;
    lucent_render_settings sb = v->wanted;
    sb.view.method = v->method_b;
    j->what =
        lucent_renderer_bakes(v->r, &v->wanted) | (v->layout != VIEWER_SINGLE ? lucent_renderer_bakes(v->r, &sb) : 0);
    j->steps = 0;
    for (int p = 0; p < PART_COUNT; p++) j->steps += (j->what & k_parts[p]) ? j->count : 0;
    atomic_store(&j->step, 0);
    atomic_store(&j->done, false);
    atomic_store(&j->at, 0);
    atomic_store(&j->part, 0u);
    j->cache = v->cache, j->pool = v->job_pool, j->status = LUCENT_OK, j->error[0] = '\0';
    j->started = lucent_clock_seconds();
    if (pthread_create(&j->thread, NULL, job_main, j) != 0)
        return lucent_error(LUCENT_ERR_INTERNAL, "cannot start the bake thread");
    j->running = true;
    return LUCENT_OK;
}

/* Applies a finished job: the materials into the scene and the renderer, the parts into the
 * renderer (only those that changed: adopting makes the methods upload again), the settings. */
static lucent_status job_apply(viewer *v)
{
    viewer_job *j = &v->job;
    lucent_status st = LUCENT_OK;
    bool mats = false;
    for (int i = 0; i < v->scene->object_count; i++) {
        lucent_scene_object *o = &v->scene->objects[i];
        if (same_material(&o->material, &j->objects[i])) continue;
        o->material = j->objects[i], mats = true;
        if (o->albedo_source == LUCENT_ALBEDO_FROM_MATERIAL) {
            lucent_material_derived d;
            lucent_material_derive(&o->material, &d);
            memcpy(o->albedo, d.rd, sizeof o->albedo);
        }
    }
    if (mats) v->changed |= LUCENT_RENDERER_MATERIALS; /* told to the renderer with the next frame */
    for (int k = 0; k < j->count && st == LUCENT_OK; k++) {
        bool known = false;
        for (int b = 0; b < v->baked_count; b++)
            known |= same_material(&v->baked_material[b], &j->material[k]) && same_baked(&v->baked[b], &j->baked[k]);
        if (known && !mats) continue;
        int a = 0; /* the latest parts of a material replace those not yet handed over */
        while (a < v->adopt_count && !same_material(&v->adopt_material[a], &j->material[k])) a++;
        if (a == VIEWER_MAX_MATERIALS) break;
        v->adopt_material[a] = j->material[k];
        st = lucent_baked_copy(&j->baked[k], &v->adopt[a]);
        if (a == v->adopt_count) v->adopt_count++;
    }
    for (int b = 0; b < v->baked_count; b++) lucent_baked_free(&v->baked[b]);
    for (int k = 0; k < j->count; k++) {
        v->baked_material[k] = j->material[k];
        v->baked[k] = j->baked[k]; /* moved */
        memset(&j->baked[k], 0, sizeof j->baked[k]);
    }
    v->baked_count = j->count, j->count = 0;
    if (st != LUCENT_OK) return st;
    v->applied = j->settings;
    v->applied_b = j->method_b;
    v->ready = true;
    v->gen++;
    return LUCENT_OK;
}

static void job_join(viewer *v)
{
    if (!v->job.running) return;
    pthread_join(v->job.thread, NULL);
    v->job.running = false;
}

void viewer_step(viewer *v)
{
    viewer_job *j = &v->job;
    if (j->running && atomic_load(&j->done)) {
        job_join(v);
        if (j->status != LUCENT_OK) {
            viewer_status(v, true, "bake failed: %s", j->error);
            v->bake_failed = true, v->first_failed = !v->ready;
            snprintf(v->bake_error, sizeof v->bake_error, "bake failed: %s", j->error);
            v->wanted = v->applied, v->method_b = v->applied_b; /* back to what works */
            for (int i = 0; i < v->scene->object_count; i++) v->wanted_material[i] = v->scene->objects[i].material;
            for (int k = 0; k < j->count; k++) lucent_baked_free(&j->baked[k]);
            j->count = 0;
        } else if (job_apply(v) != LUCENT_OK) {
            viewer_status(v, true, "%s", lucent_last_error());
        }
    }
    if (j->running) return;
    /* (the first bake failing is not tried again until something changes: it would fail again) */
    bool differ = (!v->ready && !v->first_failed) || settings_differ(&v->wanted, &v->applied) ||
                  v->method_b != v->applied_b || materials_differ(v);
    if (!differ) return;
    if (job_start(v) != LUCENT_OK) {
        viewer_status(v, true, "%s", lucent_last_error());
        return;
    }
    /* Most changes bake nothing (or little): apply them in this frame when they are done soon. */
    for (int i = 0; i < 40 && !atomic_load(&j->done); i++) nanosleep(&(struct timespec){0, 1000000}, NULL);
    if (atomic_load(&j->done)) viewer_step(v);
}

void viewer_settle(viewer *v)
{
    for (;;) {
        viewer_step(v);
        if (!v->job.running) {
            viewer_step(v); /* a change made while the last job ran */
            if (!v->job.running) return;
        }
        nanosleep(&(struct timespec){0, 5000000}, NULL);
    }
}

static const char *part_name(unsigned part)
{
    switch (part) {
    case LUCENT_BAKE_PROFILE: return "profile";
    case LUCENT_BAKE_TAPS: return "kernel taps";
    case LUCENT_BAKE_TRANSMITTANCE: return "transmittance";
    case LUCENT_BAKE_SIGMA0: return "sigma0 fit";
    case LUCENT_BAKE_SOG: return "sum of Gaussians";
    default: return "parts";
    }
}

bool viewer_baking(const viewer *v, float *fraction, char *label, size_t size)
{
    const viewer_job *j = &v->job;
    if (!j->running) return false;
    int at = atomic_load(&((viewer_job *)j)->at);
    *fraction = j->steps > 0 ? (float)atomic_load(&((viewer_job *)j)->step) / (float)j->steps : -1.0f;
    snprintf(label, size, "baking %s of %s: %.1f s", part_name(atomic_load(&((viewer_job *)j)->part)),
             at < j->count ? j->material[at].name : "", lucent_clock_seconds() - j->started);
    return true;
}

/* ---- the scene ---- */

static void file_time(const char *path, struct timespec *dest)
{
    struct stat st;
    memset(dest, 0, sizeof *dest);
    if (stat(path, &st) == 0) *dest = st.st_mtim;
}

void viewer_scene_close(viewer *v)
{
    job_join(v);
    for (int k = 0; k < v->job.count; k++) lucent_baked_free(&v->job.baked[k]);
    v->job.count = 0;
    for (int b = 0; b < v->baked_count; b++) lucent_baked_free(&v->baked[b]);
    v->baked_count = 0;
    for (int a = 0; a < v->adopt_count; a++) lucent_baked_free(&v->adopt[a]);
    v->adopt_count = 0, v->changed = 0;
    viewer_worker_drop_renderer(v); /* the render thread's copy shares the meshes of this scene */
    viewer_frame_free(&v->shown);
    lucent_scene_destroy(v->scene);
    free(v->wanted_material);
    free(v->job.objects);
    free(v->home_lights);
    v->home_lights = NULL;
    v->r = NULL, v->scene = NULL, v->wanted_material = NULL, v->job.objects = NULL, v->ready = false;
}

lucent_status viewer_scene_open(viewer *v)
{
    lucent_scene *scene = NULL;
    lucent_scene_load_desc ld = {.overrides = v->opt.sets, .override_count = v->opt.set_count};
    lucent_status st = lucent_scene_load(v->opt.scene, &ld, &scene);
    if (st != LUCENT_OK) return st;
    viewer_scene_close(v);
    v->scene = scene;
    v->home = scene->camera;
    v->home_lights = calloc((size_t)scene->light_count + 1, sizeof *v->home_lights);
    if (v->home_lights) memcpy(v->home_lights, scene->lights, (size_t)scene->light_count * sizeof *scene->lights);
    file_time(v->opt.scene, &v->mtime);
    v->wanted_material = calloc((size_t)scene->object_count + 1, sizeof *v->wanted_material);
    v->job.objects = calloc((size_t)scene->object_count + 1, sizeof *v->job.objects);
    if (!v->wanted_material || !v->job.objects) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < scene->object_count; i++) v->wanted_material[i] = scene->objects[i].material;
    st = viewer_worker_create_renderer(v); /* on the render thread, of a copy of the scene */
    if (st != LUCENT_OK) return st;
    v->wanted = scene->render;
    if (v->method_b == v->wanted.view.method || !v->ready)
        v->method_b = v->wanted.view.method == LUCENT_METHOD_LAMBERT ? LUCENT_METHOD_SSSS : LUCENT_METHOD_LAMBERT;
    v->applied = v->wanted, v->applied_b = v->method_b;
    if (v->object >= scene->object_count) v->object = 0;
    if (v->light >= scene->light_count) v->light = 0;
    v->gen++;
    return LUCENT_OK;
}
