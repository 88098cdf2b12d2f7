/* What the viewer writes and reads besides the scene: the scene with the tuned settings (and the
 * same as --set options), screenshots (PNG tonemapped, EXR linear), the window with its panel, the
 * kernel taps of the selected material, and the reference with the error of method A against it. */
#include <cjson/cJSON.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "ui.h"
#include "viewer.h"

/* ---- the scene ---- */

static cJSON *numbers(const double *x, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; a && i < n; i++) cJSON_AddItemToArray(a, cJSON_CreateNumber(x[i]));
    return a;
}

static void put(cJSON *o, const char *key, cJSON *value)
{
    if (!value) return;
    if (cJSON_GetObjectItemCaseSensitive(o, key))
        cJSON_ReplaceItemInObjectCaseSensitive(o, key, value);
    else
        cJSON_AddItemToObject(o, key, value);
}

/* The preset's name when m is one, else the material as a JSON object (docs/materials.md). */
static cJSON *material_json(const lucent_material *m)
{
    lucent_material p;
    if (lucent_material_preset_find(m->name, &p) == LUCENT_OK && lucent_skin_resolve(&p) == LUCENT_OK &&
        !memcmp(&p, m, sizeof p))
        return cJSON_CreateString(m->name);
    if (m->skin.layer_count > 0) { /* a spectral skin: its chromophores, as a material file has them */
        char *text = NULL;
        cJSON *doc = lucent_material_to_json(m, 1, false, &text) == LUCENT_OK ? cJSON_Parse(text) : NULL;
        free(text);
        cJSON *one = doc ? cJSON_DetachItemFromArray(cJSON_GetObjectItemCaseSensitive(doc, "materials"), 0) : NULL;
        cJSON_Delete(doc);
        return one;
    }
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddStringToObject(o, "name", m->name);
    cJSON_AddStringToObject(o, "units", "mm^-1");
    cJSON_AddItemToObject(o, "sigma_a", numbers(m->sigma_a, 3));
    cJSON_AddItemToObject(o, "sigma_s", numbers(m->sigma_s, 3));
    cJSON_AddItemToObject(o, "g", numbers(m->g, 3));
    cJSON_AddNumberToObject(o, "eta", m->eta);
    return o;
}

/* A setting's value as JSON, from the text lucent_setting_format writes. */
static cJSON *setting_json(const lucent_render_settings *s, const lucent_setting *st)
{
    char text[256];
    lucent_setting_format(s, st, text, sizeof text);
    switch (st->type) {
    case LUCENT_SETTING_BOOL: return cJSON_CreateBool(!strcmp(text, "true"));
    case LUCENT_SETTING_CHOICE:
    case LUCENT_SETTING_TEXT: return cJSON_CreateString(text);
    case LUCENT_SETTING_COLOR: {
        double c[3] = {0, 0, 0};
        memcpy(c, (const char *)s + st->offset, sizeof c);
        return numbers(c, 3);
    }
    case LUCENT_SETTING_SEED: return cJSON_CreateNumber((double)*(const uint64_t *)((const char *)s + st->offset));
    case LUCENT_SETTING_INT: return cJSON_CreateNumber(*(const int *)((const char *)s + st->offset));
    default: return cJSON_CreateNumber(*(const double *)((const char *)s + st->offset));
    }
}

/* Relative file names of the scene resolved against its folder (the saved file may live elsewhere). */
static void absolute_path(cJSON *o, const char *key, const char *scene_dir)
{
    cJSON *item = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsString(item) || item->valuestring[0] == '/') return;
    char joined[2 * PATH_MAX], real[PATH_MAX];
    snprintf(joined, sizeof joined, "%s/%s", scene_dir, item->valuestring);
    if (realpath(joined, real)) cJSON_ReplaceItemInObjectCaseSensitive(o, key, cJSON_CreateString(real));
}

static void append(char *dest, size_t size, const char *fmt, const char *key, const char *value)
{
    size_t n = strlen(dest);
    snprintf(dest + n, size - n, fmt, key, value);
}

