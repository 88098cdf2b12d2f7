/* The viewer's window and frame: the panel on the left, the view on the right rendered at its own
 * size (so a resize re-renders, never stretches), one method or two (split-screen or side by side),
 * the timings over it; the mouse moves the camera and the lights; the scene file is watched.
 *
 * The frames are rendered on a thread of their own (render.c): the window keeps its rate whatever a
 * frame costs, shows the last finished frame, and asks for the next one as soon as the render
 * thread is free. Key presses are queued by the GLFW callback, so a tap shorter than a frame is
 * not lost (issue 32 item 13). */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "ui.h"
#include "viewer.h"

enum { PANEL_WIDTH = 380 };

void viewer_view_rect(const viewer *v, int rect[4])
{
    int pw = v->ui ? v->panel_w : 0;
    rect[0] = pw, rect[1] = 0;
    rect[2] = v->win_w - pw > 1 ? v->win_w - pw : 1;
    rect[3] = v->win_h > 1 ? v->win_h : 1;
}

lucent_status viewer_resize(viewer *v, int width, int height)
{
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "resize: %d x %d: sizes from 1 to 16384", width, height);
    if (!v->window) {
        v->win_w = width, v->win_h = height;
        v->gen++;
        return LUCENT_OK;
    }
    glfwSetWindowSize(v->window, width, height);
    for (int i = 0; i < 200; i++) { /* the X server answers in its own time */
        glfwPollEvents();
        int w, h;
        glfwGetFramebufferSize(v->window, &w, &h);
        if (w == width && h == height) break;
        nanosleep(&(struct timespec){0, 5000000}, NULL);
    }
    glfwGetFramebufferSize(v->window, &v->win_w, &v->win_h);
    v->gen++;
    if (v->win_w != width || v->win_h != height)
        return lucent_error(LUCENT_ERR_GL, "resize: the window is %d x %d, not %d x %d", v->win_w, v->win_h, width,
                            height);
    return LUCENT_OK;
}

/* ---- input ---- */

void viewer_key_event(viewer *v, int key)
{
    if (v->key_count < (int)(sizeof v->keys / sizeof v->keys[0])) v->keys[v->key_count++] = key;
}

static void on_key(void *user, int key) { viewer_key_event(user, key); }

static void keys(viewer *v, bool typing)
{
    for (int i = 0; i < v->key_count && !typing; i++) {
        int k = v->keys[i];
        if (k == GLFW_KEY_ESCAPE) v->quit = true;
        if (k == GLFW_KEY_R) viewer_reset_camera(v);
        if (k == GLFW_KEY_TAB) {
            lucent_render_method a = v->wanted.view.method;
            v->wanted.view.method = v->method_b, v->method_b = a;
        }
        if (k >= GLFW_KEY_1 && k < GLFW_KEY_1 + LUCENT_METHOD_COUNT && k <= GLFW_KEY_9)
            v->wanted.view.method = (lucent_render_method)(k - GLFW_KEY_1);
    }
    v->key_count = 0;
}

static void moved(viewer *v, lucent_status st)
{
    if (st != LUCENT_OK) viewer_status(v, true, "%s", lucent_last_error());
}

static void input(viewer *v)
{
    ui_input in;
    ui_get_input(&in);
    static bool dragging_split = false, dragging = false;
    int rect[4];
    viewer_view_rect(v, rect);
    bool inside = in.x >= rect[0] && in.x < rect[0] + rect[2] && in.y >= rect[1] && in.y < rect[1] + rect[3];
    bool any = in.down[0] || in.down[1] || in.down[2];
    if (!any) dragging = dragging_split = false;
    if (any && !dragging && inside && !in.over_ui) {
        dragging = true;
        float sx = (float)(rect[0] + v->split * rect[2]);
        dragging_split = v->layout == VIEWER_SPLIT && in.down[0] && fabsf(in.x - sx) < 6;
    }
    if (dragging && (in.dx != 0 || in.dy != 0)) {
        if (dragging_split)
            v->split = fmin(fmax((in.x - rect[0]) / rect[2], 0.0), 1.0);
        else if (in.down[0] && in.ctrl)
            moved(v, viewer_light_rotate(v, v->light, 0.4 * in.dx, 0.4 * in.dy));
        else if (in.down[0] && !in.shift)
            moved(v, viewer_orbit(v, 0.4 * in.dx, 0.4 * in.dy));
        else
            moved(v, viewer_pan(v, in.dx, in.dy));
    }
    if (inside && !in.over_ui && in.wheel != 0) moved(v, viewer_zoom(v, pow(0.9, in.wheel)));
    keys(v, in.typing);
}

