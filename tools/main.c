/* lucent: the command-line front end. `lucent <command> [options]`. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "lucent/dist.h"

cli_common g_cli;
static lucent_pool *g_pool;

static const cli_command k_commands[] = {
    {"materials", "list material presets and their derived optical quantities", cmd_materials},
    {"image", "inspect, convert and compare images (PNG, EXR, PFM)", cmd_image},
    {"mcml", "run MCML input files (.mci), write MCML output (.mco)", cmd_mcml},
    {"profile", "radial diffuse reflectance profiles: Monte Carlo and analytic models", cmd_profile},
    {"curvature", "per-vertex mesh curvature (Rusinkiewicz, Meyer, Garimella)", cmd_curvature},
    {"mesh-uv", "a mesh's texture atlas (its own, or Lucent's charts), as OBJ or glTF with a picture", cmd_mesh_uv},
    {"cdrf-lut", "the curvature-dependent reflectance look-up table (Kubo et al.)", cmd_cdrf_lut},
    {"cdrf-fit", "fit the CDRF's sigma0 to Monte Carlo spheres of a material", cmd_cdrf_fit},
    {"kernel", "separable subsurface-scattering kernels for a material, with taps and shader exports", cmd_kernel},
    {"pack", "an engine pack for a material: taps, blur pass, CDRF LUT and snippet, T(s), constants, glTF", cmd_pack},
    {"fit", "fit each engine's subsurface parameters (Unreal, Unity, Blender, OpenPBR, Godot) to a material", cmd_fit},
    {"kernel-eval", "evaluate every kernel model of a material against the exact 2-D convolution", cmd_kernel_eval},
    {"render", "render a scene with OpenGL: Lambert, CDRF, CDRF + translucency, screen-space SSS", cmd_render},
    {"trace", "path-traced reference of a scene (Embree): media, rough or smooth boundaries", cmd_trace},
    {"compare", "every real-time method of a scene against the path-traced reference: HTML report", cmd_compare},
    {"merge", "combine the part files of --part K/N runs into the outputs of the whole run", NULL},
    {"view", "tune a scene live in a window: methods side by side, settings, materials, error", cmd_view},
};
enum { COMMAND_COUNT = sizeof k_commands / sizeof k_commands[0] };

static void print_help(FILE *out)
{
    fprintf(out,
            "Lucent %s: rendering translucent materials.\n\n"
            "usage: lucent <command> [options]\n"
            "       lucent <command> --help\n"
            "       lucent --version\n\n"
            "commands:\n",
            LUCENT_VERSION_STRING);
    for (int i = 0; i < COMMAND_COUNT; i++) fprintf(out, "  %-12s %s\n", k_commands[i].name, k_commands[i].summary);
    fprintf(out,
            "\noptions every command accepts:\n"
            "  -q, --quiet      no progress bars or informational lines\n"
            "  --threads N      worker threads (default: LUCENT_THREADS, else all cores)\n"
            "  --isa I          the Monte Carlo's SIMD path: auto, scalar, avx2, avx512 (default:\n"
            "                   LUCENT_ISA, else the best this CPU has; results differ between paths)\n"
            "  --part K/N       mcml, profile --model mc, cdrf-fit, trace: run part K of N of the\n"
            "                   Monte Carlo and write OUTPUT.part-K-of-N instead of the outputs\n"
            "                   (lucent merge combines them; docs/scale.md)\n\n"
            "Under mpirun (MPI build: %s), the same commands share their work between the ranks\n"
            "with results identical to one process's; only rank 0 writes.\n\n"
            "exit status: 0 success, 1 failure (bad input, I/O), 2 bad usage.\n",
            lucent_dist_mpi_built() ? "yes" : "no");
}

int cli_fail(void)
{
    if (lucent_dist_rank() == 0) /* every rank has the same (agreed) error: one says it */
        fprintf(stderr, "lucent: %s\n", lucent_last_error()[0] ? lucent_last_error() : "failed");
    return CLI_FAIL;
}

int cli_usage_error(const char *command, const char *fmt, ...)
{
    if (lucent_dist_rank() != 0) return CLI_USAGE;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, command ? "lucent %s: " : "lucent: ", command);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    if (command)
        fprintf(stderr, "\nTry 'lucent %s --help'.\n", command);
    else
        fprintf(stderr, "\nTry 'lucent --help'.\n");
    return CLI_USAGE;
}

void cli_info(const char *fmt, ...)
{
    if (g_cli.quiet) return;
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
}

/* The lines cli_wrote holds until the output set lands. */
static struct {
    bool holding;
    char **lines;
    size_t count, cap;
} g_wrote;