/* Every number of a JSON tree is finite (cJSON writes NaN and infinities as null). */
static const char *non_finite(const cJSON *item, char *where, size_t size)
{
    for (const cJSON *c = item ? item->child : NULL; c; c = c->next) {
        if (cJSON_IsNumber(c) && !isfinite(c->valuedouble)) {
            snprintf(where, size, "%s", c->string ? c->string : "a value");
            return where;
        }
        if (non_finite(c, where, size)) return where;
    }
    return NULL;
}

/* The scene as the viewer shows it, as JSON text (free with free()), and what differs from the file
 * as --set options into set. */
static lucent_status scene_text(viewer *v, char **dest, char *set, size_t set_size)
{
    const lucent_scene *sc = v->scene;
    cJSON *root = sc->json ? cJSON_Parse(sc->json) : NULL;
    if (!root) return lucent_error(LUCENT_ERR_INTERNAL, "the scene's JSON is not at hand");
    char value[4096];
    set[0] = '\0';
    lucent_camera shown;
    viewer_shown_camera(v, &shown); /* A's, as drawn */
    const lucent_camera *c = &shown;
    cJSON *cam = cJSON_CreateObject();
    put(cam, "position", numbers(c->position, 3));
    put(cam, "target", numbers(c->target, 3));
    put(cam, "up", numbers(c->up, 3));
    put(cam, "fov_y", cJSON_CreateNumber(c->fov_y));
    put(cam, "near", cJSON_CreateNumber(c->near_plane));
    put(cam, "far", cJSON_CreateNumber(c->far_plane));
    char *ct = cJSON_PrintUnformatted(cam);
    if (ct && memcmp(c, &v->home, sizeof *c)) append(set, set_size, " --set '%s=%s'", "camera", ct);
    free(ct);
    put(root, "camera", cam);
    cJSON *lights = cJSON_GetObjectItemCaseSensitive(root, "lights");
    for (int i = 0; i < sc->light_count && cJSON_IsArray(lights); i++) {
        const lucent_light *l = &sc->lights[i];
        cJSON *lo = cJSON_GetArrayItem(lights, i);
        if (!cJSON_IsObject(lo) || l->type == LUCENT_LIGHT_ENVIRONMENT) continue;
        bool dir = l->type == LUCENT_LIGHT_DIRECTIONAL;
        const char *key = dir ? "direction" : "position";
        const double *now = dir ? l->direction : l->position,
                     *was = dir ? v->home_lights[i].direction : v->home_lights[i].position;
        if (!memcmp(now, was, 3 * sizeof *now)) continue; /* as in the file */
        cJSON *item = numbers(now, 3);
        char *is = cJSON_PrintUnformatted(item), k[64];
        cJSON_Delete(item);
        snprintf(k, sizeof k, "lights[%d].%s", i, key);
        if (is) append(set, set_size, " --set '%s=%s'", k, is);
        free(is);
        put(lo, key, numbers(now, 3));
    }
    char dir_copy[VIEWER_PATH];
    snprintf(dir_copy, sizeof dir_copy, "%s", sc->path[0] ? sc->path : ".");
    const char *scene_dir = dirname(dir_copy);
    cJSON *objects = cJSON_GetObjectItemCaseSensitive(root, "objects");
    for (int i = 0; i < sc->object_count && cJSON_IsArray(objects); i++) {
        cJSON *o = cJSON_GetArrayItem(objects, i);
        if (!cJSON_IsObject(o)) continue;
        absolute_path(o, "mesh", scene_dir);
        absolute_path(o, "albedo_texture", scene_dir);
        cJSON *m = material_json(&sc->objects[i].material);
        char *was = cJSON_PrintUnformatted(cJSON_GetObjectItemCaseSensitive(o, "material")),
             *is = cJSON_PrintUnformatted(m);
        if (was && is && strcmp(was, is)) {
            char k[64];
            snprintf(k, sizeof k, "objects[%d].material", i);
            append(set, set_size, cJSON_IsString(m) ? " --set %s=%s" : " --set '%s=%s'", k,
                   cJSON_IsString(m) ? m->valuestring : is);
        }
        free(was), free(is);
        put(o, "material", m);
    }
    cJSON *render = cJSON_GetObjectItemCaseSensitive(root, "render");
    if (!render) render = cJSON_AddObjectToObject(root, "render");
    lucent_render_settings s = viewer_frame_settings(v, false, v->frame_w, v->frame_h);
    lucent_render_settings def = lucent_render_settings_defaults();
    for (int g = 0; g < lucent_settings_group_count(); g++) {
        const lucent_settings_group *grp = lucent_settings_group_get(g);
        for (int i = 0; i < grp->count; i++) {
            const lucent_setting *st = &grp->settings[i];
            char a[256], b[256], f[256];
            lucent_setting_format(&s, st, a, sizeof a);
            lucent_setting_format(&def, st, b, sizeof b);
            lucent_setting_format(&sc->render, st, f, sizeof f);
            if (strcmp(a, b) || cJSON_GetObjectItemCaseSensitive(render, st->key))
                put(render, st->key, setting_json(&s, st));
            if (strcmp(a, f)) {
                char k[64];
                snprintf(k, sizeof k, "render.%s", st->key);
                snprintf(value, sizeof value, "%s", a);
                append(set, set_size, strpbrk(value, " ,[]{}'\"") ? " --set '%s=%s'" : " --set %s=%s", k, value);
            }
        }
    }
    char where[128];
    if (non_finite(root, where, sizeof where)) { /* never written as null (issue 32 item 14) */
        cJSON_Delete(root);
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s is not finite: nothing written", where);
    }
    *dest = cJSON_Print(root);
    cJSON_Delete(root);
    return *dest ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
}

