/* `lucent render`: a scene through the real-time OpenGL renderer (Lambert, CDRF, CDRF with
 * translucency, screen-space separable SSS), to a tonemapped PNG, a linear EXR and a JSON sidecar
 * with per-pass GPU timings; or live in a window. */
#include <errno.h>
#include <libgen.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "cli.h"
#include "lucent/render.h"

enum { MAX_SETS = 64, MAX_FRAMES = 10000 };

static const char k_usage[] =
    "usage: lucent render SCENE.json [--method M] [--set KEY=VALUE]... --out IMAGE [options]\n"
    "\n"
    "Renders SCENE (docs/scenes.md) with OpenGL 4.5 core: headless through EGL (Mesa's surfaceless\n"
    "platform, llvmpipe without a GPU; the EGL device platform on NVIDIA) or in a window. Writes the\n"
    "image tonemapped (render.tonemap, render.exposure) as PNG, or linear as EXR/PFM, and a JSON\n"
    "sidecar: the scene after overrides, the settings, the GL renderer, per-pass GPU times (timer\n"
    "queries), sigma0 and kernel taps (docs/render.md).\n"
    "\n"
    "methods (--method, or render.method in the scene):\n"
    "  lambert              Lambert diffuse + Kelemen/Szirmay-Kalos specular (Beckmann, Schlick)\n"
    "  cdrf                 Kubo's curvature-dependent reflectance (LUT, or render.cdrf_lut=false)\n"
    "  cdrf+translucency    the CDRF plus curvature-modulated transmission (the CDRF blog)\n"
    "  ssss[:MODEL[RANK]]   Jimenez's screen-space separable SSS with a kernel of `lucent kernel`\n"
    "                       (ssss:preint, ssss:svd3, ssss:jimenez, ...)\n"
    "  points[:VARIANT]     surfels: splatting and splat-based diffusion (Kim et al.; docs/points.md);\n"
    "                       points:sog4, points:deon (d'Eon's skin table), points:brdf, points:disks\n"
    "  tsd                  d'Eon & Luebke's texture-space diffusion: irradiance in the texture atlas,\n"
    "                       a chain of stretch-corrected Gaussian blurs (docs/tsd.md)\n"
    "\n"
    "options:\n"
    "  --method M          the method (same as --set render.method=M)\n"
    "  --set KEY=VALUE     override a scene value (repeatable): render.width=1024, camera.fov_y=25,\n"
    "                      objects[0].material=skin1, 'lights[0].direction=[1,-0.2,-0.3]'\n"
    "  --out FILE          the image: .png (tonemapped, sRGB), .exr or .pfm (linear)\n"
    "  --exr FILE          also the linear HDR image as OpenEXR\n"
    "  --mask FILE         the object-coverage mask (1 channel)\n"
    "  --json FILE         the sidecar (default: the --out name with .json)\n"
    "  --frames N          render N frames and report the mean time of frames 2..N (default 1)\n"
    "  --window            show the render in a window until it is closed (Esc or Q)\n"
    "  --gl-platform P     auto (default), surfaceless, device or window (LUCENT_GL_PLATFORM)\n"
    "  --gl-device N       EGL device number, from 1 (LUCENT_GL_DEVICE)\n"
    "  --cache DIR         where sigma0 fits and slab tables are kept (default $LUCENT_CACHE_DIR, else\n"
    "                      $XDG_CACHE_HOME/lucent or ~/.cache/lucent)\n"
    "  --no-cache          do not read or write that cache\n"
    "  --settings          list every render setting (key, default, range, meaning) and exit;\n"
    "                      --settings=markdown as Markdown tables (docs/scenes.md)\n"
    "  -h, --help          show this help\n"
    "\n"
    "examples:\n"
    "  lucent render data/scenes/dragon-marble.json --out out/dragon.png --exr out/dragon.exr\n"
    "  lucent render data/scenes/bunny-skin.json --method cdrf --set render.width=1024 --out b.png\n";

typedef struct options {
    const char *scene, *out, *exr, *mask, *json, *cache;
    const char *sets[MAX_SETS + 1];
    int set_count, frames;
    bool window, no_cache;
    char method_set[160];
    lucent_gl_desc gl;
} options;

