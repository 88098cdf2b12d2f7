/* `lucent view --script FILE`: UI actions, one a line, played on the viewer's state as the panel
 * and the mouse would change it, each followed by a redraw once the bakes it needs are done and the
 * render thread drew it (so a script's frames are the ones the window would settle on). The whole
 * script is checked first (script_parse.c); a bake that fails ends the script with its error.
 * docs/view.md lists the actions. */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "script.h"
#include "ui.h"
#include "viewer.h"

enum { SCRIPT_MAX_BYTES = 16 << 20 };

/* The chromophore edits of a spectral skin (docs/skin.md): the epidermis's melanin and eumelanin share,
 * the dermis's blood and oxygenation; the skin's equivalent medium is resolved again. */
static lucent_status skin_material(viewer *v, const viewer_command *c)
{
    lucent_material m = v->wanted_material[v->object];
    for (int e = 0; e < c->edit_count; e++) {
        viewer_edit k = c->edit[e];
        if (k < VIEWER_EDIT_MELANIN)
            return lucent_error(LUCENT_ERR_PARSE,
                                "material: %s is a spectral skin: its coefficients come from its chromophores "
                                "(melanin, eumelanin, blood, oxygenation)",
                                m.name);
        bool epi = k == VIEWER_EDIT_MELANIN || k == VIEWER_EDIT_EUMELANIN;
        int kind = epi ? LUCENT_SKIN_EPIDERMIS : LUCENT_SKIN_DERMIS, l = 0;
        while (l < m.skin.layer_count && m.skin.layer[l].kind != kind) l++;
        if (l == m.skin.layer_count)
            return lucent_error(LUCENT_ERR_PARSE, "material: %s has no %s", m.name, lucent_skin_layer_name(kind));
        lucent_skin_layer *layer = &m.skin.layer[l];
        *(k == VIEWER_EDIT_MELANIN     ? &layer->melanin
          : k == VIEWER_EDIT_EUMELANIN ? &layer->eumelanin
          : k == VIEWER_EDIT_BLOOD     ? &layer->blood
                                       : &layer->oxygenation) = c->edit_value[e][0];
    }
    m.skin.resolved = 0;
    lucent_status st = lucent_skin_resolve(&m);
    if (st != LUCENT_OK) return st;
    v->wanted_material[v->object] = m;
    viewer_material_edited(v, v->object);
    return LUCENT_OK;
}

/* material PRESET | material KEY=R,G,B ... (sigma_a, sigma_s_prime, g per channel; eta one number); on a
 * spectral skin, its chromophores (skin_material) */
static lucent_status material(viewer *v, const viewer_command *c)
{
    if (!c->edit_count) return viewer_material_preset(v, v->object, c->arg[0]);
    if (v->wanted_material[v->object].skin.layer_count > 0) return skin_material(v, c);
    lucent_material m = v->wanted_material[v->object];
    for (int e = 0; e < c->edit_count; e++) {
        const double *x = c->edit_value[e];
        double sp[3];
        for (int ch = 0; ch < 3; ch++) sp[ch] = m.sigma_s[ch] * (1 - m.g[ch]);
        switch (c->edit[e]) {
        case VIEWER_EDIT_SIGMA_A: memcpy(m.sigma_a, x, sizeof m.sigma_a); break;
        case VIEWER_EDIT_SIGMA_S_PRIME:
            for (int ch = 0; ch < 3; ch++) m.sigma_s[ch] = x[ch] / (1 - m.g[ch]);
            break;
        case VIEWER_EDIT_G: /* sigma_s' kept */
            for (int ch = 0; ch < 3; ch++) m.g[ch] = x[ch], m.sigma_s[ch] = sp[ch] / (1 - x[ch]);
            break;
        case VIEWER_EDIT_ETA: m.eta = x[0]; break;
        default:
            return lucent_error(LUCENT_ERR_PARSE,
                                "material: %s is not a spectral skin: melanin, eumelanin, blood and oxygenation "
                                "are a skin's (docs/skin.md)",
                                m.name);
        }
    }
    lucent_status st = lucent_material_validate(&m);
    if (st != LUCENT_OK) return st;
    v->wanted_material[v->object] = m;
    viewer_material_edited(v, v->object);
    return LUCENT_OK;
}