lucent_status viewer_scene_text(viewer *v, char **dest)
{
    static char set[sizeof v->set_form];
    return scene_text(v, dest, set, sizeof set);
}

/* The file a path names: the same inode when both exist, else the same folder (resolved) and name. */
static bool same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char full[2][PATH_MAX + 256];
    const char *paths[2] = {a, b};
    for (int i = 0; i < 2; i++) {
        char d[PATH_MAX], n[PATH_MAX], real[PATH_MAX];
        snprintf(d, sizeof d, "%s", paths[i]);
        snprintf(n, sizeof n, "%s", paths[i]);
        const char *dir = dirname(d), *base = basename(n);
        if (!realpath(dir, real)) snprintf(real, sizeof real, "%s", dir);
        snprintf(full[i], sizeof full[i], "%s/%s", real, base);
    }
    return strcmp(full[0], full[1]) == 0;
}

/* The files the viewer reads: the scene file, the script, the reference, the objects' meshes and the
 * files the scene names (materials, textures) relative to its folder. NULL when path is none of
 * them, else the role of the one it is. */
static const char *names_input(const viewer *v, const char *path)
{
    const lucent_scene *sc = v->scene;
    if (same_file(path, v->opt.scene) || (sc->path[0] && same_file(path, sc->path))) return "the open scene file";
    if (v->opt.script && same_file(path, v->opt.script)) return "the script";
    if (v->reference && v->reference_path[0] && !v->trace.running && same_file(path, v->reference_path))
        return "the reference";
    for (int i = 0; i < sc->object_count; i++)
        if (strncmp(sc->objects[i].mesh_source, "primitive:", 10) && same_file(path, sc->objects[i].mesh_source))
            return "a mesh of the scene";
    cJSON *root = sc->json ? cJSON_Parse(sc->json) : NULL, *objects = cJSON_GetObjectItemCaseSensitive(root, "objects");
    char dir_copy[VIEWER_PATH], file[2 * VIEWER_PATH];
    snprintf(dir_copy, sizeof dir_copy, "%s", sc->path[0] ? sc->path : ".");
    const char *scene_dir = dirname(dir_copy), *role = NULL;
    static const char *const keys[] = {"material", "albedo_texture", "mesh"};
    for (int i = 0; !role && i < cJSON_GetArraySize(objects); i++)
        for (int k = 0; !role && k < 3; k++) {
            const cJSON *item = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(objects, i), keys[k]);
            if (!cJSON_IsString(item)) continue;
            snprintf(file, sizeof file, "%s%s%.*s", item->valuestring[0] == '/' ? "" : scene_dir,
                     item->valuestring[0] == '/' ? "" : "/", (int)strcspn(item->valuestring, "#"), item->valuestring);
            if (same_file(path, file)) role = k == 0 ? "a material file of the scene" : "a file of the scene";
        }
    cJSON_Delete(root);
    return role;
}

