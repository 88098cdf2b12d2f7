/* The viewer's window and frame: the panel on the left, the view on the right rendered at its own
 * size (so a resize re-renders, never stretches), one method or two (split-screen or side by side),
 * the timings over it; the mouse moves the camera and the lights; the scene file is watched. */
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
            viewer_light_rotate(v, v->light, 0.4 * in.dx, 0.4 * in.dy);
        else if (in.down[0] && !in.shift)
            viewer_orbit(v, 0.4 * in.dx, 0.4 * in.dy);
        else
            viewer_pan(v, in.dx, in.dy);
    }
    if (inside && !in.over_ui && in.wheel != 0) viewer_zoom(v, pow(0.9, in.wheel));
    if (ui_key_pressed(GLFW_KEY_ESCAPE)) v->quit = true;
    if (ui_key_pressed(GLFW_KEY_R)) viewer_reset_camera(v);
    if (ui_key_pressed(GLFW_KEY_TAB)) {
        lucent_render_method a = v->wanted.view.method;
        v->wanted.view.method = v->method_b, v->method_b = a;
    }
    for (int m = 0; m < LUCENT_METHOD_COUNT && m < 9; m++)
        if (ui_key_pressed(GLFW_KEY_1 + m)) v->wanted.view.method = (lucent_render_method)m;
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
    snprintf(text, sizeof text, "%.1f fps, redraw %.1f ms\n%s%s", v->fps, v->redraw_ms, a, b);
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

static lucent_status present(viewer *v, const int r[4], const int clip[4])
{
    lucent_present_desc d = {.x = r[0], .y = r[1], .width = r[2], .height = r[3]};
    memcpy(d.clip, clip, sizeof d.clip);
    return v->window ? lucent_render_present_region(v->r, &d) : LUCENT_OK;
}

static lucent_status draw_views(viewer *v, const int rect[4])
{
    bool side = v->layout == VIEWER_SIDE, ref = v->reference && v->match_reference;
    int w = side ? rect[2] / 2 : rect[2], h = rect[3];
    if (ref) w = v->reference->width, h = v->reference->height;
    v->frame_w = w, v->frame_h = h;
    int ra[4] = {rect[0], rect[1], w, h}, rb[4] = {rect[0] + w, rect[1], w, h};
    int left[4] = {rect[0], rect[1], side ? rect[2] / 2 : rect[2], rect[3]};
    int right[4] = {rect[0] + rect[2] / 2, rect[1], rect[2] / 2, rect[3]};
    if (ref) fit(left, w, h, ra), fit(right, w, h, rb);
    int clip_a[4] = {0, 0, 0, 0}, clip_b[4] = {0, 0, 0, 0};
    if (v->layout == VIEWER_SPLIT) { /* both at the same place, each drawn on its side of the line */
        int sx = ra[0] + (int)lround(v->split * ra[2]);
        int a[4] = {ra[0], ra[1], sx - ra[0], ra[3]}, b[4] = {sx, ra[1], ra[0] + ra[2] - sx, ra[3]};
        memcpy(clip_a, a, sizeof a), memcpy(clip_b, b, sizeof b), memcpy(rb, ra, sizeof rb);
        if (a[2] == 0) clip_a[2] = -1; /* nothing of A shows */
        if (b[2] == 0) clip_b[2] = -1;
    }
    lucent_render_settings sa = viewer_frame_settings(v, false, w, h);
    lucent_status st = v->reference && v->error_gen != v->gen ? viewer_update_error(v) /* renders A, reads it back */
                                                              : lucent_render_frame(v->r, &sa, &v->times_a);
    if (st == LUCENT_OK && clip_a[2] >= 0) st = present(v, ra, clip_a);
    if (st != LUCENT_OK || v->layout == VIEWER_SINGLE) return st;
    lucent_render_settings sb = viewer_frame_settings(v, true, w, h);
    st = lucent_render_frame(v->r, &sb, &v->times_b);
    if (st == LUCENT_OK && clip_b[2] >= 0) st = present(v, rb, clip_b);
    return st;
}

