/* The renderer on a thread of its own (issue 32 item 13): a method that costs seconds a frame on
 * llvmpipe (points, tsd) no longer stops the window. The thread owns a headless GL context
 * (lucent_gl_create on it: EGL, beside the window's own context, which draws only the panel and the
 * frames as textures), the renderer and the scene the renderer reads: a shallow copy of the
 * viewer's (its own lights and objects, the meshes shared, which nobody changes once loaded). The
 * window thread hands it a request (the camera, lights, materials, parts baked elsewhere and the
 * settings of A and B, copied) and keeps drawing the last finished frame; the thread renders A (and
 * B), reads them back, tonemaps them for the screen and hands them over. Calls that need the
 * renderer itself (creating it for a scene, dropping it) run on the thread while the window
 * thread waits. */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viewer.h"

/* ---- the thread's scene: the viewer's, shallow ---- */

static void copy_free(viewer_worker *w)
{
    free(w->scene.lights);
    free(w->scene.objects);
    memset(&w->scene, 0, sizeof w->scene);
}

static lucent_status copy_make(viewer_worker *w, const lucent_scene *sc)
{
    copy_free(w);
    w->scene = *sc;
    w->scene.json = NULL; /* the viewer's; the renderer does not read it */
    w->scene.lights = calloc((size_t)sc->light_count + 1, sizeof *sc->lights);
    w->scene.objects = calloc((size_t)sc->object_count + 1, sizeof *sc->objects);
    if (!w->scene.lights || !w->scene.objects)
        return copy_free(w), lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    memcpy(w->scene.lights, sc->lights, (size_t)sc->light_count * sizeof *sc->lights);
    memcpy(w->scene.objects, sc->objects, (size_t)sc->object_count * sizeof *sc->objects);
    return LUCENT_OK;
}

/* ---- frames ---- */

void viewer_frame_free(viewer_frame *f)
{
    for (int i = 0; i < 2; i++) {
        lucent_image_destroy(f->image[i]);
        free(f->rgba[i]);
    }
    lucent_image_destroy(f->mask);
    memset(f, 0, sizeof *f);
}

void viewer_request_free(viewer_request *q)
{
    free(q->lights);
    free(q->objects);
    for (int k = 0; k < q->adopt_count; k++) lucent_baked_free(&q->adopt[k]);
    memset(q, 0, sizeof *q);
}

/* Linear radiance to the bytes on the screen: exposure, the tonemap, sRGB (present.frag.glsl's
 * steps, with the image module's functions). */
lucent_status viewer_to_rgba(const lucent_image *img, const lucent_tonemap_desc *tm, bool encode, uint8_t **dest)
{
    size_t n = (size_t)img->width * img->height;
    uint8_t *rgba = malloc(4 * n);
    if (!rgba) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    float scale = tm ? exp2f(tm->exposure) : 1.0f;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 4; c++) {
            float x = 1.0f;
            if (c < 3) {
                x = img->data[i * img->channels + (c < img->channels ? c : 0)];
                if (tm) x = lucent_tonemap_value(tm->op, fmaxf(x, 0.0f) * scale);
                if (encode) x = lucent_srgb_encode(fminf(fmaxf(x, 0.0f), 1.0f));
                if (!(x == x)) x = 0;
            }
            rgba[4 * i + c] = (uint8_t)lroundf(255 * fminf(fmaxf(x, 0.0f), 1.0f));
        }
    *dest = rgba;
    return LUCENT_OK;
}

static lucent_status apply(viewer_worker *w, viewer_request *q)
{
    lucent_scene *sc = &w->scene;
    if (q->lights && q->light_count == sc->light_count)
        memcpy(sc->lights, q->lights, (size_t)sc->light_count * sizeof *sc->lights);
    if (q->objects && q->object_count == sc->object_count)
        for (int i = 0; i < sc->object_count; i++) {
            sc->objects[i].material = q->objects[i].material;
            memcpy(sc->objects[i].albedo, q->objects[i].albedo, sizeof sc->objects[i].albedo);
        }
    lucent_status st = q->changed ? lucent_renderer_scene_changed(w->r, q->changed) : LUCENT_OK;
    for (int k = 0; k < q->adopt_count && st == LUCENT_OK; k++) {
        st = lucent_renderer_adopt_baked(w->r, &q->adopt_material[k], &q->adopt[k]);
        if (st == LUCENT_ERR_NOT_FOUND) st = LUCENT_OK; /* a material the objects no longer have */
    }
    return st;
}

