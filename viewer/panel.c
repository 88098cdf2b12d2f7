/* The panel: the methods (A, B and how they share the view), the settings built from the settings
 * table (lucent/settings.h: every group, every setting with its range and doc as a tooltip, so a
 * method added later shows its own), the material with its profile, kernel and taps plotted, the
 * reference and its error, and the outputs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ui.h"
#include "viewer.h"

static const char *method_name(void *user, int i)
{
    (void)user;
    return i >= 0 && i < LUCENT_METHOD_COUNT ? lucent_render_method_name((lucent_render_method)i) : NULL;
}

static const char *choice_name(void *user, int i) { return ((const lucent_setting *)user)->choice(i); }

static const char *preset_name(void *user, int i)
{
    static lucent_material m;
    (void)user;
    if (i < 0 || i >= lucent_material_preset_count() || lucent_material_preset(i, &m) != LUCENT_OK) return NULL;
    return m.name;
}

static const char *format_name(void *user, int i)
{
    (void)user;
    static const char *const names[] = {"json", "c", "glsl", "hlsl", NULL};
    return i >= 0 && i < 4 ? names[i] : NULL;
}

static void tooltip(const lucent_setting *s)
{
    char text[1024], range[256] = "";
    if (s->type == LUCENT_SETTING_INT || s->type == LUCENT_SETTING_REAL || s->type == LUCENT_SETTING_COLOR ||
        s->type == LUCENT_SETTING_SEED)
        snprintf(range, sizeof range, "range [%g, %g]%s, default %g", s->lo, s->hi,
                 (s->flags & LUCENT_SETTING_ODD) ? ", odd" : "", s->def);
    else if (s->choice) {
        snprintf(range, sizeof range, "one of ");
        for (int i = 0; s->choice(i); i++)
            snprintf(range + strlen(range), sizeof range - strlen(range), "%s%s", i ? ", " : "", s->choice(i));
        snprintf(range + strlen(range), sizeof range - strlen(range), "; default %s", s->def_text ? s->def_text : "");
    } else if (s->type == LUCENT_SETTING_BOOL) {
        snprintf(range, sizeof range, "default %s", s->def != 0 ? "true" : "false");
    }
    snprintf(text, sizeof text, "render.%s: %s\n%s", s->key, s->doc ? s->doc : "", range);
    ui_tooltip(text);
}

/* One setting's widget; a change goes through lucent_setting_set (ranges checked, related members
 * set) into the wanted settings. */
static void setting_widget(viewer *v, const lucent_setting *s)
{
    if (!strcmp(s->key, "width") || !strcmp(s->key, "height") || !strcmp(s->key, "method")) {
        char value[64];
        lucent_setting_format(&v->applied, s, value, sizeof value);
        ui_text("%s: %s (the view's)", s->key,
                !strcmp(s->key, "width")    ? (snprintf(value, sizeof value, "%d", v->frame_w), value)
                : !strcmp(s->key, "height") ? (snprintf(value, sizeof value, "%d", v->frame_h), value)
                                            : value);
        tooltip(s);
        return;
    }
    char *base = (char *)&v->wanted + s->offset, text[256] = "";
    bool changed = false;
    switch (s->type) {
    case LUCENT_SETTING_BOOL: {
        bool b = *(bool *)base;
        if ((changed = ui_checkbox(s->key, &b))) snprintf(text, sizeof text, "%s", b ? "true" : "false");
        break;
    }
    case LUCENT_SETTING_INT: {
        int i = *(int *)base, lo = (int)s->lo, hi = (int)fmin(s->hi, 1e9);
        if ((changed = ui_drag_int(s->key, &i, lo, hi))) {
            if ((s->flags & LUCENT_SETTING_ODD) && i % 2 == 0) i += i > *(int *)base ? 1 : -1;
            snprintf(text, sizeof text, "%d", i);
        }
        break;
    }
    case LUCENT_SETTING_SEED: {
        double d = (double)*(uint64_t *)base;
        if ((changed = ui_drag_double(s->key, &d, s->lo, fmin(s->hi, 1e9), false, "%.0f")))
            snprintf(text, sizeof text, "%.0f", d);
        break;
    }
    case LUCENT_SETTING_REAL: {
        double d = *(double *)base;
        bool lg = s->lo > 0 && s->hi / s->lo > 1e3;
        double hi = fmin(s->hi, lg ? 1e3 * fmax(s->def, s->lo) : s->hi), lo = lg ? fmax(s->lo, 1e-3 * s->def) : s->lo;
        if (!(hi > lo)) lo = s->lo, hi = s->hi;
        if ((changed = ui_drag_double(s->key, &d, lo, hi, lg, "%.4g"))) snprintf(text, sizeof text, "%.17g", d);
        break;
    }
    case LUCENT_SETTING_COLOR: {
        double c[3];
        memcpy(c, base, sizeof c);
        if ((changed = ui_color3(s->key, c))) snprintf(text, sizeof text, "%.9g,%.9g,%.9g", c[0], c[1], c[2]);
        break;
    }
    case LUCENT_SETTING_CHOICE:
    case LUCENT_SETTING_TEXT: {
        char cur[128];
        lucent_setting_format(&v->wanted, s, cur, sizeof cur);
        if (!s->choice) {
            ui_text("%s: %s", s->key, cur);
            break;
        }
        int index = 0;
        for (int i = 0; s->choice(i); i++)
            if (!strcmp(s->choice(i), cur)) index = i;
        if ((changed = ui_combo(s->key, &index, choice_name, (void *)s)))
            snprintf(text, sizeof text, "%s", s->choice(index));
        break;
    }
    }
    tooltip(s);
    if (changed && viewer_set(v, s->key, text) != LUCENT_OK) viewer_status(v, true, "%s", lucent_last_error());
}