/* The error map or the reference instead of the frame (drawn by the UI as an image). */
static void shown_image(viewer *v, const int rect[4])
{
    const lucent_image *img = v->show == VIEWER_SHOW_ERROR ? v->error_map : v->reference;
    if (v->show == VIEWER_SHOW_IMAGE || !img) return;
    if (v->show_gen != v->gen || !v->show_tex) {
        size_t n = (size_t)img->width * img->height;
        uint8_t *rgba = malloc(4 * n);
        if (!rgba) return;
        lucent_image *tm = NULL;
        if (lucent_image_clone(img, &tm) != LUCENT_OK) return free(rgba);
        if (v->show == VIEWER_SHOW_REFERENCE)
            lucent_image_tonemap(
                tm, &(lucent_tonemap_desc){.op = v->applied.view.tonemap, .exposure = (float)v->applied.view.exposure});
        for (size_t i = 0; i < n; i++)
            for (int c = 0; c < 4; c++) {
                float x = c < 3 ? tm->data[i * tm->channels + (c < tm->channels ? c : 0)] : 1.0f;
                if (v->show == VIEWER_SHOW_ERROR && c < 3) /* the heat map is linear: sRGB-encode */
                    x = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1 / 2.4f) - 0.055f;
                rgba[4 * i + c] = (uint8_t)lroundf(255 * fminf(fmaxf(x, 0), 1));
            }
        ui_texture_set(&v->show_tex, rgba, img->width, img->height);
        lucent_image_destroy(tm);
        free(rgba);
        v->show_gen = v->gen;
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
    }
    viewer_step(v);
    viewer_trace_poll(v);
    int rect[4];
    viewer_view_rect(v, rect);
    lucent_status st = LUCENT_OK;
    if (v->ui) ui_clear();
    if (v->ready) st = draw_views(v, rect);
    if (v->ui) {
        if (v->ready) overlay(v, rect);
        shown_image(v, rect);
        ui_frame_end();
    }
    if (v->window) lucent_gl_window_swap(v->gl);
    hot_reload(v);
    double t1 = lucent_clock_ms();
    v->redraw_ms = t1 - t0;
    double dt = v->last_frame > 0 ? t1 - v->last_frame : 0;
    v->last_frame = t1;
    if (dt > 0) v->fps = v->fps > 0 ? 0.9 * v->fps + 0.1 * (1000 / dt) : 1000 / dt;
    return st;
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
    lucent_gl_desc gd = {.platform = opt->headless ? LUCENT_GL_AUTO : LUCENT_GL_WINDOW,
                         .width = w,
                         .height = h,
                         .title = "Lucent view",
                         .ignore_env = !opt->headless};
    st = lucent_gl_create(&gd, &v->gl);
    if (st == LUCENT_OK && opt->cache_dir) st = lucent_cache_create(opt->cache_dir, &v->cache);
    v->job_pool = lucent_pool_create(opt->pool ? lucent_pool_threads(opt->pool) : 1);
    v->window = v->gl ? lucent_gl_window_handle(v->gl) : NULL;
    v->win_w = w, v->win_h = h;
    if (st == LUCENT_OK) st = viewer_scene_open(v);
    if (st == LUCENT_OK && v->window) {
        v->ui = ui_init(v->window);
        if (!v->ui) st = lucent_error(LUCENT_ERR_GL, "cannot start Dear ImGui on the window");
    }
    if (st == LUCENT_OK && opt->script) {
        st = viewer_script_run(v, opt->script);
    } else if (st == LUCENT_OK) {
        viewer_status(v, false,
                      "viewing %s: drag to orbit, shift-drag to pan, wheel to zoom, ctrl-drag the light, R resets",
                      opt->scene);
        while (st == LUCENT_OK && !v->quit && lucent_gl_window_poll(v->gl)) st = viewer_redraw(v);
    }
    lucent_status keep = st;
    char message[2048];
    snprintf(message, sizeof message, "%s", lucent_last_error());
    viewer_drop_reference(v);
    if (v->ui) {
        ui_texture_free(&v->show_tex);
        ui_shutdown();
    }
    viewer_scene_close(v);
    lucent_cache_destroy(v->cache);
    lucent_pool_destroy(v->job_pool);
    lucent_gl_destroy(v->gl);
    free(v);
    if (keep != LUCENT_OK) lucent_error(keep, "%s", message);
    return keep;
}