lucent_status viewer_save_scene(viewer *v, const char *path)
{
    const lucent_scene *sc = v->scene;
    char set[sizeof v->set_form - LUCENT_SCENE_PATH_SIZE - 16], *text = NULL;
    char args[VIEWER_PATH + 16];
    snprintf(args, sizeof args, "%s", path);
    char *dot = strrchr(args, '.'), *slash = strrchr(args, '/');
    if (dot && (!slash || dot > slash)) *dot = '\0';
    snprintf(args + strlen(args), sizeof args - strlen(args), ".sets.txt");
    const char *outs[2] = {path, args}, *role;
    for (int i = 0; i < 2; i++) /* issue 32 item 14: save-scene could replace the open scene file */
        if ((role = names_input(v, outs[i])))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "save-scene: %s is %s: it would be overwritten", outs[i],
                                role);
    lucent_status st = scene_text(v, &text, set, sizeof set);
    if (st != LUCENT_OK) return lucent_error_context(st, "save-scene %s", path);
    st = lucent_write_file(path, text, strlen(text));
    free(text);
    if (st != LUCENT_OK) return st;
    snprintf(v->set_form, sizeof v->set_form, "lucent render %s%s", sc->path, set);
    char line[sizeof v->set_form + 2];
    snprintf(line, sizeof line, "%s\n", v->set_form);
    st = lucent_write_file(args, line, strlen(line));
    if (st == LUCENT_OK) viewer_status(v, false, "wrote %s and %s", path, args);
    return st;
}

/* ---- images ---- */

static void stem_of(const char *path, char *dest, size_t size)
{
    snprintf(dest, size, "%s", path);
    char *dot = strrchr(dest, '.'), *slash = strrchr(dest, '/');
    if (dot && (!slash || dot > slash) && (!strcmp(dot, ".png") || !strcmp(dot, ".exr"))) *dot = '\0';
}

/* What the view shows (issue 32 item 15): method A's last frame (PNG tonemapped with the settings,
 * EXR linear), or the error map (its heat map's colours, PNG and EXR alike), or the reference. */
lucent_status viewer_screenshot(viewer *v, const char *path)
{
    char stem[VIEWER_PATH], png[VIEWER_PATH + 8], exr[VIEWER_PATH + 8];
    stem_of(path, stem, sizeof stem);
    snprintf(png, sizeof png, "%s.png", stem);
    snprintf(exr, sizeof exr, "%s.exr", stem);
    const lucent_image *img = v->shown.count ? v->shown.image[0] : NULL;
    const char *what = lucent_render_method_name(v->applied.view.method);
    bool tonemap = true;
    if (v->show == VIEWER_SHOW_ERROR && v->error_map)
        img = v->error_map, what = "the error map", tonemap = false;
    else if (v->show == VIEWER_SHOW_REFERENCE && v->reference)
        img = v->reference, what = "the reference";
    if (!img) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "screenshot %s: no frame drawn yet", path);
    const lucent_view_settings *vs = &v->applied.view;
    lucent_image *tm = NULL;
    lucent_status st = lucent_image_write(exr, img, NULL);
    if (st == LUCENT_OK) st = lucent_image_clone(img, &tm);
    if (st == LUCENT_OK) {
        if (tonemap)
            lucent_image_tonemap(tm, &(lucent_tonemap_desc){.op = vs->tonemap, .exposure = (float)vs->exposure});
        st = lucent_image_write(png, tm, NULL);
    }
    lucent_image_destroy(tm);
    if (st == LUCENT_OK)
        viewer_status(v, false, "wrote %s and %s (%s, %dx%d)", png, exr, what, img->width, img->height);
    return st;
}