void cli_wrote(const char *fmt, ...)
{
    if (g_cli.quiet) return;
    va_list ap;
    va_start(ap, fmt);
    char *line = NULL;
    int n = vasprintf(&line, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if (!g_wrote.holding) {
        puts(line);
        free(line);
        return;
    }
    if (g_wrote.count == g_wrote.cap) {
        size_t cap = g_wrote.cap ? 2 * g_wrote.cap : 16;
        char **grown = realloc(g_wrote.lines, cap * sizeof *grown);
        if (!grown) {
            free(line);
            return;
        }
        g_wrote.lines = grown, g_wrote.cap = cap;
    }
    g_wrote.lines[g_wrote.count++] = line;
}

/* Prints (landed) or drops the held lines and stops holding. */
static void wrote_release(bool landed)
{
    for (size_t i = 0; i < g_wrote.count; i++) {
        if (landed) puts(g_wrote.lines[i]);
        free(g_wrote.lines[i]);
    }
    free(g_wrote.lines);
    g_wrote.lines = NULL, g_wrote.count = g_wrote.cap = 0, g_wrote.holding = false;
}

bool cli_parse_int(const char *text, int *dest)
{
    char *end;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : -1;
    if (!text || !*text || *end || errno || v < 0 || v > 1000000000L) return false;
    *dest = (int)v;
    return true;
}

bool cli_parse_double(const char *text, double *dest)
{
    char *end;
    errno = 0;
    double v = text ? strtod(text, &end) : 0;
    if (!text || !*text || *end || errno || v != v || v > 1e300 || v < -1e300) return false;
    *dest = v;
    return true;
}

bool cli_parse_length_mm(const char *text, double *mm)
{
    if (!text || !*text) return false;
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    /* a unit is required: a bare "30" read as 30 m drew a kernel 1000 times too narrow for 30 mm */
    double unit = !strcmp(end, "m") ? 1000 : !strcmp(end, "cm") ? 10 : !strcmp(end, "mm") ? 1 : 0;
    if (errno || !(unit > 0) || !(v * unit >= CLI_LENGTH_MIN_MM && v * unit <= CLI_LENGTH_MAX_MM)) return false;
    *mm = v * unit;
    return true;
}

/* One side of WxH: 1..65536, digits only (no sign, no wrap: 4294967297 was read as 1). */
static bool parse_side(const char *p, const char *end, int *dest)
{
    long v = 0;
    if (p == end || end - p > 6) return false;
    for (; p < end; p++) {
        if (*p < '0' || *p > '9') return false;
        v = 10 * v + (*p - '0');
    }
    if (v < 1 || v > 65536) return false;
    *dest = (int)v;
    return true;
}

bool cli_parse_size(const char *text, int *w, int *h)
{
    const char *x = text ? strchr(text, 'x') : NULL;
    return x && parse_side(text, x, w) && parse_side(x + 1, x + strlen(x), h);
}

void cli_out_prefix(const char *out, const char *default_name, char *dest, size_t size)
{
    size_t n = out ? strlen(out) : 0;
    if (!out)
        snprintf(dest, size, "%s", default_name);
    else if (out[n - 1] == '/')
        snprintf(dest, size, "%s%s", out, default_name);
    else
        snprintf(dest, size, "%s", out);
}

cli_view cli_view_defaults(void)
{
    return (cli_view){.width = 1920, .height = 1080, .fov = 45, .object_height_mm = 1800};
}

int cli_view_option(const char *command, int argc, char **argv, int *i, cli_view *v)
{
    static const char *const names[] = {"--screen", "--fov", "--object-height", "--distance"};
    static const char *const wants[] = {"WxH in pixels (1..65536 each)", "degrees in (0, 180)",
                                        "a length with its unit (m, cm or mm) from 0.001 mm to 1e12 mm",
                                        "a length with its unit (m, cm or mm) from 0.001 mm to 1e12 mm"};
    const char *t = NULL;
    int n = 0;
    while (n < 4 && !cli_option(argc, argv, i, names[n], &t)) n++;
    if (n == 4) return -1;
    bool ok = n == 0   ? cli_parse_size(t, &v->width, &v->height)
              : n == 1 ? cli_parse_double(t, &v->fov) && v->fov > 0 && v->fov < 180
              : n == 2 ? cli_parse_length_mm(t, &v->object_height_mm)
                       : cli_parse_length_mm(t, &v->distance_mm);
    v->given = true;
    if (ok && (n == 2 || n == 3)) {
        if (v->depth_option && v->depth_option != n)
            return cli_usage_error(command, "--object-height and --distance: give one (each sets the depth)");
        v->depth_option = n;
    }
    return ok ? CLI_OK : cli_usage_error(command, "%s needs %s, got '%s'", names[n], wants[n], t ? t : "");
}

double cli_view_depth_mm(const cli_view *v)
{
    return v->distance_mm > 0 ? v->distance_mm : lucent_screen_depth_mm(v->object_height_mm, v->fov);
}

void cli_print_kernel_width(FILE *out, double radius_mm, const cli_view *v)
{
    if (g_cli.quiet) return;
    double z = cli_view_depth_mm(v), w = 2 * radius_mm * lucent_screen_pixels_per_mm(v->height, v->fov, z);
    fprintf(out, "kernel width: %.2f px (2 x %.6g mm at depth %.6g mm; %dx%d, fov_y %.6g deg)\n", w, radius_mm, z,
            v->width, v->height, v->fov);
}

bool cli_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) return true;
    return false;
}

