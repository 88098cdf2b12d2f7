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

/* Refuses (a usage error, exit 2) outputs that name an input or the same file twice: flags[i] names
 * outputs[i] in the message ("--json"); NULL entries are skipped. */
int cli_check_outputs(const char *command, const char *const *inputs, int input_count, const char *const *outputs,
                      const char *const *flags, int output_count);

/* Prints an informational line to stdout unless --quiet. */
void cli_info(const char *fmt, ...) LUCENT_PRINTF(1, 2);

/* Parses a whole non-negative integer / a finite double; false on garbage. */
bool cli_parse_int(const char *text, int *dest);
bool cli_parse_double(const char *text, double *dest);

/* True when argv[1..argc-1] holds --help or -h. */
bool cli_wants_help(int argc, char **argv);

/* Matches argv[*i] against an option that takes a value, given as `NAME VALUE` or `NAME=VALUE`.
 * On a match sets *value (NULL when the value is missing or empty), moves *i past a separate
 * value, and returns true; otherwise returns false and changes nothing. */
bool cli_option(int argc, char **argv, int *i, const char *name, const char **value);

/* The pool shared by the command's work, sized by --threads (created on first use). */
lucent_pool *cli_pool(void);

/* The subcommands (one cmd_<name>.c each). */
int cmd_materials(int argc, char **argv);
int cmd_image(int argc, char **argv);
int cmd_profile(int argc, char **argv);
int cmd_mcml(int argc, char **argv);
int cmd_curvature(int argc, char **argv);
int cmd_cdrf_lut(int argc, char **argv);
int cmd_cdrf_fit(int argc, char **argv);
int cmd_kernel(int argc, char **argv);
int cmd_kernel_eval(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_view(int argc, char **argv);

#endif