static void methods(viewer *v)
{
    if (!ui_header("Methods", true)) return;
    int a = (int)v->wanted.view.method, b = (int)v->method_b;
    if (ui_combo("A", &a, method_name, NULL)) v->wanted.view.method = (lucent_render_method)a;
    ui_tooltip("the method drawn (keys 1-9); Tab swaps A and B");
    int layout = (int)v->layout;
    ui_radio("A only", &layout, VIEWER_SINGLE);
    ui_same_line();
    ui_radio("split A|B", &layout, VIEWER_SPLIT);
    ui_same_line();
    ui_radio("side by side", &layout, VIEWER_SIDE);
    v->layout = (viewer_layout)layout;
    if (v->layout != VIEWER_SINGLE && ui_combo("B", &b, method_name, NULL)) v->method_b = (lucent_render_method)b;
    if (v->layout == VIEWER_SPLIT) ui_drag_double("split", &v->split, 0, 1, false, "%.2f");
    float f;
    char label[256];
    if (viewer_baking(v, &f, label, sizeof label)) ui_progress(f, label);
}

static void settings(viewer *v)
{
    if (ui_header("Settings of A", true)) {
        const char *key;
        for (int i = 0; (key = lucent_render_method_setting(v->wanted.view.method, i)); i++) {
            const lucent_setting *s = lucent_setting_find(key, NULL);
            if (!s) continue;
            ui_push_id(1000 + i);
            setting_widget(v, s);
            ui_pop_id();
        }
        if (!lucent_render_method_setting(v->wanted.view.method, 0)) ui_text("(no settings of its own)");
    }
    if (!ui_header("All settings", false)) return;
    for (int g = 0; g < lucent_settings_group_count(); g++) {
        const lucent_settings_group *grp = lucent_settings_group_get(g);
        ui_text_colored(0.6f, 0.8f, 1.0f, "%s: %s", grp->name, grp->doc ? grp->doc : "");
        for (int i = 0; i < grp->count; i++) {
            ui_push_id(g * 100 + i);
            setting_widget(v, &grp->settings[i]);
            ui_pop_id();
        }
    }
}

/* The baked parts of the selected object's material, when the viewer has them. */
static const lucent_baked *object_baked(const viewer *v)
{
    const lucent_material *m = &v->scene->objects[v->object].material;
    for (int b = 0; b < v->baked_count; b++)
        if (!strcmp(v->baked_material[b].name, m->name) &&
            !memcmp(v->baked_material[b].sigma_a, m->sigma_a, sizeof m->sigma_a) &&
            !memcmp(v->baked_material[b].sigma_s, m->sigma_s, sizeof m->sigma_s))
            return &v->baked[b];
    return NULL;
}