bool cli_option(int argc, char **argv, int *i, const char *name, const char **value)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (strncmp(a, name, n) != 0 || (a[n] != '\0' && a[n] != '=')) return false;
    if (a[n] == '=')
        *value = a + n + 1;
    else
        *value = *i + 1 < argc ? argv[++*i] : NULL;
    if (*value && !**value) *value = NULL;
    return true;
}

/* Removes argv[i .. i+n-1]. */
static void remove_args(int *argc, char **argv, int i, int n)
{
    memmove(argv + i, argv + i + n, (size_t)(*argc - i - n + 1) * sizeof *argv);
    *argc -= n;
}

int cli_common_options(int *argc, char **argv)
{
    for (int i = 1; i < *argc;) {
        const char *a = argv[i];
        if (strcmp(a, "--") == 0) break;
        if (strcmp(a, "-q") == 0 || strcmp(a, "--quiet") == 0) {
            g_cli.quiet = true;
            remove_args(argc, argv, i, 1);
        } else if (strcmp(a, "--threads") == 0 || strncmp(a, "--threads=", 10) == 0) {
            const char *v = a[9] == '=' ? a + 10 : (i + 1 < *argc ? argv[i + 1] : NULL);
            if (!cli_parse_int(v, &g_cli.threads) || g_cli.threads < 1 || g_cli.threads > LUCENT_POOL_MAX_THREADS)
                return cli_usage_error(NULL, "--threads needs a positive whole number, at most %d",
                                       LUCENT_POOL_MAX_THREADS);
            remove_args(argc, argv, i, a[9] == '=' ? 1 : 2);
        } else if (strcmp(a, "--isa") == 0 || strncmp(a, "--isa=", 6) == 0) {
            const char *v = a[5] == '=' ? a + 6 : (i + 1 < *argc ? argv[i + 1] : NULL);
            lucent_isa isa;
            if (!v || lucent_isa_parse(v, &isa) != LUCENT_OK)
                return cli_usage_error(NULL, "--isa needs auto, scalar, avx2 or avx512");
            if (lucent_isa_set(isa) != LUCENT_OK) return cli_usage_error(NULL, "--isa %s: this CPU lacks it", v);
            remove_args(argc, argv, i, a[5] == '=' ? 1 : 2);
        } else if (strcmp(a, "--part") == 0 || strncmp(a, "--part=", 7) == 0) {
            const char *v = a[6] == '=' ? a + 7 : (i + 1 < *argc ? argv[i + 1] : NULL);
            char *slash = v ? strchr(v, '/') : NULL, k[16];
            if (!slash || (size_t)(slash - v) >= sizeof k)
                return cli_usage_error(NULL, "--part needs K/N (part K of N, 1 <= K <= N)");
            memcpy(k, v, (size_t)(slash - v));
            k[slash - v] = '\0';
            if (!cli_parse_int(k, &g_cli.part_k) || !cli_parse_int(slash + 1, &g_cli.part_n) || g_cli.part_k < 1 ||
                g_cli.part_k > g_cli.part_n || g_cli.part_n > 65536)
                return cli_usage_error(NULL, "--part %s: needs K/N with 1 <= K <= N <= 65536", v);
            remove_args(argc, argv, i, a[6] == '=' ? 1 : 2);
        } else {
            i++;
        }
    }
    const char *env = getenv("LUCENT_THREADS");
    int env_threads;
    if (!g_cli.threads && env && *env &&
        (!cli_parse_int(env, &env_threads) || env_threads < 1 || env_threads > LUCENT_POOL_MAX_THREADS))
        return cli_usage_error(NULL, "LUCENT_THREADS='%.32s': needs a whole number from 1 to %d (or unset: all cores)",
                               env, LUCENT_POOL_MAX_THREADS);
    if (lucent_dist_rank() != 0) g_cli.quiet = true; /* rank 0 speaks for the job */
    if (!g_cli.quiet && isatty(STDERR_FILENO)) lucent_progress_set_output(stderr);
    lucent_files_create_parents(true); /* every command creates the folder of its outputs */
    lucent_log_set_sink(lucent_log_stderr_sink, stderr, g_cli.quiet ? LUCENT_LOG_WARN : LUCENT_LOG_INFO);
    return CLI_OK;
}

