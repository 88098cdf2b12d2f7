/* `lucent view`: the interactive viewer (viewer/, docs/view.md): a window with a panel for tuning a
 * scene's method, settings and materials live, or a script of the same actions played headless. */
#include <stdlib.h>
#include <string.h>

#include "../viewer/viewer.h"
#include "cli.h"

enum { MAX_SETS = 64 };

static const char k_usage[] =
    "usage: lucent view SCENE.json [--set KEY=VALUE]... [--script FILE [--headless]] [options]\n"
    "\n"
    "Opens SCENE (docs/scenes.md) in a window with a panel (Dear ImGui): the method and a second one to\n"
    "compare (split-screen or side by side), every render setting of the table with its range and doc,\n"
    "the material (preset or sigma_a, sigma_s', g, eta per channel) with its profile, kernel and taps\n"
    "plotted, a reference EXR of `lucent trace` with the error map and relative RMS error, per-pass GPU\n"
    "times and frames per second; saves the scene with the tuned settings (also as --set options),\n"
    "screenshots (PNG + EXR) and the taps. The scene file is reloaded when it changes. Bakes (a new\n"
    "material, kernel or profile) and the frames run on threads of their own: the window keeps its\n"
    "rate however slow a method is. A script is checked whole before its first line runs. docs/view.md.\n"
    "\n"
    "mouse: drag to orbit, shift-drag (or the right button) to pan, the wheel to zoom, ctrl-drag to\n"
    "turn the light; keys: R resets the camera, 1-9 choose method A, Tab swaps A and B, Esc quits.\n"
    "\n"
    "options:\n"
    "  --set KEY=VALUE     override a scene value (repeatable), as lucent render takes it\n"
    "  --script FILE       play the actions of FILE (docs/view.md: orbit, set, method, material,\n"
    "                      load-reference, save-scene, screenshot, resize, bench, quit...) and exit\n"
    "  --headless          no window (EGL surfaceless): with --script, where there is no display\n"
    "  --size WxH          the window's size (default: the scene's image plus the panel, as tall\n"
    "                      as the panel needs)\n"
    "  --cache DIR         where sigma0 fits and slab tables are kept (default as lucent render)\n"
    "  --no-cache          do not read or write that cache\n"
    "  -h, --help          show this help\n"
    "\n"
    "examples:\n"
    "  lucent view data/scenes/bunny-skin.json\n"
    "  lucent view data/scenes/bunny-skin.json --script tune.txt --headless\n";

int cmd_view(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    viewer_options o = {.quiet = g_cli.quiet};
    const char *sets[MAX_SETS + 1], *cache = NULL;
    bool no_cache = false;
    int set_count = 0;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL, *a = argv[i];
        if (cli_option(argc, argv, &i, "--set", &v)) {
            if (!v) return cli_usage_error("view", "--set needs KEY=VALUE");
            if (set_count == MAX_SETS) return cli_usage_error("view", "at most %d --set options", MAX_SETS);
            sets[set_count++] = v;
        } else if (cli_option(argc, argv, &i, "--script", &v)) {
            if (!v) return cli_usage_error("view", "--script needs a file");
            o.script = v;
        } else if (cli_option(argc, argv, &i, "--cache", &v)) {
            if (!v) return cli_usage_error("view", "--cache needs a folder");
            cache = v;
        } else if (cli_option(argc, argv, &i, "--size", &v)) {
            if (!v || sscanf(v, "%dx%d", &o.width, &o.height) != 2 || o.width < 1 || o.height < 1 || o.width > 16384 ||
                o.height > 16384)
                return cli_usage_error("view", "--size needs WIDTHxHEIGHT (1 to 16384 each)");
        } else if (!strcmp(a, "--headless")) {
            o.headless = true;
        } else if (!strcmp(a, "--no-cache")) {
            no_cache = true;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage_error("view", "unknown option '%s'", a);
        } else if (!o.scene) {
            o.scene = a;
        } else {
            return cli_usage_error("view", "unexpected argument '%s'", a);
        }
    }
    if (!o.scene) return cli_usage_error("view", "expected a scene file");
    if (o.headless && !o.script) return cli_usage_error("view", "--headless needs --script (there is nothing to see)");
    char buf[4096];
    o.sets = sets, o.set_count = set_count;
    o.cache_dir = cli_cache_dir(cache, no_cache, buf, sizeof buf);
    o.pool = cli_pool();
    return viewer_run(&o) == LUCENT_OK ? CLI_OK : cli_fail();
}