/* ---- the frame ---- */

static void times_text(const char *label, const lucent_frame_times *t, int w, int h, char *dest, size_t size)
{
    snprintf(dest, size, "%s %dx%d: GPU %.2f ms", label, w, h, t->gpu_ms);
    for (int i = 0; i < t->pass_count; i++)
        snprintf(dest + strlen(dest), size - strlen(dest), "%s%s %.2f", i % 4 ? ", " : "\n  ", t->pass_name[i],
                 t->pass_ms[i]);
}

static void overlay(viewer *v, const int rect[4])
{
    char text[2048], a[768], b[768] = "";
    int w = v->frame_w, h = v->frame_h;
    times_text(lucent_render_method_name(v->applied.view.method), &v->times_a, w, h, a, sizeof a);
    if (v->layout != VIEWER_SINGLE) {
        times_text(lucent_render_method_name(v->applied_b), &v->times_b, v->layout == VIEWER_SIDE ? w : w, h, b + 1,
                   sizeof b - 1);
        b[0] = '\n';
    }
    snprintf(text, sizeof text, "%.1f fps, frame %.1f ms%s\n%s%s", v->fps, v->frame_ms,
             viewer_worker_busy(v) ? ", rendering the next" : "", a, b);
    if (v->reference)
        snprintf(text + strlen(text), sizeof text - strlen(text), "\nrelative RMS error of %s: %.4f",
                 lucent_render_method_name(v->applied.view.method), v->rel_rms);
    ui_overlay_text((float)rect[0] + 8, (float)rect[1] + 6, text);
    if (v->layout == VIEWER_SPLIT) {
        float x = (float)(rect[0] + v->split * rect[2]);
        ui_overlay_line(x, (float)rect[1], x, (float)(rect[1] + rect[3]), 0xC0FFFFFFu, 2);
        ui_overlay_text(x - 70, (float)(rect[1] + rect[3] - 24), "A | B");
    }
    float f;
    char label[256];
    if (viewer_baking(v, &f, label, sizeof label))
        ui_overlay_text((float)rect[0] + 8, (float)(rect[1] + rect[3] - 24), label);
}

/* The rectangle of a w x h frame fitted, aspect kept, into the centre of rect. */
static void fit(const int rect[4], int w, int h, int dest[4])
{
    double k = fmin((double)rect[2] / w, (double)rect[3] / h);
    if (k > 1) k = 1;
    dest[2] = (int)lround(w * k), dest[3] = (int)lround(h * k);
    dest[0] = rect[0] + (rect[2] - dest[2]) / 2, dest[1] = rect[1] + (rect[3] - dest[3]) / 2;
}

/* The size of the frames the view wants now. */
static void frame_size(const viewer *v, int *w, int *h)
{
    int rect[4];
    viewer_view_rect(v, rect);
    *w = v->layout == VIEWER_SIDE ? rect[2] / 2 : rect[2], *h = rect[3];
    if (v->reference && v->match_reference) *w = v->reference->width, *h = v->reference->height;
    if (*w < 1) *w = 1;
    if (*h < 1) *h = 1;
}

/* The request for what the viewer wants drawn now. */
static lucent_status make_request(viewer *v, viewer_request *q)
{
    frame_size(v, &v->frame_w, &v->frame_h);
    memset(q, 0, sizeof *q);
    q->gen = v->gen;
    q->count = v->layout == VIEWER_SINGLE ? 1 : 2;
    viewer_shown_camera(v, &q->camera[0]);
    q->camera[1] = q->camera[0];
    q->settings[0] = viewer_frame_settings(v, false, v->frame_w, v->frame_h);
    q->settings[1] = viewer_frame_settings(v, true, v->frame_w, v->frame_h);
    const lucent_scene *sc = v->scene;
    q->changed = v->changed, q->light_count = sc->light_count, q->object_count = sc->object_count;
    if (v->changed & LUCENT_RENDERER_LIGHTS) {
        q->lights = malloc(((size_t)sc->light_count + 1) * sizeof *q->lights);
        if (!q->lights) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        memcpy(q->lights, sc->lights, (size_t)sc->light_count * sizeof *q->lights);
    }
    if (v->changed & LUCENT_RENDERER_MATERIALS) {
        q->objects = malloc(((size_t)sc->object_count + 1) * sizeof *q->objects);
        if (!q->objects) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        memcpy(q->objects, sc->objects, (size_t)sc->object_count * sizeof *q->objects);
    }
    q->adopt_count = v->adopt_count; /* moved */
    for (int a = 0; a < v->adopt_count; a++) {
        q->adopt_material[a] = v->adopt_material[a];
        q->adopt[a] = v->adopt[a];
        memset(&v->adopt[a], 0, sizeof v->adopt[a]);
    }
    return LUCENT_OK;
}

