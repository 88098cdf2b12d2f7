/* The check of a whole `lucent view` script before any line runs (script.h). Only the lucent headers: no
 * window, no renderer, so the fuzz target calls it as it is. Each action's words are counted, its
 * numbers read (finite, whole where a count or an index is), its names looked up (settings,
 * methods, layouts, presets, key names); what depends on the state when the line runs (a
 * material's validity after several edits, files written by earlier lines) is checked then. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "script.h"

typedef struct action_info {
    const char *name;
    int lo, hi; /* words after the action */
    const char *usage;
} action_info;

static const action_info k_actions[VIEWER_ACTION_COUNT] = {
    [VIEWER_ORBIT] = {"orbit", 2, 2, "orbit YAW PITCH (degrees)"},
    [VIEWER_PAN] = {"pan", 2, 2, "pan DX DY (pixels)"},
    [VIEWER_ZOOM] = {"zoom", 1, 1, "zoom FACTOR (> 0)"},
    [VIEWER_RESET] = {"reset", 0, 0, "reset"},
    [VIEWER_LIGHT] = {"light", 3, 3, "light INDEX YAW PITCH"},
    [VIEWER_SET] = {"set", 1, 1, "set KEY=VALUE"},
    [VIEWER_METHOD] = {"method", 1, 1, "method NAME"},
    [VIEWER_METHOD_B] = {"method-b", 1, 1, "method-b NAME"},
    [VIEWER_LAYOUT] = {"layout", 1, 2, "layout single|split|side [SPLIT]"},
    [VIEWER_OBJECT] = {"object", 1, 1, "object INDEX"},
    [VIEWER_MATERIAL] = {"material", 1, VIEWER_SCRIPT_EDITS,
                         "material PRESET | material [sigma_a=R,G,B] [sigma_s_prime=R,G,B] [g=R,G,B] [eta=X] | "
                         "material [melanin=X] [eumelanin=X] [blood=X] [oxygenation=X] (a spectral skin)"},
    [VIEWER_LOAD_REFERENCE] = {"load-reference", 1, 1, "load-reference FILE.exr"},
    [VIEWER_SHOW] = {"show", 1, 1, "show image|error|reference"},
    [VIEWER_SAVE_SCENE] = {"save-scene", 1, 1, "save-scene FILE.json"},
    [VIEWER_SCREENSHOT] = {"screenshot", 1, 1, "screenshot FILE[.png]"},
    [VIEWER_WINDOW_SHOT] = {"window-shot", 1, 1, "window-shot FILE.png"},
    [VIEWER_EXPORT_TAPS] = {"export-taps", 1, 2, "export-taps FILE [json|c|glsl|hlsl]"},
    [VIEWER_RESIZE] = {"resize", 2, 2, "resize WIDTH HEIGHT"},
    [VIEWER_PRINT] = {"print", 0, 0, "print"},
    [VIEWER_BENCH] = {"bench", 0, 1, "bench [FRAMES]"},
    [VIEWER_FRAMES] = {"frames", 1, 1, "frames N"},
    [VIEWER_WAIT_RELOAD] = {"wait-reload", 1, 1, "wait-reload SECONDS"},
    [VIEWER_TRACE_START] = {"trace-start", 0, 0, "trace-start"},
    [VIEWER_TRACE_WAIT] = {"trace-wait", 1, 2, "trace-wait SPP [SECONDS]"},
    [VIEWER_TRACE_STOP] = {"trace-stop", 0, 0, "trace-stop"},
    [VIEWER_KEY] = {"key", 1, 1, "key R|TAB|ESCAPE|1..9"},
    [VIEWER_UI_FRAMES] = {"ui-frames", 1, 1, "ui-frames SECONDS"},
    [VIEWER_PANEL] = {"panel", 0, 1, "panel [all]"},
    [VIEWER_QUIT] = {"quit", 0, 0, "quit"},
};

const char *viewer_action_name(viewer_action a)
{
    return a >= 0 && a < VIEWER_ACTION_COUNT ? k_actions[a].name : "unknown";
}

static lucent_status fail(const char *fmt, ...) LUCENT_PRINTF(1, 2);
static lucent_status fail(const char *fmt, ...)
{
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return lucent_error(LUCENT_ERR_PARSE, "%s", text);
}

/* A finite number, the whole word. */
static bool finite_number(const char *word, double *dest)
{
    char *end;
    errno = 0;
    double x = strtod(word, &end);
    if (!*word || *end || errno == ERANGE || !isfinite(x)) return false;
    *dest = x;
    return true;
}

