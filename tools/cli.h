/* The `lucent` command: shared declarations for main.c and the cmd_*.c files.
 *
 * Conventions every subcommand keeps:
 *   - `lucent <command> --help` prints usage to stdout and exits 0;
 *   - bad usage prints "lucent <command>: <what>" and a hint to stderr, exit 2;
 *   - a failure (bad input, I/O) prints "lucent: <message>" (the message names the file and
 *     the field) and exits 1; outputs are written atomically, so nothing partial is left;
 *   - success exits 0; what was written is said on stdout ("wrote out/x.png").  */
#ifndef LUCENT_TOOLS_CLI_H
#define LUCENT_TOOLS_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "lucent/lucent.h"

enum { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2 };

typedef struct cli_command {
    const char *name;
    const char *summary;               /* one line for `lucent --help` */
    int (*run)(int argc, char **argv); /* argv[0] is the command name */
} cli_command;

/* Options every command accepts, parsed and removed from argv by cli_common_options. */
typedef struct cli_common {
    bool quiet;         /* --quiet / -q: no progress bars, no info lines */
    int threads;        /* --threads N (0: LUCENT_THREADS or all cores) */
    int part_k, part_n; /* --part K/N (0/0: none): this job's share of the Monte Carlo (lucent/dist.h) */
    bool merging;       /* the command runs on merged part files (lucent merge): nothing is simulated here,
                           so it has no rate to print */
} cli_common;

extern cli_common g_cli;

/* Strips --quiet/-q, --threads N / --threads=N and --part K/N from argv[1..], wherever they stand (updating
 * *argc), into g_cli, and configures logging and progress output. Returns CLI_OK, or CLI_USAGE
 * after a message. main.c calls it once, before choosing the command. */
int cli_common_options(int *argc, char **argv);

/* Prints "lucent: <lucent_last_error()>" to stderr and returns CLI_FAIL. */
int cli_fail(void);

/* Prints "lucent <command>: <message>\nTry 'lucent <command> --help'." to stderr (command NULL:
 * "lucent: ..."); returns CLI_USAGE. */
int cli_usage_error(const char *command, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* Refuses (a usage error, exit 2) outputs that name an input or the same file twice (several may name one
 * device or FIFO): flags[i] names outputs[i] in the message ("--json"); NULL entries are skipped. Then checks
 * that each can be written (lucent_output_check: its folder, what it names; exit 1 naming it), so that no
 * work is lost to an unwritable output. Call it before the work starts. */
int cli_check_outputs(const char *command, const char *const *inputs, int input_count, const char *const *outputs,
                      const char *const *flags, int output_count);

/* The same check for the folder a command writes into (compare, pack, kernel-eval): CLI_OK or CLI_FAIL. */
int cli_check_folder(const char *dir);

/* The file a material spec reads (FILE.json, a path, or FILE#NAME without #NAME) into dest, for
 * cli_check_outputs; NULL for a preset name. */
const char *cli_spec_file(const char *spec, char *dest, size_t size);

/* Prints an informational line to stdout unless --quiet. */
void cli_info(const char *fmt, ...) LUCENT_PRINTF(1, 2);

/* An informational line about an output ("wrote out/x.png"): while the command's output set is open
 * it is held and printed once the set has landed (after the renames), dropped when it does not;
 * outside a set (view) printed at once. */
void cli_wrote(const char *fmt, ...) LUCENT_PRINTF(1, 2);

/* Parses a whole non-negative integer / a finite double; false on garbage. */
bool cli_parse_int(const char *text, int *dest);
bool cli_parse_double(const char *text, double *dest);

/* True when argv[1..argc-1] holds --help or -h. */
bool cli_wants_help(int argc, char **argv);

/* Matches argv[*i] against an option that takes a value, given as `NAME VALUE` or `NAME=VALUE`.
 * On a match sets *value (NULL when the value is missing or empty), moves *i past a separate
 * value, and returns true; otherwise returns false and changes nothing. */
bool cli_option(int argc, char **argv, int *i, const char *name, const char **value);

/* The screen an engine draws a kernel on (lucent pack, lucent kernel): --screen WxH (default
 * 1920x1080), --fov DEG (vertical, default 45), --object-height H (default 1.8m: the object fills the
 * screen's height) or --distance D (its depth); lengths take m, cm or mm (bare: m). */
typedef struct cli_view {
    int width, height;
    double fov;              /* degrees */
    double object_height_mm; /* > 0 */
    double distance_mm;      /* 0: from object_height_mm */
    bool given;              /* one of the options was given */
    int depth_option;        /* which of --object-height (2) or --distance (3) was given; 0: neither */
} cli_view;

cli_view cli_view_defaults(void);

/* Matches argv[*i] against the options above. Returns CLI_OK (taken, *i moved past its value),
 * CLI_USAGE (after a message naming command), or -1: not one of them. */
int cli_view_option(const char *command, int argc, char **argv, int *i, cli_view *v);

/* The depth (mm) the width is measured at: distance_mm, else where an object of object_height_mm
 * fills the screen's height, object_height / (2 tan(fov / 2)). */
double cli_view_depth_mm(const cli_view *v);

/* Prints "kernel width: W px (2 x R mm at depth Z mm; WxH, fov_y F deg)" for a kernel of half-width
 * radius_mm: W = 2 R lucent_screen_pixels_per_mm(H, F, Z), the renderer's scale (ssss.c); nothing under --quiet. */
void cli_print_kernel_width(FILE *out, double radius_mm, const cli_view *v);

/* "1.8m", "180cm", "1800mm" (the unit is required: "1.8" is refused): a length in mm, from CLI_LENGTH_MIN_MM (1 um) to CLI_LENGTH_MAX_MM
 * (beyond them the kernel's width in pixels has hundreds of digits, or none). */
#define CLI_LENGTH_MIN_MM 1e-3
#define CLI_LENGTH_MAX_MM 1e12
bool cli_parse_length_mm(const char *text, double *mm);

/* The prefix of a command that writes PREFIX.json, .csv, .svg (profile, cdrf-fit): --out as given;
 * or, when --out ends in '/', that folder and the default name inside it; or the default name here
 * (out NULL). */
void cli_out_prefix(const char *out, const char *default_name, char *dest, size_t size);

/* "WxH", each 1..65536. */
bool cli_parse_size(const char *text, int *w, int *h);

/* The disk cache folder of the bakes: none with --no-cache, else --cache DIR, $LUCENT_CACHE_DIR,
 * $XDG_CACHE_HOME/lucent or ~/.cache/lucent (written into buf); NULL when none can be named. */
const char *cli_cache_dir(const char *option, bool none, char *buf, size_t size);

/* The pool shared by the command's work, sized by --threads (created on first use). */
lucent_pool *cli_pool(void);

/* Reads --layers "MATERIAL:THICKNESS_MM,..." (the last may be "inf") into dest (at most max layers). */
lucent_status cli_parse_layers(const char *list, lucent_layer *dest, int max, int *count);

/* The subcommands (one cmd_<name>.c each). */
int cmd_materials(int argc, char **argv);
int cmd_image(int argc, char **argv);
int cmd_profile(int argc, char **argv);
int cmd_mcml(int argc, char **argv);
int cmd_curvature(int argc, char **argv);
int cmd_mesh_uv(int argc, char **argv);
int cmd_cdrf_lut(int argc, char **argv);
int cmd_cdrf_fit(int argc, char **argv);
int cmd_kernel(int argc, char **argv);
int cmd_kernel_eval(int argc, char **argv);
int cmd_pack(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_fit(int argc, char **argv);

#endif