static lucent_status render(viewer_worker *w, viewer_request *q, viewer_frame *f)
{
    lucent_status st = apply(w, q);
    f->gen = q->gen, f->count = q->count;
    for (int i = 0; i < q->count && st == LUCENT_OK; i++) {
        w->scene.camera = q->camera[i];
        lucent_render_result res = {0};
        st = lucent_render(w->r, &q->settings[i], &res);
        if (st == LUCENT_OK) {
            const lucent_view_settings *vs = &q->settings[i].view;
            st = viewer_to_rgba(res.image, &(lucent_tonemap_desc){.op = vs->tonemap, .exposure = (float)vs->exposure},
                                true, &f->rgba[i]);
            f->times[i] = res.times;
            f->width = res.image->width, f->height = res.image->height;
            f->image[i] = res.image, res.image = NULL; /* moved */
            if (i == 0) f->mask = res.mask, res.mask = NULL;
        }
        lucent_render_result_free(&res);
    }
    return st;
}

static void *worker_main(void *arg)
{
    viewer *v = arg;
    viewer_worker *w = &v->worker;
    lucent_gl_desc gd = {.platform = LUCENT_GL_AUTO, .ignore_env = w->window};
    lucent_status st = lucent_gl_create(&gd, &w->gl);
    pthread_mutex_lock(&w->lock);
    w->started = true, w->start_status = st;
    if (st != LUCENT_OK) snprintf(w->start_error, sizeof w->start_error, "%s", lucent_last_error());
    pthread_cond_broadcast(&w->done);
    while (st == LUCENT_OK && !w->quit) {
        if (!w->has_request && !w->call) {
            pthread_cond_wait(&w->wake, &w->lock);
            continue;
        }
        w->busy = true;
        if (w->call) { /* the window thread waits for it */
            pthread_mutex_unlock(&w->lock);
            lucent_status cs = w->call(v, w->call_arg);
            if (cs != LUCENT_OK) snprintf(w->call_error, sizeof w->call_error, "%s", lucent_last_error());
            pthread_mutex_lock(&w->lock);
            w->call_status = cs;
            w->call = NULL, w->busy = false;
            pthread_cond_broadcast(&w->done);
            continue;
        }
        viewer_request q = w->request; /* moved */
        memset(&w->request, 0, sizeof w->request);
        w->has_request = false;
        pthread_mutex_unlock(&w->lock);
        viewer_frame f = {0};
        double t0 = lucent_clock_ms();
        f.status = w->r ? render(w, &q, &f) : lucent_error(LUCENT_ERR_GL, "no renderer");
        if (f.status != LUCENT_OK) snprintf(f.error, sizeof f.error, "%s", lucent_last_error());
        f.ms = lucent_clock_ms() - t0;
        viewer_request_free(&q);
        pthread_mutex_lock(&w->lock);
        viewer_frame_free(&w->frame); /* one not taken is replaced */
        w->frame = f, w->has_frame = true, w->busy = false, w->frames++;
        pthread_cond_broadcast(&w->done);
        if (w->window) glfwPostEmptyEvent(); /* the window thread may be waiting for events */
    }
    pthread_mutex_unlock(&w->lock);
    lucent_renderer_destroy(w->r);
    w->r = NULL;
    copy_free(w);
    lucent_gl_destroy(w->gl);
    w->gl = NULL;
    return NULL;
}

lucent_status viewer_worker_start(viewer *v)
{
    viewer_worker *w = &v->worker;
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    pthread_cond_init(&w->done, NULL);
    w->window = v->window != NULL;
    if (pthread_create(&w->thread, NULL, worker_main, v) != 0)
        return lucent_error(LUCENT_ERR_INTERNAL, "cannot start the render thread");
    w->running = true;
    pthread_mutex_lock(&w->lock);
    while (!w->started) pthread_cond_wait(&w->done, &w->lock);
    lucent_status st = w->start_status;
    pthread_mutex_unlock(&w->lock);
    if (st != LUCENT_OK) {
        pthread_join(w->thread, NULL);
        w->running = false;
        return lucent_error(st, "%s", w->start_error);
    }
    return LUCENT_OK;
}