static lucent_status number(const viewer_command *c, int i, double lo, double hi, bool whole, double *dest)
{
    const char *w = c->arg[i], *usage = k_actions[c->action].usage;
    if (!finite_number(w, dest)) return fail("'%s' is not a finite number (usage: %s)", w, usage);
    if (whole && *dest != floor(*dest)) return fail("'%s' is not a whole number (usage: %s)", w, usage);
    if (*dest < lo || *dest > hi) return fail("%s is out of range: %g to %g (usage: %s)", w, lo, hi, usage);
    return LUCENT_OK;
}

static int pick(const char *word, const char *const *names)
{
    for (int i = 0; names[i]; i++)
        if (!strcmp(word, names[i])) return i;
    return -1;
}

/* One value of a material edit: one number (every channel) or three (R, G, B). */
static lucent_status edit_values(const char *key, const char *text, double dest[3])
{
    char buf[256];
    int n = 0;
    if (strlen(text) >= sizeof buf) return fail("material: %s=...: too long", key);
    snprintf(buf, sizeof buf, "%s", text);
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save), n++)
        if (n == 3 || !finite_number(t, &dest[n]))
            return fail("material: %s=%s: expected one finite number or three (R,G,B)", key, text);
    if ((n != 1 && n != 3) || text[strlen(text) - 1] == ',' || text[0] == ',' || strstr(text, ",,"))
        return fail("material: %s=%s: expected one finite number or three (R,G,B)", key, text);
    if (n == 1) dest[1] = dest[2] = dest[0];
    return LUCENT_OK;
}

static lucent_status material(viewer_command *c, const viewer_script_context *ctx)
{
    static const char *const keys[] = {"sigma_a",   "sigma_s_prime", "g",           "eta", "melanin",
                                       "eumelanin", "blood",         "oxygenation", NULL};
    if (!strchr(c->arg[0], '=')) {
        if (c->argc != 1) return fail("usage: %s", k_actions[c->action].usage);
        lucent_material m;
        return ctx->resolve_materials ? lucent_material_resolve(c->arg[0], &m) : LUCENT_OK;
    }
    for (int i = 0; i < c->argc; i++) {
        char *eq = strchr(c->arg[i], '=');
        if (!eq) return fail("'%s': expected KEY=VALUE (usage: %s)", c->arg[i], k_actions[c->action].usage);
        *eq = '\0';
        const char *key = c->arg[i], *value = eq + 1;
        int k = pick(key, keys);
        if (k < 0)
            return fail("material: unknown key '%s' (sigma_a, sigma_s_prime, g, eta; on a spectral skin melanin, "
                        "eumelanin, blood, oxygenation)",
                        key);
        double x[3];
        lucent_status st = edit_values(key, value, x);
        if (st != LUCENT_OK) return st;
        for (int ch = 0; ch < 3; ch++) {
            if (k == VIEWER_EDIT_SIGMA_A && !(x[ch] >= 0))
                return fail("material: sigma_a=%s: must be >= 0 mm^-1", value);
            if (k == VIEWER_EDIT_SIGMA_S_PRIME && !(x[ch] > 0))
                return fail("material: sigma_s_prime=%s: must be > 0 mm^-1", value);
            if (k == VIEWER_EDIT_G && !(x[ch] > -1 && x[ch] < 1)) /* sigma_s = sigma_s' / (1 - g) */
                return fail("material: g=%s: must be in (-1, 1) (sigma_s' is kept: sigma_s = sigma_s' / (1 - g))",
                            value);
        }
        if (k >= VIEWER_EDIT_MELANIN && (x[0] != x[1] || x[0] != x[2] || !(x[0] >= 0 && x[0] <= 1)))
            return fail("material: %s=%s: one fraction in [0, 1]", key, value);
        if (k == VIEWER_EDIT_ETA && (x[0] != x[1] || x[0] != x[2]))
            return fail("material: eta=%s: one number (it is not per channel)", value);
        if (k == VIEWER_EDIT_ETA && !(x[0] >= LUCENT_MATERIAL_ETA_MIN && x[0] <= LUCENT_MATERIAL_ETA_MAX))
            return fail("material: eta=%s: must be in [%g, %g]", value, LUCENT_MATERIAL_ETA_MIN,
                        LUCENT_MATERIAL_ETA_MAX);
        c->edit[c->edit_count] = (viewer_edit)k;
        memcpy(c->edit_value[c->edit_count++], x, sizeof x);
        *eq = '=';
    }
    return LUCENT_OK;
}

static lucent_status index_of(viewer_command *c, int i, int count, const char *what)
{
    lucent_status st = number(c, i, 0, 1e9, true, &c->x[i]);
    if (st == LUCENT_OK && count > 0 && c->x[i] >= count)
        return fail("%s: no %s %g (the scene has %d)", k_actions[c->action].name, what, c->x[i], count);
    return st;
}