/* Hands the render thread the next frame when it is free and something changed; takes the frame
 * it finished. */
static lucent_status exchange(viewer *v)
{
    viewer_frame f;
    if (viewer_worker_take(v, &f, 0)) {
        if (f.status != LUCENT_OK) {
            lucent_status st = lucent_error(f.status, "%s", f.error);
            viewer_frame_free(&f);
            return st;
        }
        viewer_frame_free(&v->shown);
        v->shown = f; /* moved */
        v->times_a = f.times[0], v->times_b = f.times[1], v->frame_ms = f.ms;
        if (v->ui)
            for (int i = 0; i < f.count; i++) ui_texture_set(&v->frame_tex[i], f.rgba[i], f.width, f.height);
    }
    if (v->reference && v->shown.count && (v->error_gen != v->shown.gen || v->error_ref_gen != v->ref_gen)) {
        lucent_status st = viewer_update_error(v);
        if (st != LUCENT_OK) return st;
    }
    int w, h;
    frame_size(v, &w, &h); /* the window resized, the layout changed: a frame of the new shape */
    int count = v->layout == VIEWER_SINGLE ? 1 : 2;
    if (w != v->frame_w || h != v->frame_h || count != v->asked_count) v->gen++;
    bool want = v->ready && (v->gen != v->asked || v->changed || v->adopt_count);
    if (!want || viewer_worker_busy(v)) return LUCENT_OK;
    viewer_request q;
    lucent_status st = make_request(v, &q);
    if (st != LUCENT_OK) return viewer_request_free(&q), st;
    unsigned long gen = q.gen;
    if (!viewer_worker_submit(v, &q)) return viewer_request_free(&q), LUCENT_OK; /* cannot happen: we alone submit */
    v->asked = gen, v->changed = 0, v->adopt_count = 0, v->asked_at = lucent_clock_ms(), v->asked_count = count;
    return LUCENT_OK;
}

/* The last finished frames into the view: A alone, A left of the split line and B right of it, or
 * side by side; each at its size (a frame made for another size fits until the next comes). */
static void draw_frames(viewer *v, const int rect[4])
{
    const viewer_frame *f = &v->shown;
    if (!f->count || !v->ui) return;
    bool side = v->layout == VIEWER_SIDE && f->count == 2;
    int left[4] = {rect[0], rect[1], side ? rect[2] / 2 : rect[2], rect[3]};
    int right[4] = {rect[0] + rect[2] / 2, rect[1], rect[2] / 2, rect[3]};
    int ra[4], rb[4];
    fit(left, f->width, f->height, ra);
    fit(right, f->width, f->height, rb);
    if (v->layout == VIEWER_SPLIT && f->count == 2) { /* both at the same place, each on its side of the line */
        float s = (float)v->split, x0 = (float)ra[0], x1 = (float)(ra[0] + ra[2]), xs = x0 + s * (x1 - x0);
        float y0 = (float)ra[1], y1 = (float)(ra[1] + ra[3]);
        ui_background_image_uv(v->frame_tex[0], x0, y0, xs, y1, 0, 0, s, 1);
        ui_background_image_uv(v->frame_tex[1], xs, y0, x1, y1, s, 0, 1, 1);
        return;
    }
    ui_background_image(v->frame_tex[0], (float)ra[0], (float)ra[1], (float)(ra[0] + ra[2]), (float)(ra[1] + ra[3]));
    if (side)
        ui_background_image(v->frame_tex[1], (float)rb[0], (float)rb[1], (float)(rb[0] + rb[2]),
                            (float)(rb[1] + rb[3]));
}