static lucent_status bench(viewer *v, int count)
{
    viewer_settle(v);
    lucent_status st = viewer_redraw_sync(v); /* warm */
    double sum = 0, gpu = 0, cpu = 0;
    for (int i = 0; i < count && st == LUCENT_OK; i++) {
        v->gen++; /* a redraw as after a camera move */
        st = viewer_redraw_sync(v);
        sum += v->redraw_ms, gpu += v->times_a.gpu_ms, cpu += v->times_a.cpu_ms;
    }
    if (st == LUCENT_OK)
        printf("view bench: %s %dx%d, %d redraws: redraw %.2f ms, of which the frame %.2f ms (GPU %.2f ms)\n",
               lucent_render_method_name(v->applied.view.method), v->frame_w, v->frame_h, count, sum / count,
               cpu / count, gpu / count);
    return st;
}

/* Redraws without waiting for the bakes: what the window does while one runs. */
static lucent_status frames(viewer *v, int count)
{
    lucent_status st = LUCENT_OK;
    for (int i = 0; st == LUCENT_OK && i < count; i++) {
        float f;
        char label[256] = "";
        bool baking = viewer_baking(v, &f, label, sizeof label);
        v->gen++;
        st = viewer_redraw_sync(v);
        printf("frame %d: redraw %.1f ms, %s%s\n", i + 1, v->redraw_ms, baking ? "while " : "no bake running",
               baking ? label : "");
    }
    return st;
}

static unsigned long worker_frames(viewer *v)
{
    pthread_mutex_lock(&v->worker.lock);
    unsigned long n = v->worker.frames;
    pthread_mutex_unlock(&v->worker.lock);
    return n;
}

/* Window frames for a while without waiting for the render thread, paced as the window is (at most
 * 60 a second): how the window keeps its rate while a frame renders (issue 32 item 13). */
static lucent_status ui_frames(viewer *v, double seconds)
{
    unsigned long frames0 = v->ui_frames, rendered0 = worker_frames(v), busy_frames = 0;
    double t0 = lucent_clock_seconds(), slowest = 0, busy_time = 0;
    lucent_status st = LUCENT_OK;
    while (st == LUCENT_OK && lucent_clock_seconds() - t0 < seconds) {
        double a = lucent_clock_seconds();
        bool busy = viewer_worker_busy(v);
        if (v->window) glfwPollEvents();
        st = viewer_redraw(v);
        double left = 1.0 / 60 - (lucent_clock_seconds() - a);
        if (left > 0) nanosleep(&(struct timespec){0, (long)(left * 1e9)}, NULL);
        double spent = lucent_clock_seconds() - a;
        if (spent > slowest) slowest = spent;
        if (busy && viewer_worker_busy(v)) busy_frames++, busy_time += spent; /* a frame rendered all along */
    }
    double t = lucent_clock_seconds() - t0;
    unsigned long n = v->ui_frames - frames0;
    printf("ui-frames: %lu window frames in %.2f s (%.1f a second), the slowest %.1f ms; while the render thread "
           "rendered: %lu in %.2f s (%.1f a second); it finished %lu frames\n",
           n, t, n / (t > 0 ? t : 1), 1e3 * slowest, busy_frames, busy_time,
           busy_frames / (busy_time > 0 ? busy_time : 1), worker_frames(v) - rendered0);
    fflush(stdout);
    return st;
}