/* The words of one action (its name and count checked). */
static lucent_status check(viewer_command *c, const viewer_script_context *ctx)
{
    static const char *const layouts[] = {"single", "split", "side", NULL};
    static const char *const shows[] = {"image", "error", "reference", NULL};
    static const char *const formats[] = {"json", "c", "glsl", "hlsl", NULL};
    static const char *const keys[] = {"R", "TAB", "ESCAPE", NULL};
    const action_info *a = &k_actions[c->action];
    lucent_status st = LUCENT_OK;
    switch (c->action) {
    case VIEWER_ORBIT:
    case VIEWER_PAN:
        for (int i = 0; i < 2 && st == LUCENT_OK; i++) st = number(c, i, -DBL_MAX, DBL_MAX, false, &c->x[i]);
        return st; /* what the camera becomes is checked when it moves (viewer_orbit: finite) */
    case VIEWER_ZOOM:
        st = number(c, 0, 0, DBL_MAX, false, &c->x[0]);
        return st == LUCENT_OK && !(c->x[0] > 0) ? fail("zoom: the factor must be > 0") : st;
    case VIEWER_LIGHT:
        st = index_of(c, 0, ctx->light_count, "light");
        for (int i = 1; i < 3 && st == LUCENT_OK; i++) st = number(c, i, -DBL_MAX, DBL_MAX, false, &c->x[i]);
        return st;
    case VIEWER_SET: {
        char *eq = strchr(c->arg[0], '=');
        if (!eq) return fail("set '%s': expected KEY=VALUE", c->arg[0]);
        *eq = '\0';
        const lucent_setting *s = lucent_setting_find(c->arg[0], NULL);
        lucent_render_settings t = lucent_render_settings_defaults();
        lucent_render_method m;
        if (!s)
            st = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render.%s: no such setting", c->arg[0]);
        else if (!strcmp(s->key, "method"))
            st = lucent_render_method_parse(eq + 1, &m, &t);
        else
            st = lucent_setting_set(&t, s, eq + 1);
        *eq = '=';
        return st;
    }
    case VIEWER_METHOD:
    case VIEWER_METHOD_B: {
        lucent_render_settings t = lucent_render_settings_defaults();
        lucent_render_method m;
        return lucent_render_method_parse(c->arg[0], &m, &t);
    }
    case VIEWER_LAYOUT:
        if ((c->choice = pick(c->arg[0], layouts)) < 0) return fail("layout: '%s': single, split or side", c->arg[0]);
        c->x[1] = 0.5;
        return c->argc == 2 ? number(c, 1, 0, 1, false, &c->x[1]) : LUCENT_OK;
    case VIEWER_OBJECT: return index_of(c, 0, ctx->object_count, "object");
    case VIEWER_MATERIAL: return material(c, ctx);
    case VIEWER_SHOW:
        if ((c->choice = pick(c->arg[0], shows)) < 0) return fail("show: '%s': image, error or reference", c->arg[0]);
        return LUCENT_OK;
    case VIEWER_WINDOW_SHOT:
        return ctx->window ? LUCENT_OK : fail("window-shot %s: there is no window (headless)", c->arg[0]);
    case VIEWER_EXPORT_TAPS:
        if (c->argc == 2 && (c->choice = pick(c->arg[1], formats)) < 0)
            return fail("export-taps: '%s': json, c, glsl or hlsl", c->arg[1]);
        return LUCENT_OK;
    case VIEWER_RESIZE:
        for (int i = 0; i < 2 && st == LUCENT_OK; i++) st = number(c, i, 1, 16384, true, &c->x[i]);
        return st;
    case VIEWER_BENCH: c->x[0] = 10; return c->argc ? number(c, 0, 1, 100000, true, &c->x[0]) : LUCENT_OK;
    case VIEWER_FRAMES: return number(c, 0, 1, 100000, true, &c->x[0]);
    case VIEWER_WAIT_RELOAD:
    case VIEWER_UI_FRAMES: return number(c, 0, 0, 86400, false, &c->x[0]);
    case VIEWER_TRACE_WAIT:
        c->x[1] = 600;
        st = number(c, 0, 1, 1 << 24, true, &c->x[0]);
        return st == LUCENT_OK && c->argc == 2 ? number(c, 1, 0, 86400, false, &c->x[1]) : st;
    case VIEWER_KEY:
        if ((c->choice = pick(c->arg[0], keys)) >= 0) return LUCENT_OK;
        if (strlen(c->arg[0]) == 1 && c->arg[0][0] >= '1' && c->arg[0][0] <= '9')
            return c->choice = VIEWER_KEY_1 + (c->arg[0][0] - '1'), LUCENT_OK;
        return fail("key: '%s': R, TAB, ESCAPE or 1 to 9", c->arg[0]);
    case VIEWER_PANEL:
        if (c->argc && strcmp(c->arg[0], "all")) return fail("panel: '%s': nothing or all", c->arg[0]);
        c->choice = c->argc;
        return LUCENT_OK;
    default: (void)a; return LUCENT_OK;
    }
}