enum { PLOT_MAX = 512 };

static void plots(viewer *v)
{
    const lucent_baked *b = object_baked(v);
    static const uint32_t rgb[3] = {0xFF5050FFu, 0xFF50FF50u, 0xFFFF7070u};
    static double x[PLOT_MAX], y[3][PLOT_MAX];
    if (!b || !b->profile) {
        ui_text("(the profile and taps appear once a method bakes them: ssss)");
        return;
    }
    const lucent_profile *p = b->profile;
    int n = 0, step = p->count / PLOT_MAX + 1;
    for (int j = 0; j < p->count && n < PLOT_MAX; j += step, n++) {
        x[n] = p->r[j];
        for (int c = 0; c < 3; c++) y[c][n] = p->value[c][j] * p->r[j]; /* r R(r): the power per radius */
    }
    ui_series s[3];
    for (int c = 0; c < 3; c++) s[c] = (ui_series){x, y[c], n, rgb[c], false};
    char label[LUCENT_BAKE_KEY_SIZE + 64];
    snprintf(label, sizeof label, "profile r R(r), %s (log)", p->model);
    ui_plot(label, s, 3, 90, true);
    const lucent_taps *t = b->taps;
    if (!t) return;
    /* The kernel's axis slice as its taps sample it: weight per mm (weight over the tap's interval)
     * of pass 1, and the taps themselves as stems. */
    static double xs[256], ys[3][256], ws[3][256];
    int m = t->count < 256 ? t->count : 256;
    for (int i = 0; i < m; i++) {
        xs[i] = t->offset[i];
        double lo = i > 0 ? t->offset[i - 1] : t->offset[i], hi = i < m - 1 ? t->offset[i + 1] : t->offset[i];
        double width = 0.5 * fabs(hi - lo);
        for (int c = 0; c < 3; c++) {
            ws[c][i] = t->weight[c][i];
            ys[c][i] = width > 0 ? t->weight[c][i] / width : 0;
        }
    }
    /* offsets are listed centre first: sort a copy by offset for the curve */
    static double xo[256], yo[3][256];
    int idx[256];
    for (int i = 0; i < m; i++) idx[i] = i;
    for (int i = 1; i < m; i++)
        for (int k = i; k > 0 && xs[idx[k - 1]] > xs[idx[k]]; k--) {
            int tmp = idx[k];
            idx[k] = idx[k - 1], idx[k - 1] = tmp;
        }
    for (int i = 0; i < m; i++) {
        xo[i] = xs[idx[i]];
        for (int c = 0; c < 3; c++) yo[c][i] = c < 3 ? ys[c][idx[i]] : 0;
    }
    for (int i = 0; i < m; i++) { /* the interval widths again in sorted order */
        double lo = i > 0 ? xo[i - 1] : xo[i], hi = i < m - 1 ? xo[i + 1] : xo[i], width = 0.5 * fabs(hi - lo);
        for (int c = 0; c < 3; c++) yo[c][i] = width > 0 ? t->weight[c][idx[i]] / width : 0;
    }
    for (int c = 0; c < 3; c++) s[c] = (ui_series){xo, yo[c], m, rgb[c], false};
    snprintf(label, sizeof label, "kernel axis slice (pass 1), %s", b->taps_key);
    ui_plot(label, s, 3, 80, false);
    for (int c = 0; c < 3; c++) s[c] = (ui_series){xs, ws[c], m, rgb[c], true};
    snprintf(label, sizeof label, "%d taps x %d passes (weights)", t->count, t->rank);
    ui_plot(label, s, 3, 70, false);
}

/* A spectral skin's chromophores (docs/skin.md): each change resolves its equivalent medium again and
 * starts a bake of its spectral profile. */
