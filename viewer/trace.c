/* A progressive path-traced reference (lucent/trace.h) on a thread of its own: the scene as the
 * viewer shows it when the trace starts (its JSON, at the frame's size), one sample per pixel per
 * pass; each pass's estimate replaces the reference, so the error map and the relative RMS error
 * sharpen as the window keeps drawing. */
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viewer.h"

static void *trace_main(void *arg)
{
    viewer_trace *t = arg;
    lucent_scene *scene = NULL;
    lucent_tracer *tracer = NULL;
    lucent_status st = lucent_scene_parse(t->json, "progressive trace", t->base_dir, NULL, &scene);
    if (st == LUCENT_OK) st = lucent_tracer_create(scene, NULL, &tracer);
    while (st == LUCENT_OK && !atomic_load(&t->stop)) {
        lucent_trace_result res = {0};
        st = lucent_tracer_render(tracer, &(lucent_trace_desc){.spp = 1, .pool = t->pool, .time_limit = -1}, &res);
        if (st == LUCENT_OK) {
            pthread_mutex_lock(&t->lock);
            lucent_image_destroy(t->image);
            t->image = res.image, res.image = NULL; /* moved */
            t->spp = res.spp, t->seconds = res.seconds, t->fresh = true;
            pthread_mutex_unlock(&t->lock);
        }
        lucent_trace_result_free(&res);
    }
    t->status = st;
    if (st != LUCENT_OK) snprintf(t->error, sizeof t->error, "%s", lucent_last_error());
    lucent_tracer_destroy(tracer);
    lucent_scene_destroy(scene);
    atomic_store(&t->done, true);
    return NULL;
}

void viewer_trace_stop(viewer *v)
{
    viewer_trace *t = &v->trace;
    if (!t->running) return;
    atomic_store(&t->stop, true);
    pthread_join(t->thread, NULL);
    pthread_mutex_destroy(&t->lock);
    lucent_image_destroy(t->image);
    lucent_pool_destroy(t->pool);
    free(t->json);
    t->image = NULL, t->pool = NULL, t->json = NULL, t->running = false;
}

lucent_status viewer_trace_start(viewer *v)
{
    viewer_trace_stop(v);
    viewer_trace *t = &v->trace;
    char *json = NULL;
    lucent_status st = viewer_scene_text(v, &json);
    if (st != LUCENT_OK) return st;
    memset(t, 0, sizeof *t);
    t->json = json; /* its render.width and height are the frame's (viewer_scene_text) */
    char dir[VIEWER_PATH];
    snprintf(dir, sizeof dir, "%s", v->scene->path[0] ? v->scene->path : ".");
    snprintf(t->base_dir, sizeof t->base_dir, "%s", dirname(dir));
    t->pool = lucent_pool_create(v->opt.pool ? lucent_pool_threads(v->opt.pool) : 1);
    pthread_mutex_init(&t->lock, NULL);
    atomic_store(&t->stop, false);
    atomic_store(&t->done, false);
    if (pthread_create(&t->thread, NULL, trace_main, t) != 0) {
        pthread_mutex_destroy(&t->lock);
        lucent_pool_destroy(t->pool);
        free(t->json);
        memset(t, 0, sizeof *t);
        return lucent_error(LUCENT_ERR_INTERNAL, "cannot start the trace thread");
    }
    t->running = true;
    viewer_status(v, false, "progressive trace of %s at %dx%d started", v->scene->name, v->frame_w, v->frame_h);
    return LUCENT_OK;
}

void viewer_trace_poll(viewer *v)
{
    viewer_trace *t = &v->trace;
    if (!t->running) return;
    lucent_image *img = NULL;
    pthread_mutex_lock(&t->lock);
    if (t->fresh) img = t->image, t->image = NULL, t->fresh = false;
    uint64_t spp = t->spp;
    double seconds = t->seconds;
    pthread_mutex_unlock(&t->lock);
    if (img) {
        lucent_image_destroy(v->reference);
        v->reference = img;
        v->trace_spp = spp;
        snprintf(v->reference_path, sizeof v->reference_path, "progressive trace, %llu spp in %.1f s",
                 (unsigned long long)spp, seconds);
        v->ref_gen++, v->show_gen = 0; /* a new error; a new frame only for another size (app.c) */
    }
    if (atomic_load(&t->done) && t->status != LUCENT_OK) {
        viewer_status(v, true, "progressive trace: %s", t->error);
        viewer_trace_stop(v);
    }
}