/* The error map or the reference instead of the frame (drawn by the UI as an image). */
static void shown_image(viewer *v, const int rect[4])
{
    const lucent_image *img = v->show == VIEWER_SHOW_ERROR ? v->error_map : v->reference;
    if (v->show == VIEWER_SHOW_IMAGE || !img) return;
    if (!v->show_gen || !v->show_tex) {
        uint8_t *rgba = NULL;
        lucent_tonemap_desc tm = {.op = v->applied.view.tonemap, .exposure = (float)v->applied.view.exposure};
        /* the reference as a frame is shown; the heat map is linear */
        if (viewer_to_rgba(img, v->show == VIEWER_SHOW_REFERENCE ? &tm : NULL, true, &rgba) != LUCENT_OK) return;
        ui_texture_set(&v->show_tex, rgba, img->width, img->height);
        free(rgba);
        v->show_gen = 1;
    }
    int r[4];
    fit(rect, img->width, img->height, r);
    ui_background_image(v->show_tex, (float)r[0], (float)r[1], (float)(r[0] + r[2]), (float)(r[1] + r[3]));
}

static void hot_reload(viewer *v)
{
    double now = lucent_clock_seconds();
    if (!v->hot_reload || now < v->next_check) return;
    v->next_check = now + 0.5;
    struct stat sb;
    if (stat(v->opt.scene, &sb) != 0) return;
    if (sb.st_mtim.tv_sec == v->mtime.tv_sec && sb.st_mtim.tv_nsec == v->mtime.tv_nsec) return;
    v->mtime = sb.st_mtim;
    lucent_camera cam = v->scene->camera, home = v->home;
    if (viewer_scene_open(v) != LUCENT_OK) {
        viewer_status(v, true, "reload failed (the last scene stays): %s", lucent_last_error());
        return;
    }
    bool same_home = !memcmp(&home, &v->home, sizeof home);
    if (same_home) v->scene->camera = cam; /* the file's camera did not change: keep the user's */
    v->reloads++;
    viewer_status(v, false, "reloaded %s", v->opt.scene);
}

lucent_status viewer_redraw(viewer *v)
{
    double t0 = lucent_clock_ms();
    if (!v->r) return lucent_error(LUCENT_ERR_GL, "%s: no renderer for the reloaded scene", v->opt.scene);
    if (v->window) glfwGetFramebufferSize(v->window, &v->win_w, &v->win_h);
    if (v->ui) {
        ui_frame_begin();
        input(v);
        viewer_panel(v);
    } else {
        keys(v, false);
    }
    viewer_step(v);
    viewer_trace_poll(v);
    int rect[4];
    viewer_view_rect(v, rect);
    lucent_status st = exchange(v);
    if (v->ui) {
        ui_clear();
        draw_frames(v, rect);
        if (v->ready) overlay(v, rect);
        shown_image(v, rect);
        ui_frame_end();
    }
    if (v->window) lucent_gl_window_swap(v->gl);
    hot_reload(v);
    double t1 = lucent_clock_ms();
    v->redraw_ms = t1 - t0;
    v->ui_frames++;
    double dt = v->last_frame > 0 ? t1 - v->last_frame : 0;
    v->last_frame = t1;
    if (dt > 0) v->fps = v->fps > 0 ? 0.9 * v->fps + 0.1 * (1000 / dt) : 1000 / dt;
    return st;
}

lucent_status viewer_redraw_sync(viewer *v)
{
    double t0 = lucent_clock_ms();
    lucent_status st = viewer_redraw(v);
    unsigned long want = v->gen;
    while (st == LUCENT_OK &&
           (!v->shown.count || v->shown.gen < want || v->changed || v->adopt_count || viewer_worker_busy(v))) {
        if (!v->ready) {
            viewer_settle(v);
            if (!v->ready) /* the first bake failed: there is nothing to draw */
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s",
                                    v->bake_failed ? v->bake_error : "nothing to draw: the first bake did not finish");
        }
        if (!v->ui) { /* no window to keep: sleep until the render thread is done */
            viewer_frame f;
            if (viewer_worker_take(v, &f, 50)) { /* put it back for exchange to take */
                pthread_mutex_lock(&v->worker.lock);
                v->worker.frame = f, v->worker.has_frame = true;
                pthread_mutex_unlock(&v->worker.lock);
            }
        } else {
            glfwWaitEventsTimeout(0.016); /* the render thread posts an event when a frame is done */
        }
        st = viewer_redraw(v);
    }
    v->redraw_ms = lucent_clock_ms() - t0;
    return st;
}

/* Without --size the window is as tall as the panel needs with its sections as they open (issue 35:
 * 512 rows needed the panel scrolled), within the screen's work area. */