/* The settings table as text (or Markdown): what --set render.KEY=VALUE takes. */
static int list_settings(bool markdown)
{
    char *text = NULL;
    if (lucent_settings_help(markdown, &text) != LUCENT_OK) return cli_fail();
    fputs(text, stdout);
    free(text);
    return CLI_OK;
}

static int add_set(options *o, const char *kv)
{
    if (o->set_count == MAX_SETS) return cli_usage_error("render", "at most %d --set options", MAX_SETS);
    o->sets[o->set_count++] = kv;
    return CLI_OK;
}

static int parse_value(options *o, const char *name, const char *v)
{
    if (!v) return cli_usage_error("render", "%s needs a value", name);
    if (!strcmp(name, "--method")) {
        snprintf(o->method_set, sizeof o->method_set, "render.method=%s", v);
        return add_set(o, o->method_set);
    }
    if (!strcmp(name, "--set")) return add_set(o, v);
    if (!strcmp(name, "--frames"))
        return cli_parse_int(v, &o->frames) && o->frames >= 1 && o->frames <= MAX_FRAMES
                   ? CLI_OK
                   : cli_usage_error("render", "--frames needs a whole number from 1 to %d", MAX_FRAMES);
    if (!strcmp(name, "--gl-platform"))
        return lucent_gl_platform_parse(v, &o->gl.platform) == LUCENT_OK
                   ? CLI_OK
                   : cli_usage_error("render", "--gl-platform must be auto, surfaceless, device or window");
    if (!strcmp(name, "--gl-device"))
        return cli_parse_int(v, &o->gl.device) && o->gl.device >= 1
                   ? CLI_OK
                   : cli_usage_error("render", "--gl-device needs a device number from 1");
    const char **slot = !strcmp(name, "--out")    ? &o->out
                        : !strcmp(name, "--exr")  ? &o->exr
                        : !strcmp(name, "--mask") ? &o->mask
                        : !strcmp(name, "--json") ? &o->json
                                                  : &o->cache;
    *slot = v;
    return CLI_OK;
}

static const char *const k_valued[] = {"--method", "--set",         "--out",       "--exr",   "--mask", "--json",
                                       "--frames", "--gl-platform", "--gl-device", "--cache", NULL};

static int parse_args(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *v = NULL, *a = argv[i];
        int rc = -1;
        for (int k = 0; k_valued[k] && rc < 0; k++)
            if (cli_option(argc, argv, &i, k_valued[k], &v)) rc = parse_value(o, k_valued[k], v);
        if (rc > 0) return rc;
        if (rc == CLI_OK) continue;
        if (!strcmp(a, "--window"))
            o->window = true;
        else if (!strcmp(a, "--no-cache"))
            o->no_cache = true;
        else if (a[0] == '-' && a[1])
            return cli_usage_error("render", "unknown option '%s'", a);
        else if (!o->scene)
            o->scene = a;
        else
            return cli_usage_error("render", "unexpected argument '%s'", a);
    }
    if (!o->scene) return cli_usage_error("render", "expected a scene file");
    if (!o->out && !o->window) return cli_usage_error("render", "--out is required (or --window)");
    if (o->window && o->gl.platform == LUCENT_GL_AUTO) o->gl.platform = LUCENT_GL_WINDOW;
    return CLI_OK;
}

/* ---- outputs ---- */

static int check_image_path(const char *opt, const char *path, bool png_ok)
{
    lucent_image_format f;
    if (!path) return CLI_OK;
    if (lucent_image_format_from_path(path, &f) != LUCENT_OK || (!png_ok && f == LUCENT_IMAGE_FORMAT_PNG))
        return cli_usage_error("render", "%s '%s': use %s", opt, path, png_ok ? ".png, .exr or .pfm" : ".exr or .pfm");
    return CLI_OK;
}

/* Creates an output's folder, and fails (before any rendering) when it is not writable. */
static lucent_status check_dir(const char *path)
{
    if (!path) return LUCENT_OK;
    char copy[4096];
    snprintf(copy, sizeof copy, "%s", path);
    const char *dir = dirname(copy);
    if (access(dir, F_OK) != 0) {
        lucent_status s = lucent_mkdir_p(dir);
        if (s != LUCENT_OK) return lucent_error_context(s, "%s", path);
    }
    if (access(dir, W_OK) != 0)
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write into %s: %s", path, dir, strerror(errno));
    return LUCENT_OK;
}

