/* `lucent view --script FILE`: UI actions, one a line, played on the viewer's state as the panel
 * and the mouse would change it, each followed by a redraw once the bakes it needs are done (so a
 * script's frames are the ones the window would settle on). docs/view.md lists the actions. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "viewer.h"

enum { MAX_WORDS = 16 };

static bool number(const char *text, double *dest)
{
    char *end;
    errno = 0;
    double x = text ? strtod(text, &end) : 0;
    if (!text || !*text || *end || errno || x != x) return false;
    *dest = x;
    return true;
}

static lucent_status need(int n, int lo, int hi, const char *usage)
{
    return n >= lo && n <= hi ? LUCENT_OK : lucent_error(LUCENT_ERR_PARSE, "usage: %s", usage);
}

static lucent_status numbers(char **w, int n, double *dest, const char *usage)
{
    for (int i = 0; i < n; i++)
        if (!number(w[i], &dest[i]))
            return lucent_error(LUCENT_ERR_PARSE, "'%s' is not a number (usage: %s)", w[i], usage);
    return LUCENT_OK;
}

/* material melanin=X eumelanin=X blood=X oxygenation=X on a spectral skin: the epidermis's melanin and
 * eumelanin share, the dermis's blood and oxygenation (docs/skin.md); its equivalent medium resolved. */