const char *cli_cache_dir(const char *option, bool none, char *buf, size_t size)
{
    const char *env = getenv("LUCENT_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (none) return NULL;
    if (option) return option;
    if (env && *env) return env;
    if (xdg && *xdg)
        snprintf(buf, size, "%s/lucent", xdg);
    else if (home && *home)
        snprintf(buf, size, "%s/.cache/lucent", home);
    else
        return NULL;
    return buf;
}

lucent_pool *cli_pool(void)
{
    if (!g_pool) g_pool = lucent_pool_create(g_cli.threads);
    return g_pool;
}

extern const char lucent_cli_revision[]; /* generated/revision.c (cmake/revision.cmake) */

/* `lucent --version`: the version, the git revision it was built from, and what it links. */
static int print_version(void)
{
    printf("lucent %s\n", LUCENT_VERSION_STRING);
    printf("revision  %s\n", lucent_cli_revision);
    printf("embree    %s\n", lucent_trace_embree_version());
    printf("openexr   %s\n", lucent_image_openexr_version());
    printf("simd      %s (this CPU:", lucent_isa_name(lucent_isa_active()));
    for (int i = LUCENT_ISA_SCALAR; i < LUCENT_ISA_COUNT; i++)
        if (lucent_isa_supported((lucent_isa)i)) printf(" %s", lucent_isa_name((lucent_isa)i));
    printf(")\n");
    lucent_log_set_sink(NULL, NULL, LUCENT_LOG_ERROR);
    lucent_gl_context *gl = NULL;
    if (lucent_gl_create(NULL, &gl) == LUCENT_OK) {
        lucent_gl_info info;
        lucent_gl_get_info(gl, &info);
        printf("gl        %s; %s (%s)\n", info.renderer, info.version, info.platform);
        lucent_gl_destroy(gl);
    } else {
        printf("gl        none: %s\n", lucent_last_error());
    }
    return CLI_OK;
}

static const cli_command *find_command(const char *name)
{
    for (int i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(k_commands[i].name, name) == 0) return &k_commands[i];
    return NULL;
}

/* The commands whose Monte Carlo work is shared by --part and mpirun. */
static bool shares_work(const char *name)
{
    const char *k[] = {"mcml", "profile", "cdrf-fit", "trace"};
    for (size_t i = 0; i < sizeof k / sizeof *k; i++)
        if (strcmp(name, k[i]) == 0) return true;
    return false;
}

/* Part mode: runs the command (its outputs go nowhere) and writes its tallies beside its first
 * output, as OUTPUT.part-K-of-N. */
static int run_part(const cli_command *cmd, int argc, char **argv)
{
    if (!shares_work(cmd->name))
        return cli_usage_error(NULL, "--part goes with mcml, profile, cdrf-fit and trace, not '%s'", cmd->name);
    if (lucent_dist_set_part(g_cli.part_k, g_cli.part_n, argc, argv) != LUCENT_OK) return cli_fail();
    fflush(stdout);
    FILE *quiet_out = freopen("/dev/null", "w", stdout); /* the results of one part are not the results */
    (void)quiet_out;
    int rc = cmd->run(argc, argv);
    if (rc != CLI_OK) return rc;
    const char *out = lucent_dist_first_output();
    if (!out)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--part: '%s' wrote no output to put the part beside",
                            cmd->name),
               cli_fail();
    size_t n = strlen(out) + 40;
    char *path = malloc(n);
    if (!path) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory"), cli_fail();
    snprintf(path, n, "%s.part-%d-of-%d", out, g_cli.part_k, g_cli.part_n);
    lucent_status s = lucent_dist_part_write(path);
    if (s == LUCENT_OK && !g_cli.quiet && lucent_dist_rank() == 0)
        fprintf(stderr, "lucent: wrote %s (part %d of %d; lucent merge combines the parts)\n", path, g_cli.part_k,
                g_cli.part_n);
    free(path);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}

