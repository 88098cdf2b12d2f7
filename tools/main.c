/* lucent: the command-line front end. `lucent <command> [options]`. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

cli_common g_cli;
static lucent_pool *g_pool;

static const cli_command k_commands[] = {
    {"materials", "list material presets and their derived optical quantities", cmd_materials},
    {"image", "inspect, convert and compare images (PNG, EXR, PFM)", cmd_image},
    {"mcml", "run MCML input files (.mci), write MCML output (.mco)", cmd_mcml},
    {"profile", "radial diffuse reflectance profiles: Monte Carlo and analytic models", cmd_profile},
    {"curvature", "per-vertex mesh curvature (Rusinkiewicz, Meyer, Garimella)", cmd_curvature},
    {"cdrf-lut", "the curvature-dependent reflectance look-up table (Kubo et al.)", cmd_cdrf_lut},
    {"cdrf-fit", "fit the CDRF's sigma0 to Monte Carlo spheres of a material", cmd_cdrf_fit},
    {"kernel", "separable subsurface-scattering kernels for a material, with taps and shader exports", cmd_kernel},
    {"kernel-eval", "evaluate every kernel model of a material against the exact 2-D convolution", cmd_kernel_eval},
    {"render", "render a scene with OpenGL: Lambert, CDRF, CDRF + translucency, screen-space SSS", cmd_render},
    {"trace", "path-traced reference of a scene (Embree): media, rough or smooth boundaries", cmd_trace},
    {"compare", "every real-time method of a scene against the path-traced reference: HTML report", cmd_compare},
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
    fprintf(out, "\noptions every command accepts:\n"
                 "  -q, --quiet      no progress bars or informational lines\n"
                 "  --threads N      worker threads (default: LUCENT_THREADS, else all cores)\n\n"
                 "exit status: 0 success, 1 failure (bad input, I/O), 2 bad usage.\n");
}

int cli_fail(void)
{
    fprintf(stderr, "lucent: %s\n", lucent_last_error()[0] ? lucent_last_error() : "failed");
    return CLI_FAIL;
}

int cli_usage_error(const char *command, const char *fmt, ...)
{
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
            if (!cli_parse_int(v, &g_cli.threads) || g_cli.threads < 1)
                return cli_usage_error(NULL, "--threads needs a positive whole number");
            remove_args(argc, argv, i, a[9] == '=' ? 1 : 2);
        } else {
            i++;
        }
    }
    if (!g_cli.quiet && isatty(STDERR_FILENO)) lucent_progress_set_output(stderr);
    lucent_log_set_sink(lucent_log_stderr_sink, stderr, g_cli.quiet ? LUCENT_LOG_WARN : LUCENT_LOG_INFO);
    return CLI_OK;
}

lucent_pool *cli_pool(void)
{
    if (!g_pool) g_pool = lucent_pool_create(g_cli.threads);
    return g_pool;
}

static const cli_command *find_command(const char *name)
{
    for (int i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(k_commands[i].name, name) == 0) return &k_commands[i];
    return NULL;
}

int main(int argc, char **argv)
{
    /* The common options may stand anywhere: `lucent -q profile ...`, `lucent profile ... -q`. */
    if (cli_common_options(&argc, argv) != CLI_OK) return CLI_USAGE;
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        if (argc >= 3 && find_command(argv[2])) {
            char *sub[] = {argv[2], "--help", NULL};
            return find_command(argv[2])->run(2, sub);
        }
        print_help(argc < 2 ? stderr : stdout);
        return argc < 2 ? CLI_USAGE : CLI_OK;
    }
    if (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "version") == 0) {
        printf("lucent %s\n", LUCENT_VERSION_STRING);
        return CLI_OK;
    }
    const cli_command *cmd = find_command(argv[1]);
    if (!cmd) {
        fprintf(stderr, "lucent: unknown command '%s'\nTry 'lucent --help'.\n", argv[1]);
        return CLI_USAGE;
    }
    int rc = cmd->run(argc - 1, argv + 1);
    lucent_pool_destroy(g_pool);
    return rc;
}