/* The words of one line, cut in place; the line's own number for the messages. */
static lucent_status line_words(char *line, int ln, char **words, int *count)
{
    int n = 0;
    char *save = NULL;
    for (char *t = strtok_r(line, " \t\r\v\f", &save); t; t = strtok_r(NULL, " \t\r\v\f", &save)) {
        if (n == VIEWER_SCRIPT_WORDS + 1) return fail("line %d: more than %d words", ln, VIEWER_SCRIPT_WORDS);
        words[n++] = t;
    }
    *count = n;
    return LUCENT_OK;
}

static lucent_status parse_line(char *line, int ln, const viewer_script_context *ctx, viewer_command *c, bool *empty)
{
    char *w[VIEWER_SCRIPT_WORDS + 2];
    int n = 0;
    lucent_status st = line_words(line, ln, w, &n);
    *empty = st == LUCENT_OK && (n == 0 || w[0][0] == '#');
    if (st != LUCENT_OK || *empty) return st;
    memset(c, 0, sizeof *c);
    c->line = ln;
    int first = 0;
    if (!strcmp(w[0], "async")) {
        if (n == 1) return fail("line %d (async): async needs an action to run without waiting (async ACTION ...)", ln);
        if (!strcmp(w[1], "async")) return fail("line %d (async): async async: one async is enough", ln);
        c->async = true, first = 1;
    }
    int a = 0;
    while (a < VIEWER_ACTION_COUNT && strcmp(w[first], k_actions[a].name)) a++;
    if (a == VIEWER_ACTION_COUNT)
        return fail("line %d (%.64s): unknown action '%.64s' (orbit, pan, zoom, reset, light, set, method, method-b, "
                    "layout, object, material, load-reference, show, save-scene, screenshot, window-shot, "
                    "export-taps, resize, print, bench, frames, wait-reload, trace-start, trace-wait, trace-stop, key, "
                    "ui-frames, panel, async, quit)",
                    ln, w[first], w[first]);
    c->action = (viewer_action)a;
    c->argc = n - first - 1;
    for (int i = 0; i < c->argc; i++) c->arg[i] = w[first + 1 + i];
    if (c->argc < k_actions[a].lo || c->argc > k_actions[a].hi)
        st = fail("usage: %s", k_actions[a].usage);
    else
        st = check(c, ctx);
    return st == LUCENT_OK ? st : lucent_error_context(st, "line %d (%s)", ln, k_actions[a].name);
}

void viewer_script_free(viewer_script *s)
{
    free(s->text);
    free(s->commands);
    memset(s, 0, sizeof *s);
}

lucent_status viewer_script_parse(const char *text, size_t size, const char *name, const viewer_script_context *ctx,
                                  viewer_script *dest)
{
    static const viewer_script_context none = {0};
    memset(dest, 0, sizeof *dest);
    if (!ctx) ctx = &none;
    char *copy = malloc(size + 1);
    size_t lines = 1;
    for (size_t i = 0; i < size; i++) lines += text[i] == '\n';
    viewer_command *cmds = calloc(lines, sizeof *cmds);
    if (!copy || !cmds)
        return free(copy), free(cmds), lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    memcpy(copy, text, size);
    copy[size] = '\0';
    lucent_status st = LUCENT_OK;
    int count = 0, ln = 1;
    for (size_t at = 0; at <= size && st == LUCENT_OK; ln++) {
        size_t end = at;
        while (end < size && copy[end] != '\n') end++;
        const char *nul = memchr(copy + at, '\0', end - at);
        if (nul) {
            st = fail("line %d: a NUL byte at column %zu (a script is text)", ln, (size_t)(nul - (copy + at)) + 1);
        } else if (end - at > VIEWER_SCRIPT_LINE) {
            st = fail("line %d: longer than %d characters", ln, VIEWER_SCRIPT_LINE);
        } else {
            copy[end] = '\0';
            bool empty;
            st = parse_line(copy + at, ln, ctx, &cmds[count], &empty);
            if (st == LUCENT_OK && !empty) count++;
        }
        at = end + 1;
    }
    if (st != LUCENT_OK) {
        free(copy), free(cmds);
        return lucent_error_context(st, "%s", name);
    }
    *dest = (viewer_script){.text = copy, .commands = cmds, .count = count};
    return LUCENT_OK;
}