static void skin_sliders(viewer *v, lucent_material *m)
{
    lucent_skin old = m->skin;
    for (int i = 0; i < m->skin.layer_count; i++) {
        lucent_skin_layer *l = &m->skin.layer[i];
        char label[48];
        if (l->kind == LUCENT_SKIN_EPIDERMIS) {
            ui_drag_double("melanin", &l->melanin, 0.0, 0.5, false, "%.4f");
            ui_tooltip("melanosome volume fraction of the epidermis");
            ui_drag_double("eumelanin", &l->eumelanin, 0.0, 1.0, false, "%.2f");
            ui_tooltip("eumelanin share of the melanin (the rest pheomelanin)");
        } else {
            snprintf(label, sizeof label, "blood (%s)", lucent_skin_layer_name(l->kind));
            ui_drag_double(label, &l->blood, 0.0, 0.5, false, "%.4f");
            ui_tooltip("blood volume fraction of the layer");
            snprintf(label, sizeof label, "oxygenation (%s)", lucent_skin_layer_name(l->kind));
            ui_drag_double(label, &l->oxygenation, 0.0, 1.0, false, "%.2f");
            ui_tooltip("oxygen saturation of the blood");
        }
    }
    if (!memcmp(&old, &m->skin, sizeof old)) return;
    m->skin.resolved = 0;
    if (lucent_skin_resolve(m) != LUCENT_OK) {
        viewer_status(v, true, "%s", lucent_last_error());
        m->skin = old;
        return;
    }
    viewer_material_edited(v, v->object);
}

static void material(viewer *v)
{
    if (!ui_header("Material", true)) return;
    lucent_scene *sc = v->scene;
    if (sc->object_count > 1) {
        ui_drag_int("object", &v->object, 0, sc->object_count - 1);
        ui_same_line();
        ui_text("%s", sc->objects[v->object].name);
    }
    lucent_material *m = &v->wanted_material[v->object];
    int preset = -1;
    lucent_material p;
    for (int i = 0; i < lucent_material_preset_count(); i++)
        if (lucent_material_preset(i, &p) == LUCENT_OK && !strcmp(p.name, m->name)) preset = i;
    if (ui_combo("preset", &preset, preset_name, NULL) && lucent_material_preset(preset, &p) == LUCENT_OK &&
        lucent_skin_resolve(&p) == LUCENT_OK)
        *m = p;
    ui_tooltip("Jensen et al. 2001's measured materials and the spectral skins (lucent materials)");
    ui_text("%s", m->name);
    if (m->skin.layer_count > 0) {
        skin_sliders(v, m);
        plots(v);
        return;
    }
    bool edited = false;
    double sp[3];
    for (int c = 0; c < 3; c++) sp[c] = m->sigma_s[c] * (1 - m->g[c]);
    double g[3] = {m->g[0], m->g[1], m->g[2]};
    edited |= ui_drag_double3("sigma_a", m->sigma_a, 1e-5, 100, true, "%.3g");
    ui_tooltip("absorption coefficient per channel (R, G, B), mm^-1");
    bool scatter = ui_drag_double3("sigma_s'", sp, 1e-4, 1000, true, "%.3g");
    ui_tooltip("reduced scattering coefficient sigma_s (1 - g) per channel, mm^-1");
    if (ui_drag_double3("g", g, -0.99, 0.99, false, "%.2f")) memcpy(m->g, g, sizeof g), scatter = true;
    ui_tooltip("Henyey-Greenstein mean cosine per channel (sigma_s' is kept)");
    for (int c = 0; scatter && c < 3; c++) m->sigma_s[c] = sp[c] / (1 - m->g[c]);
    edited |= scatter;
    edited |= ui_drag_double("eta", &m->eta, LUCENT_MATERIAL_ETA_MIN, LUCENT_MATERIAL_ETA_MAX, false, "%.3f");
    ui_tooltip("relative index of refraction");
    if (edited) viewer_material_edited(v, v->object);
    if (ui_header("Profile, kernel and taps", false)) plots(v); /* closed: the panel fits a 768-row screen */
}