lucent_status viewer_window_shot(viewer *v, const char *path)
{
    if (!v->window) return lucent_error(LUCENT_ERR_UNSUPPORTED, "window-shot %s: there is no window (headless)", path);
    int w = v->win_w, h = v->win_h;
    uint8_t *rgba = malloc((size_t)w * h * 4);
    lucent_image *img = NULL;
    lucent_status st =
        rgba ? lucent_image_create(w, h, 3, &img) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (st == LUCENT_OK && !ui_read_window(w, h, rgba))
        st = lucent_error(LUCENT_ERR_GL, "window-shot: cannot read the window");
    for (size_t i = 0; st == LUCENT_OK && i < (size_t)w * h * 3;
         i++) { /* sRGB bytes to the linear values PNG writing expects */
        float x = rgba[i / 3 * 4 + i % 3] / 255.0f;
        img->data[i] = x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
    }
    if (st == LUCENT_OK) st = lucent_image_write(path, img, NULL);
    if (st == LUCENT_OK) viewer_status(v, false, "wrote %s (the window, %dx%d)", path, w, h);
    lucent_image_destroy(img);
    free(rgba);
    return st;
}

lucent_status viewer_export_taps(viewer *v, const char *path, const char *format)
{
    lucent_kernel_format f;
    lucent_status st = lucent_kernel_format_parse(format ? format : "json", &f);
    if (st != LUCENT_OK) return st;
    const lucent_material *m = &v->scene->objects[v->object].material;
    const lucent_baked *b = NULL;
    for (int k = 0; k < v->baked_count; k++)
        if (!memcmp(&v->baked_material[k], m, sizeof *m)) b = &v->baked[k];
    if (!b || !b->taps)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no taps baked for %s (taps come with method ssss)", path,
                            m->name);
    char *text = NULL, label[LUCENT_MATERIAL_NAME_SIZE + LUCENT_BAKE_KEY_SIZE + 4];
    snprintf(label, sizeof label, "%s %s", m->name, b->taps_key);
    st = lucent_taps_export(b->taps, f, label, &text);
    if (st == LUCENT_OK) st = lucent_write_file(path, text, strlen(text));
    free(text);
    if (st == LUCENT_OK) viewer_status(v, false, "wrote %s (%d taps of %s)", path, b->taps->count, m->name);
    return st;
}

/* ---- the reference ---- */

void viewer_drop_reference(viewer *v)
{
    viewer_trace_stop(v);
    lucent_image_destroy(v->reference);
    lucent_image_destroy(v->error_map);
    v->reference = v->error_map = NULL;
    v->reference_path[0] = '\0';
    v->show = VIEWER_SHOW_IMAGE, v->show_gen = 0;
    v->ref_gen++;
    v->gen++;
}

lucent_status viewer_load_reference(viewer *v, const char *path)
{
    lucent_image *img = NULL, *rgb = NULL;
    lucent_status st = lucent_image_load(path, &img);
    if (st == LUCENT_OK && img->channels != 3) st = lucent_image_convert_channels(img, 3, &rgb);
    if (st != LUCENT_OK) return lucent_image_destroy(img), lucent_error_context(st, "reference");
    if (rgb) lucent_image_destroy(img), img = rgb;
    viewer_drop_reference(v);
    v->reference = img;
    snprintf(v->reference_path, sizeof v->reference_path, "%s", path);
    v->ref_gen++, v->show_gen = 0;
    v->gen++;
    viewer_status(v, false, "reference %s: %dx%d", path, img->width, img->height);
    return LUCENT_OK;
}

/* The error of A's last frame against the reference (the frame is read back by the render thread). */
lucent_status viewer_update_error(viewer *v)
{
    const viewer_frame *f = &v->shown;
    v->error_gen = f->gen, v->error_ref_gen = v->ref_gen, v->show_gen = 0;
    lucent_image_destroy(v->error_map);
    v->error_map = NULL;
    v->rel_rms = NAN;
    lucent_image_error_stats e;
    if (f->image[0] && f->image[0]->width == v->reference->width && f->image[0]->height == v->reference->height &&
        lucent_image_compare_masked(f->image[0], v->reference, f->mask, &e) == LUCENT_OK) {
        v->rel_rms = e.rel_rms_all;
        lucent_compare_error_map(f->image[0], v->reference, f->mask->data, &v->error_map);
    }
    return LUCENT_OK;
}