void viewer_worker_stop(viewer *v)
{
    viewer_worker *w = &v->worker;
    if (!w->running) return;
    pthread_mutex_lock(&w->lock);
    w->quit = true;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    w->running = false;
    viewer_request_free(&w->request);
    viewer_frame_free(&w->frame);
    pthread_mutex_destroy(&w->lock);
    pthread_cond_destroy(&w->wake);
    pthread_cond_destroy(&w->done);
}

/* Runs fn on the render thread once the frame under way is done; waits for it. */
static lucent_status worker_call(viewer *v, lucent_status (*fn)(viewer *, void *), void *arg)
{
    viewer_worker *w = &v->worker;
    if (!w->running) return lucent_error(LUCENT_ERR_INTERNAL, "the render thread is not running");
    pthread_mutex_lock(&w->lock);
    while (w->call) pthread_cond_wait(&w->done, &w->lock);
    w->call = fn, w->call_arg = arg;
    pthread_cond_broadcast(&w->wake);
    while (w->call) pthread_cond_wait(&w->done, &w->lock);
    lucent_status st = w->call_status;
    pthread_mutex_unlock(&w->lock);
    return st == LUCENT_OK ? st : lucent_error(st, "%s", w->call_error);
}

static lucent_status call_create(viewer *v, void *arg)
{
    (void)arg;
    viewer_worker *w = &v->worker;
    lucent_renderer_destroy(w->r);
    w->r = NULL;
    lucent_status st = copy_make(w, v->scene);
    lucent_renderer_desc rd = lucent_renderer_defaults();
    rd.pool = v->opt.pool;
    rd.cache_dir = v->opt.cache_dir;
    if (st == LUCENT_OK) st = lucent_renderer_create(w->gl, &w->scene, &rd, &w->r);
    v->r = w->r;
    return st;
}

static lucent_status call_drop(viewer *v, void *arg)
{
    (void)arg;
    viewer_worker *w = &v->worker;
    lucent_renderer_destroy(w->r);
    w->r = v->r = NULL;
    copy_free(w);
    viewer_request_free(&w->request); /* for the old scene */
    w->has_request = false;
    viewer_frame_free(&w->frame);
    w->has_frame = false;
    return LUCENT_OK;
}

lucent_status viewer_worker_create_renderer(viewer *v) { return worker_call(v, call_create, NULL); }

void viewer_worker_drop_renderer(viewer *v)
{
    if (v->worker.running) worker_call(v, call_drop, NULL);
}

bool viewer_worker_busy(viewer *v)
{
    viewer_worker *w = &v->worker;
    pthread_mutex_lock(&w->lock);
    bool busy = w->busy || w->has_request;
    pthread_mutex_unlock(&w->lock);
    return busy;
}

bool viewer_worker_submit(viewer *v, viewer_request *q)
{
    viewer_worker *w = &v->worker;
    pthread_mutex_lock(&w->lock);
    bool free_now = !w->busy && !w->has_request;
    if (free_now) {
        w->request = *q; /* moved */
        memset(q, 0, sizeof *q);
        w->has_request = true;
        pthread_cond_broadcast(&w->wake);
    }
    pthread_mutex_unlock(&w->lock);
    return free_now;
}

bool viewer_worker_take(viewer *v, viewer_frame *dest, double wait_ms)
{
    viewer_worker *w = &v->worker;
    pthread_mutex_lock(&w->lock);
    if (!w->has_frame && wait_ms > 0 && (w->busy || w->has_request)) {
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        long long ns = until.tv_nsec + (long long)(wait_ms * 1e6);
        until.tv_sec += (time_t)(ns / 1000000000), until.tv_nsec = (long)(ns % 1000000000);
        while (!w->has_frame && (w->busy || w->has_request))
            if (pthread_cond_timedwait(&w->done, &w->lock, &until) != 0) break;
    }
    bool have = w->has_frame;
    if (have) {
        *dest = w->frame; /* moved */
        memset(&w->frame, 0, sizeof w->frame);
        w->has_frame = false;
    }
    pthread_mutex_unlock(&w->lock);
    return have;
}