static lucent_status skin_material(viewer *v, char **w, int n)
{
    lucent_material m = v->wanted_material[v->object];
    for (int i = 1; i < n; i++) {
        char *eq = strchr(w[i], '=');
        double x;
        if (!eq || !number(eq + 1, &x))
            return lucent_error(LUCENT_ERR_PARSE, "'%s': expected KEY=NUMBER (melanin, eumelanin, blood, oxygenation)",
                                w[i]);
        *eq = '\0';
        bool epi = !strcmp(w[i], "melanin") || !strcmp(w[i], "eumelanin");
        if (!epi && strcmp(w[i], "blood") && strcmp(w[i], "oxygenation"))
            return lucent_error(LUCENT_ERR_PARSE,
                                "material: unknown key '%s' of a skin (melanin, eumelanin, blood, "
                                "oxygenation)",
                                w[i]);
        int kind = epi ? LUCENT_SKIN_EPIDERMIS : LUCENT_SKIN_DERMIS, k = 0;
        while (k < m.skin.layer_count && m.skin.layer[k].kind != kind) k++;
        if (k == m.skin.layer_count)
            return lucent_error(LUCENT_ERR_PARSE, "material: %s has no %s", m.name, lucent_skin_layer_name(kind));
        lucent_skin_layer *l = &m.skin.layer[k];
        *(!strcmp(w[i], "melanin")     ? &l->melanin
          : !strcmp(w[i], "eumelanin") ? &l->eumelanin
          : !strcmp(w[i], "blood")     ? &l->blood
                                       : &l->oxygenation) = x;
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
static lucent_status material(viewer *v, char **w, int n)
{
    const char *usage = "material PRESET | material [sigma_a=R,G,B] [sigma_s_prime=R,G,B] [g=R,G,B] [eta=X]";
    lucent_status st = need(n, 2, 6, usage);
    if (st != LUCENT_OK) return st;
    if (!strchr(w[1], '=')) return n == 2 ? viewer_material_preset(v, v->object, w[1]) : need(0, 1, 1, usage);
    if (v->wanted_material[v->object].skin.layer_count > 0) return skin_material(v, w, n);
    lucent_material m = v->wanted_material[v->object];
    for (int i = 1; i < n; i++) {
        char *eq = strchr(w[i], '=');
        if (!eq) return lucent_error(LUCENT_ERR_PARSE, "'%s': expected KEY=VALUE (usage: %s)", w[i], usage);
        *eq = '\0';
        double x[3];
        int k = sscanf(eq + 1, "%lf,%lf,%lf", &x[0], &x[1], &x[2]);
        if (k == 1) x[1] = x[2] = x[0];
        if (k != 1 && k != 3) return lucent_error(LUCENT_ERR_PARSE, "%s: expected one number or R,G,B", w[i]);
        double sp[3];
        for (int c = 0; c < 3; c++) sp[c] = m.sigma_s[c] * (1 - m.g[c]);
        if (!strcmp(w[i], "sigma_a"))
            memcpy(m.sigma_a, x, sizeof x);
        else if (!strcmp(w[i], "sigma_s_prime"))
            for (int c = 0; c < 3; c++) m.sigma_s[c] = x[c] / (1 - m.g[c]);
        else if (!strcmp(w[i], "g"))
            for (int c = 0; c < 3; c++) m.g[c] = x[c], m.sigma_s[c] = sp[c] / (1 - x[c]); /* sigma_s' kept */
        else if (!strcmp(w[i], "eta"))
            m.eta = x[0];
        else
            return lucent_error(LUCENT_ERR_PARSE, "material: unknown key '%s' (usage: %s)", w[i], usage);
    }
    st = lucent_material_validate(&m);
    if (st != LUCENT_OK) return st;
    v->wanted_material[v->object] = m;
    viewer_material_edited(v, v->object);
    return LUCENT_OK;
}

static lucent_status layout(viewer *v, char **w, int n)
{
    lucent_status st = need(n, 2, 3, "layout single|split|side [SPLIT]");
    double x = 0.5;
    if (st == LUCENT_OK && n == 3) st = numbers(w + 2, 1, &x, "layout split 0.5");
    if (st != LUCENT_OK) return st;
    if (!strcmp(w[1], "single"))
        v->layout = VIEWER_SINGLE;
    else if (!strcmp(w[1], "split"))
        v->layout = VIEWER_SPLIT, v->split = x < 0 ? 0 : x > 1 ? 1 : x;
    else if (!strcmp(w[1], "side"))
        v->layout = VIEWER_SIDE;
    else
        return lucent_error(LUCENT_ERR_PARSE, "layout: '%s': single, split or side", w[1]);
    return LUCENT_OK;
}

static lucent_status bench(viewer *v, char **w, int n)
{
    double frames = 10;
    lucent_status st = need(n, 1, 2, "bench [FRAMES]");
    if (st == LUCENT_OK && n == 2) st = numbers(w + 1, 1, &frames, "bench 20");
    if (st != LUCENT_OK) return st;
    viewer_settle(v);
    st = viewer_redraw(v); /* warm */
    double sum = 0, gpu = 0, cpu = 0;
    int count = frames < 1 ? 1 : (int)frames;
    for (int i = 0; i < count && st == LUCENT_OK; i++) {
        v->gen++; /* a redraw as after a camera move */
        st = viewer_redraw(v);
        sum += v->redraw_ms, gpu += v->times_a.gpu_ms, cpu += v->times_a.cpu_ms;
    }
    if (st == LUCENT_OK)
        printf("view bench: %s %dx%d, %d redraws: redraw %.2f ms, of which the frame %.2f ms (GPU %.2f ms)\n",
               lucent_render_method_name(v->applied.view.method), v->frame_w, v->frame_h, count, sum / count,
               cpu / count, gpu / count);
    return st;
}

/* Redraws without waiting for the bakes: what the window does while one runs. */
static lucent_status frames(viewer *v, char **w, int n)
{
    double count;
    lucent_status st = need(n, 2, 2, "frames N");
    if (st == LUCENT_OK) st = numbers(w + 1, 1, &count, "frames 5");
    for (int i = 0; st == LUCENT_OK && i < (int)count; i++) {
        float f;
        char label[256] = "";
        bool baking = viewer_baking(v, &f, label, sizeof label);
        st = viewer_redraw(v);
        printf("frame %d: redraw %.1f ms, %s%s\n", i + 1, v->redraw_ms, baking ? "while " : "no bake running",
               baking ? label : "");
    }
    return st;
}

/* Redraws until the scene file changed and was read again (the file is watched twice a second). */
static lucent_status wait_reload(viewer *v, char **w, int n)
{
    double seconds;
    lucent_status st = need(n, 2, 2, "wait-reload SECONDS");
    if (st == LUCENT_OK) st = numbers(w + 1, 1, &seconds, "wait-reload 10");
    int before = v->reloads;
    double end = lucent_clock_seconds() + seconds;
    while (st == LUCENT_OK && v->reloads == before && lucent_clock_seconds() < end) {
        st = viewer_redraw(v);
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    if (st == LUCENT_OK && v->reloads == before)
        st = lucent_error(LUCENT_ERR_IO, "wait-reload: %s did not change in %g s", v->opt.scene, seconds);
    return st;
}

/* trace-wait SPP [SECONDS]: redraws until the progressive trace has SPP samples per pixel. */
static lucent_status trace_wait(viewer *v, char **w, int n)
{
    double x[2] = {1, 600};
    lucent_status st = need(n, 2, 3, "trace-wait SPP [SECONDS]");
    if (st == LUCENT_OK) st = numbers(w + 1, n - 1, x, "trace-wait 4 60");
    if (st == LUCENT_OK && !v->trace.running)
        st = lucent_error(LUCENT_ERR_PARSE, "trace-wait: no trace runs (trace-start)");
    double end = lucent_clock_seconds() + x[1];
    while (st == LUCENT_OK && v->trace.running && v->trace_spp < x[0] && lucent_clock_seconds() < end) {
        st = viewer_redraw(v);
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
    if (st == LUCENT_OK && v->trace_spp < x[0])
        st = lucent_error(LUCENT_ERR_INTERNAL, "trace-wait: %llu of %g spp after %g s",
                          (unsigned long long)v->trace_spp, x[0], x[1]);
    return st;
}

static lucent_status action(viewer *v, char **w, int n)
{
    const char *a = w[0];
    double x[3];
    lucent_status st;
    if (!strcmp(a, "orbit")) {
        if ((st = need(n, 3, 3, "orbit YAW PITCH (degrees)")) || (st = numbers(w + 1, 2, x, "orbit 30 10"))) return st;
        return viewer_orbit(v, x[0], x[1]), LUCENT_OK;
    }
    if (!strcmp(a, "pan")) {
        if ((st = need(n, 3, 3, "pan DX DY (pixels)")) || (st = numbers(w + 1, 2, x, "pan 10 0"))) return st;
        return viewer_pan(v, x[0], x[1]), LUCENT_OK;
    }
    if (!strcmp(a, "zoom")) {
        if ((st = need(n, 2, 2, "zoom FACTOR")) || (st = numbers(w + 1, 1, x, "zoom 0.8"))) return st;
        if (!(x[0] > 0)) return lucent_error(LUCENT_ERR_PARSE, "zoom: the factor must be > 0");
        return viewer_zoom(v, x[0]), LUCENT_OK;
    }
    if (!strcmp(a, "reset"))
        return (st = need(n, 1, 1, "reset")) != LUCENT_OK ? st : (viewer_reset_camera(v), LUCENT_OK);
    if (!strcmp(a, "light")) {
        if ((st = need(n, 4, 4, "light INDEX YAW PITCH")) || (st = numbers(w + 1, 3, x, "light 0 20 0"))) return st;
        if (x[0] < 0 || x[0] >= v->scene->light_count || x[0] != (int)x[0])
            return lucent_error(LUCENT_ERR_PARSE, "light: no light %g (the scene has %d)", x[0], v->scene->light_count);
        return viewer_light_rotate(v, (int)x[0], x[1], x[2]), LUCENT_OK;
    }
    if (!strcmp(a, "set")) {
        if ((st = need(n, 2, 2, "set KEY=VALUE"))) return st;
        char *eq = strchr(w[1], '=');
        if (!eq) return lucent_error(LUCENT_ERR_PARSE, "set '%s': expected KEY=VALUE", w[1]);
        *eq = '\0';
        return viewer_set(v, w[1], eq + 1);
    }
    if (!strcmp(a, "method") || !strcmp(a, "method-b"))
        return (st = need(n, 2, 2, "method NAME")) != LUCENT_OK ? st : viewer_method(v, w[1], a[6] == '-');
    if (!strcmp(a, "layout")) return layout(v, w, n);
    if (!strcmp(a, "object")) {
        if ((st = need(n, 2, 2, "object INDEX")) || (st = numbers(w + 1, 1, x, "object 0"))) return st;
        if (x[0] < 0 || x[0] >= v->scene->object_count || x[0] != (int)x[0])
            return lucent_error(LUCENT_ERR_PARSE, "object: no object %g (the scene has %d)", x[0],
                                v->scene->object_count);
        return v->object = (int)x[0], LUCENT_OK;
    }
    if (!strcmp(a, "material")) return material(v, w, n);
    if (!strcmp(a, "load-reference"))
        return (st = need(n, 2, 2, "load-reference FILE.exr")) != LUCENT_OK ? st : viewer_load_reference(v, w[1]);
    if (!strcmp(a, "show")) {
        if ((st = need(n, 2, 2, "show image|error|reference"))) return st;
        viewer_show s = !strcmp(w[1], "image")       ? VIEWER_SHOW_IMAGE
                        : !strcmp(w[1], "error")     ? VIEWER_SHOW_ERROR
                        : !strcmp(w[1], "reference") ? VIEWER_SHOW_REFERENCE
                                                     : (viewer_show)-1;
        if ((int)s < 0) return lucent_error(LUCENT_ERR_PARSE, "show: '%s': image, error or reference", w[1]);
        return v->show = s, v->show_gen = 0, LUCENT_OK;
    }
    if (!strcmp(a, "save-scene"))
        return (st = need(n, 2, 2, "save-scene FILE.json")) != LUCENT_OK ? st : viewer_save_scene(v, w[1]);
    if (!strcmp(a, "screenshot"))
        return (st = need(n, 2, 2, "screenshot FILE[.png]")) != LUCENT_OK ? st : viewer_screenshot(v, w[1]);
    if (!strcmp(a, "window-shot"))
        return (st = need(n, 2, 2, "window-shot FILE.png")) != LUCENT_OK ? st : viewer_window_shot(v, w[1]);
    if (!strcmp(a, "export-taps"))
        return (st = need(n, 2, 3, "export-taps FILE [json|c|glsl|hlsl]")) != LUCENT_OK
                   ? st
                   : viewer_export_taps(v, w[1], n == 3 ? w[2] : NULL);
    if (!strcmp(a, "resize")) {
        if ((st = need(n, 3, 3, "resize WIDTH HEIGHT")) || (st = numbers(w + 1, 2, x, "resize 640 480"))) return st;
        return viewer_resize(v, (int)x[0], (int)x[1]);
    }
    if (!strcmp(a, "print")) {
        printf("view: %s, frame %dx%d, camera %.17g %.17g %.17g, rel_rms %.6g, reference %s\n",
               lucent_render_method_name(v->applied.view.method), v->frame_w, v->frame_h, v->scene->camera.position[0],
               v->scene->camera.position[1], v->scene->camera.position[2], v->rel_rms,
               v->reference ? v->reference_path : "none");
        fflush(stdout); /* a watching process reads it now */
        return need(n, 1, 1, "print");
    }
    if (!strcmp(a, "bench")) return bench(v, w, n);
    if (!strcmp(a, "frames")) return frames(v, w, n);
    if (!strcmp(a, "trace-start")) return (st = need(n, 1, 1, "trace-start")) != LUCENT_OK ? st : viewer_trace_start(v);
    if (!strcmp(a, "trace-stop"))
        return (st = need(n, 1, 1, "trace-stop")) != LUCENT_OK ? st : (viewer_trace_stop(v), LUCENT_OK);
    if (!strcmp(a, "trace-wait")) return trace_wait(v, w, n);
    if (!strcmp(a, "wait-reload")) return wait_reload(v, w, n);
    if (!strcmp(a, "quit")) return v->quit = true, need(n, 1, 1, "quit");
    return lucent_error(LUCENT_ERR_PARSE,
                        "unknown action '%s' (orbit, pan, zoom, reset, light, set, method, method-b, layout, object, "
                        "material, load-reference, show, save-scene, screenshot, window-shot, export-taps, resize, "
                        "print, bench, frames, wait-reload, trace-start, trace-wait, trace-stop, quit)",
                        a);
}

lucent_status viewer_script_run(viewer *v, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return lucent_error(LUCENT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    char line[4096];
    lucent_status st = LUCENT_OK;
    viewer_settle(v);
    st = viewer_redraw(v);
    for (int ln = 1; st == LUCENT_OK && !v->quit && fgets(line, sizeof line, f); ln++) {
        if (!strchr(line, '\n') && !feof(f)) {
            st = lucent_error(LUCENT_ERR_PARSE, "%s: line %d: longer than %zu characters", path, ln, sizeof line - 2);
            break;
        }
        char *words[MAX_WORDS], *save = NULL;
        int n = 0;
        for (char *t = strtok_r(line, " \t\r\n", &save); t && n < MAX_WORDS; t = strtok_r(NULL, " \t\r\n", &save))
            words[n++] = t;
        if (n == 0 || words[0][0] == '#') continue;
        bool async = !strcmp(words[0], "async") && n > 1; /* do not wait for the bakes it starts */
        st = action(v, words + async, n - async);
        if (async && st == LUCENT_OK) viewer_step(v);
        bool no_wait =
            async || !strcmp(words[0], "frames") || !strcmp(words[0], "wait-reload") || !strcmp(words[0], "trace-wait");
        if (st == LUCENT_OK && !no_wait) {
            viewer_settle(v);
            st = viewer_redraw(v);
        }
        if (st != LUCENT_OK) lucent_error_context(st, "%s: line %d (%s)", path, ln, words[0]);
    }
    fclose(f);
    return st;
}