static lucent_status fit_panel(viewer *v)
{
    ui_layout l;
    for (int i = 0; i < 2; i++) { /* the panel's size is known once it was laid out */
        ui_frame_begin();
        viewer_panel(v);
        ui_frame_end();
    }
    ui_panel_layout(&l);
    int need = (int)ceilf(l.content_h + 8), h = v->win_h, screen_w = 0, screen_h = 0;
    GLFWmonitor *m = glfwGetPrimaryMonitor();
    if (m) {
        int x, y;
        glfwGetMonitorWorkarea(m, &x, &y, &screen_w, &screen_h);
    }
    if (need > h) h = screen_h > 0 && need > screen_h ? screen_h : need;
    return h != v->win_h ? viewer_resize(v, v->win_w, h) : LUCENT_OK;
}

lucent_status viewer_run(const viewer_options *opt)
{
    viewer *v = calloc(1, sizeof *v);
    if (!v) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    v->opt = *opt;
    v->panel_w = PANEL_WIDTH, v->split = 0.5, v->match_reference = true, v->hot_reload = true, v->taps_format = 0;
    snprintf(v->save_path, sizeof v->save_path, "tuned.json");
    snprintf(v->shot_path, sizeof v->shot_path, "view.png");
    snprintf(v->taps_path, sizeof v->taps_path, "taps.json");
    lucent_scene *probe = NULL; /* the window's size comes from the scene's image */
    lucent_scene_load_desc ld = {.overrides = opt->sets, .override_count = opt->set_count, .skip_meshes = true};
    lucent_status st = lucent_scene_load(opt->scene, &ld, &probe);
    if (st != LUCENT_OK) return free(v), st;
    int w = opt->width ? opt->width : probe->render.view.width + (opt->headless ? 0 : PANEL_WIDTH);
    int h = opt->height ? opt->height : probe->render.view.height;
    lucent_scene_destroy(probe);
    /* The window (its context draws the panel and the frames as textures); the frames are rendered
     * on the render thread's own headless context. */
    if (!opt->headless)
        st = lucent_gl_create(
            &(lucent_gl_desc){
                .platform = LUCENT_GL_WINDOW, .width = w, .height = h, .title = "Lucent view", .ignore_env = true},
            &v->gl);
    if (st == LUCENT_OK && opt->cache_dir) st = lucent_cache_create(opt->cache_dir, &v->cache);
    v->job_pool = lucent_pool_create(opt->pool ? lucent_pool_threads(opt->pool) : 1);
    v->window = v->gl ? lucent_gl_window_handle(v->gl) : NULL;
    v->win_w = w, v->win_h = h;
    if (st == LUCENT_OK) st = viewer_worker_start(v);
    if (st == LUCENT_OK) st = viewer_scene_open(v);
    if (st == LUCENT_OK && v->window) {
        v->ui = ui_init(v->window);
        if (!v->ui) st = lucent_error(LUCENT_ERR_GL, "cannot start Dear ImGui on the window");
        if (v->ui) ui_on_key(on_key, v);
        if (v->ui && !opt->width && !opt->height) st = fit_panel(v);
    }
    if (st == LUCENT_OK && opt->script) {
        st = viewer_script_run(v, opt->script);
    } else if (st == LUCENT_OK) {
        viewer_status(v, false,
                      "viewing %s: drag to orbit, shift-drag to pan, wheel to zoom, ctrl-drag the light, R resets",
                      opt->scene);
        while (st == LUCENT_OK && !v->quit && lucent_gl_window_poll(v->gl)) {
            double t0 = lucent_clock_seconds();
            st = viewer_redraw(v);
            double left = 1.0 / 60 - (lucent_clock_seconds() - t0); /* no faster than 60 frames a second */
            if (left > 0) glfwWaitEventsTimeout(left);
        }
    }
    lucent_status keep = st;
    char message[2048];
    snprintf(message, sizeof message, "%s", lucent_last_error());
    viewer_drop_reference(v);
    if (v->ui) {
        ui_texture_free(&v->show_tex);
        for (int i = 0; i < 2; i++) ui_texture_free(&v->frame_tex[i]);
        ui_shutdown();
    }
    viewer_scene_close(v);
    viewer_worker_stop(v);
    lucent_cache_destroy(v->cache);
    lucent_pool_destroy(v->job_pool);
    lucent_gl_destroy(v->gl);
    free(v);
    if (keep != LUCENT_OK) lucent_error(keep, "%s", message);
    return keep;
}