static void sidecar_path(const options *o, char *dest, size_t size)
{
    if (o->json) {
        snprintf(dest, size, "%s", o->json);
        return;
    }
    snprintf(dest, size, "%s", o->out ? o->out : "render");
    char *dot = strrchr(dest, '.'), *slash = strrchr(dest, '/');
    if (dot && (!slash || dot > slash)) *dot = '\0';
    snprintf(dest + strlen(dest), size - strlen(dest), ".json");
}

static lucent_status write_image(const char *path, const lucent_image *img, const lucent_render_settings *s)
{
    lucent_image_format f;
    lucent_status st = lucent_image_format_from_path(path, &f);
    if (st != LUCENT_OK || f != LUCENT_IMAGE_FORMAT_PNG)
        return st == LUCENT_OK ? lucent_image_write(path, img, NULL) : st;
    lucent_image *tm = NULL;
    st = lucent_image_clone(img, &tm);
    if (st == LUCENT_OK) {
        lucent_image_tonemap(tm, &(lucent_tonemap_desc){.op = s->view.tonemap, .exposure = (float)s->view.exposure});
        st = lucent_image_write(path, tm, NULL);
    }
    lucent_image_destroy(tm);
    return st;
}

static lucent_status write_outputs(const options *o, lucent_renderer *r, const lucent_render_settings *s,
                                   const lucent_render_result *res)
{
    char json_path[4096];
    sidecar_path(o, json_path, sizeof json_path);
    lucent_status st = LUCENT_OK;
    if (o->out) st = write_image(o->out, res->image, s);
    if (st == LUCENT_OK && o->exr) st = lucent_image_write(o->exr, res->image, NULL);
    if (st == LUCENT_OK && o->mask) st = lucent_image_write(o->mask, res->mask, NULL);
    char *text = NULL;
    if (st == LUCENT_OK && o->out) st = lucent_render_sidecar(r, s, res, &text);
    if (text) st = lucent_write_file(json_path, text, strlen(text));
    free(text);
    const char *written[4] = {o->out, o->exr, o->mask, o->out ? json_path : NULL};
    for (int i = 0; st == LUCENT_OK && i < 4; i++)
        if (written[i]) cli_wrote("wrote %s", written[i]);
    return st;
}

/* ---- rendering ---- */

static void add_times(lucent_frame_times *sum, const lucent_frame_times *t, double k)
{
    sum->pass_count = t->pass_count;
    for (int i = 0; i < t->pass_count; i++) {
        memcpy(sum->pass_name[i], t->pass_name[i], sizeof sum->pass_name[i]);
        sum->pass_ms[i] += k * t->pass_ms[i];
    }
    sum->gpu_ms += k * t->gpu_ms, sum->cpu_ms += k * t->cpu_ms, sum->blur_ms += k * t->blur_ms;
}

/* frames > 1: the first frame prepares and compiles; the mean of frames 2..N is reported. */
static lucent_status render(const options *o, lucent_renderer *r, const lucent_render_settings *s,
                            lucent_render_result *res)
{
    lucent_frame_times t, mean = {0};
    double setup = 0, k = 1.0 / (o->frames > 1 ? o->frames - 1 : 1);
    lucent_status st = LUCENT_OK;
    for (int f = 1; f < o->frames && st == LUCENT_OK; f++) {
        st = lucent_render_frame(r, s, &t);
        if (f == 1)
            setup = t.setup_ms;
        else
            add_times(&mean, &t, k);
    }
    if (st == LUCENT_OK) st = lucent_render(r, s, res);
    if (st == LUCENT_OK && o->frames > 1) {
        add_times(&mean, &res->times, k);
        mean.setup_ms = setup;
        res->times = mean;
    }
    return st;
}