static void lights(viewer *v)
{
    if (!ui_header("Camera and light", false)) return;
    if (ui_button("reset camera (R)")) viewer_reset_camera(v);
    const lucent_camera *c = &v->scene->camera;
    ui_text("camera at %.1f %.1f %.1f mm", c->position[0], c->position[1], c->position[2]);
    if (v->scene->light_count > 1) ui_drag_int("light", &v->light, 0, v->scene->light_count - 1);
    const lucent_light *l = &v->scene->lights[v->light];
    ui_text("light %d: %s, ctrl-drag turns it", v->light, lucent_light_type_name(l->type));
    if (l->type == LUCENT_LIGHT_DIRECTIONAL)
        ui_text("direction %.3f %.3f %.3f", l->direction[0], l->direction[1], l->direction[2]);
}

static void reference(viewer *v)
{
    if (!ui_header("Reference", v->reference != NULL)) return;
    ui_input_text("EXR", v->ref_input, sizeof v->ref_input);
    ui_tooltip("the linear EXR of `lucent trace` for this scene");
    ui_same_line();
    if (ui_button("load")) {
        if (viewer_load_reference(v, v->ref_input) != LUCENT_OK) viewer_status(v, true, "%s", lucent_last_error());
    }
    if (!v->trace.running && ui_button("start a progressive trace") && viewer_trace_start(v) != LUCENT_OK)
        viewer_status(v, true, "%s", lucent_last_error());
    ui_tooltip("path-trace the scene as it is now (camera, lights, materials, settings) at the frame's size on a "
               "thread of its own; each pass becomes the reference");
    if (v->trace.running) {
        ui_same_line();
        if (ui_button("stop the trace")) viewer_trace_stop(v);
    }
    if (!v->reference) return;
    ui_text("%s (%dx%d)", v->reference_path, v->reference->width, v->reference->height);
    if (ui_checkbox("render at its size", &v->match_reference)) v->gen++;
    int show = (int)v->show;
    ui_radio("image", &show, VIEWER_SHOW_IMAGE);
    ui_same_line();
    ui_radio("error map", &show, VIEWER_SHOW_ERROR);
    ui_same_line();
    ui_radio("reference", &show, VIEWER_SHOW_REFERENCE);
    if (show != (int)v->show) v->show = (viewer_show)show, v->show_gen = 0;
    ui_text("relative RMS error of A: %.4f", v->rel_rms);
    ui_tooltip("sqrt(mean (A - ref)^2) / sqrt(mean ref^2) over the object's pixels, R, G, B pooled "
               "(lucent_image_compare)");
    if (ui_button("drop reference")) viewer_drop_reference(v);
}

static void outputs(viewer *v)
{
    if (!ui_header("Save", false)) return;
    ui_input_text("scene", v->save_path, sizeof v->save_path);
    ui_same_line();
    if (ui_button("save##scene") && viewer_save_scene(v, v->save_path) != LUCENT_OK)
        viewer_status(v, true, "%s", lucent_last_error());
    ui_input_text("screenshot", v->shot_path, sizeof v->shot_path);
    ui_same_line();
    if (ui_button("save##shot") && viewer_screenshot(v, v->shot_path) != LUCENT_OK)
        viewer_status(v, true, "%s", lucent_last_error());
    ui_input_text("taps", v->taps_path, sizeof v->taps_path);
    ui_same_line();
    if (ui_button("save##taps") && viewer_export_taps(v, v->taps_path, format_name(NULL, v->taps_format)) != LUCENT_OK)
        viewer_status(v, true, "%s", lucent_last_error());
    ui_combo("taps format", &v->taps_format, format_name, NULL);
    ui_checkbox("reload the scene file when it changes", &v->hot_reload);
    if (v->set_form[0]) {
        ui_text("as --set options:");
        ui_text_wrapped(v->set_form);
    }
}

void viewer_panel(viewer *v)
{
    ui_panel_begin("Lucent view", 0, 0, (float)v->panel_w, (float)v->win_h);
    ui_text("%s", v->scene->name);
    ui_item_width((float)v->panel_w * 0.55f);
    methods(v);
    settings(v);
    material(v);
    lights(v);
    reference(v);
    outputs(v);
    ui_item_width(0);
    if (v->status[0]) {
        ui_separator();
        if (v->status_error)
            ui_text_colored(1, 0.45f, 0.4f, "%s", v->status);
        else
            ui_text_wrapped(v->status);
    }
    ui_panel_end();
}