/* Redraws until the scene file changed and was read again (the file is watched twice a second). */
static lucent_status wait_reload(viewer *v, double seconds)
{
    int before = v->reloads;
    double end = lucent_clock_seconds() + seconds;
    lucent_status st = LUCENT_OK;
    while (st == LUCENT_OK && v->reloads == before && lucent_clock_seconds() < end) {
        st = viewer_redraw(v);
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    if (st == LUCENT_OK && v->reloads == before)
        st = lucent_error(LUCENT_ERR_IO, "wait-reload: %s did not change in %g s", v->opt.scene, seconds);
    return st;
}

/* trace-wait SPP [SECONDS]: redraws until the progressive trace has SPP samples per pixel. */
static lucent_status trace_wait(viewer *v, double spp, double seconds)
{
    if (!v->trace.running) return lucent_error(LUCENT_ERR_PARSE, "trace-wait: no trace runs (trace-start)");
    double end = lucent_clock_seconds() + seconds;
    lucent_status st = LUCENT_OK;
    while (st == LUCENT_OK && v->trace.running && v->trace_spp < spp && lucent_clock_seconds() < end) {
        st = viewer_redraw(v);
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    if (st == LUCENT_OK && v->trace_spp < spp)
        st = lucent_error(LUCENT_ERR_INTERNAL, "trace-wait: %llu of %g spp after %g s",
                          (unsigned long long)v->trace_spp, spp, seconds);
    return st;
}

/* A key tapped (pressed and released at once, shorter than any frame), through the window's GLFW
 * key callback when there is a window. */
static void key(viewer *v, int choice)
{
    int k = choice == VIEWER_KEY_R        ? GLFW_KEY_R
            : choice == VIEWER_KEY_TAB    ? GLFW_KEY_TAB
            : choice == VIEWER_KEY_ESCAPE ? GLFW_KEY_ESCAPE
                                          : GLFW_KEY_1 + (choice - VIEWER_KEY_1);
    if (v->ui)
        ui_inject_key(k);
    else
        viewer_key_event(v, k);
}

/* panel [all]: the panel's layout (with every section open: all): what it needs and what it has. */
static lucent_status panel(viewer *v, bool all)
{
    if (!v->ui) return lucent_error(LUCENT_ERR_UNSUPPORTED, "panel: there is no window (headless)");
    ui_open_all(all);
    lucent_status st = viewer_redraw(v);        /* the sections open, */
    if (st == LUCENT_OK) st = viewer_redraw(v); /* then laid out */
    ui_open_all(false);
    ui_layout l;
    ui_panel_layout(&l);
    printf("panel%s: content %.0f px high in a window of %.0f, the widest item %.0f px in %.0f\n", all ? " all" : "",
           l.content_h, l.visible_h, l.widest, l.visible_w);
    fflush(stdout);
    return st;
}

static lucent_status action(viewer *v, const viewer_command *c)
{
    const double *x = c->x;
    switch (c->action) {
    case VIEWER_ORBIT: return viewer_orbit(v, x[0], x[1]);
    case VIEWER_PAN: return viewer_pan(v, x[0], x[1]);
    case VIEWER_ZOOM: return viewer_zoom(v, x[0]);
    case VIEWER_RESET: return viewer_reset_camera(v), LUCENT_OK;
    case VIEWER_LIGHT: return viewer_light_rotate(v, (int)x[0], x[1], x[2]);
    case VIEWER_SET: {
        char kv[VIEWER_SCRIPT_LINE + 2];
        snprintf(kv, sizeof kv, "%s", c->arg[0]);
        char *eq = strchr(kv, '=');
        *eq = '\0';
        return viewer_set(v, kv, eq + 1);
    }
    case VIEWER_METHOD:
    case VIEWER_METHOD_B: return viewer_method(v, c->arg[0], c->action == VIEWER_METHOD_B);
    case VIEWER_LAYOUT:
        v->layout = (viewer_layout)c->choice;
        if (v->layout == VIEWER_SPLIT) v->split = x[1];
        v->gen++;
        return LUCENT_OK;
    case VIEWER_OBJECT:
        if (x[0] >= v->scene->object_count)
            return lucent_error(LUCENT_ERR_PARSE, "object: no object %g (the scene has %d)", x[0],
                                v->scene->object_count);
        return v->object = (int)x[0], LUCENT_OK;
    case VIEWER_MATERIAL: return material(v, c);
    case VIEWER_LOAD_REFERENCE: return viewer_load_reference(v, c->arg[0]);
    case VIEWER_SHOW: return v->show = (viewer_show)c->choice, v->show_gen = 0, LUCENT_OK;
    case VIEWER_SAVE_SCENE: return viewer_save_scene(v, c->arg[0]);
    case VIEWER_SCREENSHOT: return viewer_screenshot(v, c->arg[0]);
    case VIEWER_WINDOW_SHOT: return viewer_window_shot(v, c->arg[0]);
    case VIEWER_EXPORT_TAPS: return viewer_export_taps(v, c->arg[0], c->argc == 2 ? c->arg[1] : NULL);
    case VIEWER_RESIZE: return viewer_resize(v, (int)x[0], (int)x[1]);
    case VIEWER_PRINT:
        printf("view: %s, frame %dx%d, camera %.17g %.17g %.17g, rel_rms %.6g, reference %s\n",
               lucent_render_method_name(v->applied.view.method), v->frame_w, v->frame_h, v->scene->camera.position[0],
               v->scene->camera.position[1], v->scene->camera.position[2], v->rel_rms,
               v->reference ? v->reference_path : "none");
        fflush(stdout); /* a watching process reads it now */
        return LUCENT_OK;
    case VIEWER_BENCH: return bench(v, (int)x[0]);
    case VIEWER_FRAMES: return frames(v, (int)x[0]);
    case VIEWER_WAIT_RELOAD: return wait_reload(v, x[0]);
    case VIEWER_TRACE_START: return viewer_trace_start(v);
    case VIEWER_TRACE_WAIT: return trace_wait(v, x[0], x[1]);
    case VIEWER_TRACE_STOP: return viewer_trace_stop(v), LUCENT_OK;
    case VIEWER_KEY: return key(v, c->choice), viewer_redraw(v); /* the next window frame handles it */
    case VIEWER_UI_FRAMES: return ui_frames(v, x[0]);
    case VIEWER_PANEL: return panel(v, c->choice == 1);
    case VIEWER_QUIT: return v->quit = true, LUCENT_OK;
    default: return lucent_error(LUCENT_ERR_INTERNAL, "action %d", (int)c->action);
    }
}

/* The script's bytes, NUL bytes included (the check refuses them, naming the line). */
static lucent_status read_script(const char *path, char **text, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return lucent_error(LUCENT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 4096;
            char *grown = cap <= SCRIPT_MAX_BYTES + 1 ? realloc(buf, cap) : NULL;
            if (!grown) {
                free(buf), fclose(f);
                return cap > SCRIPT_MAX_BYTES + 1
                           ? lucent_error(LUCENT_ERR_PARSE, "%s: larger than %d MiB: not a script", path,
                                          SCRIPT_MAX_BYTES >> 20)
                           : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
            }
            buf = grown;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    bool bad = ferror(f);
    fclose(f);
    if (bad) return free(buf), lucent_error(LUCENT_ERR_IO, "%s: read failed", path);
    *text = buf, *size = n;
    return LUCENT_OK;
}

lucent_status viewer_script_run(viewer *v, const char *path)
{
    char *text = NULL;
    size_t size = 0;
    lucent_status st = read_script(path, &text, &size);
    if (st != LUCENT_OK) return st;
    viewer_script s;
    viewer_script_context ctx = {.light_count = v->scene->light_count,
                                 .object_count = v->scene->object_count,
                                 .window = v->window != NULL,
                                 .resolve_materials = true};
    st = viewer_script_parse(text, size, path, &ctx, &s); /* the whole script before its first line runs */
    free(text);
    if (st != LUCENT_OK) return st;
    viewer_settle(v);
    st = viewer_redraw_sync(v);
    for (int i = 0; st == LUCENT_OK && !v->quit && i < s.count; i++) {
        const viewer_command *c = &s.commands[i];
        v->bake_failed = false;
        st = action(v, c);
        viewer_action a = c->action;
        bool no_wait = c->async || a == VIEWER_FRAMES || a == VIEWER_WAIT_RELOAD || a == VIEWER_TRACE_WAIT ||
                       a == VIEWER_UI_FRAMES || a == VIEWER_KEY || a == VIEWER_PANEL || a == VIEWER_BENCH;
        if (st == LUCENT_OK && c->async) viewer_step(v);
        if (st == LUCENT_OK && !no_wait) {
            viewer_settle(v);
            /* a bake the action started failed: the script fails (docs/view.md; issue 32 item 15) */
            st =
                v->bake_failed ? lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s", v->bake_error) : viewer_redraw_sync(v);
        }
        if (st != LUCENT_OK) lucent_error_context(st, "%s: line %d (%s)", path, c->line, viewer_action_name(a));
    }
    viewer_script_free(&s);
    return st;
}