static lucent_status show_window(lucent_gl_context *ctx, lucent_renderer *r, const lucent_scene *scene)
{
    const lucent_render_settings *s = &scene->render;
    lucent_frame_times t;
    lucent_status st = LUCENT_OK;
    for (int n = 0; st == LUCENT_OK && lucent_gl_window_poll(ctx); n++) {
        st = lucent_render_frame(r, s, &t);
        if (st == LUCENT_OK) st = lucent_render_present(r);
        char title[160];
        snprintf(title, sizeof title, "Lucent: %s, %s: %.2f ms GPU (blur %.2f ms)", scene->name,
                 lucent_render_method_name(s->view.method), t.gpu_ms, t.blur_ms);
        if (n % 10 == 0) lucent_gl_window_set_title(ctx, title);
    }
    return st;
}

static void summary(const lucent_gl_context *ctx, const lucent_render_settings *s, const lucent_render_result *res)
{
    lucent_gl_info info;
    lucent_gl_get_info(ctx, &info);
    char passes[512] = "";
    for (int i = 0; i < res->times.pass_count; i++)
        snprintf(passes + strlen(passes), sizeof passes - strlen(passes), "%s%s %.3f", i ? ", " : "",
                 res->times.pass_name[i], res->times.pass_ms[i]);
    cli_info("render: %s %dx%d on %s (%s): GPU %.3f ms (%s), frame %.3f ms, setup %.0f ms",
             lucent_render_method_name(s->view.method), s->view.width, s->view.height, info.renderer, info.platform,
             res->times.gpu_ms, passes, res->times.cpu_ms, res->times.setup_ms);
}

static lucent_status run(const options *o, lucent_scene *scene)
{
    lucent_gl_context *ctx = NULL;
    lucent_renderer *r = NULL;
    lucent_render_result res = {0};
    char cache[4096];
    lucent_renderer_desc rd = lucent_renderer_defaults();
    rd.pool = cli_pool();
    rd.cache_dir = cli_cache_dir(o->cache, o->no_cache, cache, sizeof cache);
    lucent_gl_desc gd = o->gl;
    gd.width = scene->render.view.width, gd.height = scene->render.view.height, gd.title = "Lucent";
    lucent_status st = lucent_gl_create(&gd, &ctx);
    if (st == LUCENT_OK) st = lucent_renderer_create(ctx, scene, &rd, &r);
    if (st == LUCENT_OK && o->window) st = show_window(ctx, r, scene);
    if (st == LUCENT_OK && o->out) st = render(o, r, &scene->render, &res);
    if (st == LUCENT_OK && o->out) summary(ctx, &scene->render, &res);
    if (st == LUCENT_OK && o->out) st = write_outputs(o, r, &scene->render, &res);
    lucent_render_result_free(&res);
    lucent_renderer_destroy(r);
    lucent_gl_destroy(ctx);
    return st;
}

int cmd_render(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--settings") || !strcmp(argv[i], "--settings=markdown"))
            return list_settings(argv[i][10]);
    options o = {.frames = 1};
    int rc = parse_args(argc, argv, &o);
    if (rc == CLI_OK) rc = check_image_path("--out", o.out, true);
    if (rc == CLI_OK) rc = check_image_path("--exr", o.exr, false);
    if (rc == CLI_OK) rc = check_image_path("--mask", o.mask, true);
    if (rc != CLI_OK) return rc;
    char json_path[4096];
    sidecar_path(&o, json_path, sizeof json_path);
    const char *outs[4] = {o.out, o.exr, o.mask, o.out ? json_path : NULL};
    static const char *const flags[4] = {"--out", "--exr", "--mask", "--json"};
    const char *ins[1] = {o.scene};
    if ((rc = cli_check_outputs("render", ins, 1, outs, flags, 4)) != CLI_OK) return rc;
    for (int i = 0; i < 4; i++)
        if (check_dir(outs[i]) != LUCENT_OK) return cli_fail();
    lucent_scene *scene = NULL;
    lucent_scene_load_desc ld = {.overrides = o.sets, .override_count = o.set_count};
    if (lucent_scene_load(o.scene, &ld, &scene) != LUCENT_OK) return cli_fail();
    lucent_status st = run(&o, scene);
    lucent_scene_destroy(scene);
    return st == LUCENT_OK ? CLI_OK : cli_fail();
}