static const char k_merge_usage[] =
    "usage: lucent merge PART... [-- OPTION...]\n"
    "\n"
    "Combines the part files of `lucent COMMAND ... --part K/N` runs (parts 1 to N of one command,\n"
    "each named OUTPUT.part-K-of-N) into the outputs the whole command would have written in one\n"
    "run, byte for byte: it sums the parts' tallies (exactly) and runs the command's reduction and\n"
    "writers on them, so the command's input files must still be where they were. OPTIONs after --\n"
    "are added to the command (later options win: -- --out merged.png, -- --out-dir merged/).\n"
    "See docs/scale.md.\n"
    "\n"
    "examples:\n"
    "  lucent merge out/sample.mco.part-*-of-4\n"
    "  lucent merge out/dragon.png.part-*-of-16 -- --exr out/dragon.exr\n";

static int cmd_merge(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_merge_usage, stdout);
        return CLI_OK;
    }
    int parts = 0, extra = argc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--") == 0) {
            extra = i + 1;
            break;
        }
        if (argv[i][0] == '-') return cli_usage_error("merge", "unknown option '%s'", argv[i]);
        parts++;
    }
    if (!parts) return cli_usage_error("merge", "expected part files (OUTPUT.part-K-of-N)");
    int cargc = 0;
    char **cargv = NULL;
    if (lucent_dist_merge_load((const char *const *)argv + 1, parts, &cargc, &cargv) != LUCENT_OK) return cli_fail();
    const cli_command *cmd = find_command(cargv[0]);
    if (!cmd || !cmd->run || !shares_work(cmd->name)) {
        lucent_error(LUCENT_ERR_PARSE, "%s: header: the command '%s' is not one that --part shares", argv[1], cargv[0]);
        return cli_fail();
    }
    int n = cargc + (argc - extra);
    char **all = calloc((size_t)n + 1, sizeof *all);
    if (!all) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory"), cli_fail();
    memcpy(all, cargv, (size_t)cargc * sizeof *all);
    memcpy(all + cargc, argv + extra, (size_t)(argc - extra) * sizeof *all);
    g_cli.merging = true;
    int rc = cmd->run(n, all);
    free(all);
    if (rc == CLI_OK && lucent_dist_merge_check_used() != LUCENT_OK) rc = cli_fail();
    return rc;
}

static int run_command(int argc, char **argv)
{
    /* The common options may stand anywhere: `lucent -q profile ...`, `lucent profile ... -q`. */
    if (cli_common_options(&argc, argv) != CLI_OK) return CLI_USAGE;
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        if (argc >= 3 && find_command(argv[2])) {
            char *sub[] = {argv[2], "--help", NULL};
            const cli_command *c = find_command(argv[2]);
            return c->run ? c->run(2, sub) : cmd_merge(2, sub);
        }
        print_help(argc < 2 ? stderr : stdout);
        return argc < 2 ? CLI_USAGE : CLI_OK;
    }
    if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "version") == 0) {
        return print_version();
    }
    const cli_command *cmd = find_command(argv[1]);
    if (!cmd) {
        fprintf(stderr, "lucent: unknown command '%s'\nTry 'lucent --help'.\n", argv[1]);
        return CLI_USAGE;
    }
    if (!cmd->run && g_cli.part_n) return cli_usage_error(NULL, "--part does not go with merge");
    if (strcmp(cmd->name, "view") == 0) return cmd->run(argc - 1, argv + 1); /* saves land when made */
    /* Every output of the command lands together when it succeeds, none when it fails. */
    lucent_outputs_begin();
    g_wrote.holding = true; /* "wrote X" once X has landed */
    int rc = !cmd->run      ? cmd_merge(argc - 1, argv + 1)
             : g_cli.part_n ? run_part(cmd, argc - 1, argv + 1)
                            : cmd->run(argc - 1, argv + 1);
    if (lucent_outputs_end(rc == CLI_OK) != LUCENT_OK) rc = cli_fail();
    wrote_release(rc == CLI_OK);
    return rc;
}

int main(int argc, char **argv)
{
    lucent_outputs_handle_signals(); /* an interrupted command leaves no temporary, its old outputs as they were */
    if (lucent_dist_init(&argc, &argv) != LUCENT_OK) return cli_fail();
    if (lucent_dist_rank() != 0) { /* rank 0 speaks for the job */
        FILE *quiet_out = freopen("/dev/null", "w", stdout);
        (void)quiet_out;
    }
    int rc = run_command(argc, argv);
    lucent_pool_destroy(g_pool);
    return lucent_dist_finish(rc);
}
