/* cli_check_outputs (cli.h): a command's outputs must be distinct files, none of them an input, each one
 * writable (lucent_output_check) before the work starts. */
#include <libgen.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli.h"

/* The file a path names: the same inode when both exist, else the same canonical path (the folder
 * resolved by realpath, then the name). */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char ca[PATH_MAX + 256], cb[PATH_MAX + 256];
    const char *paths[2] = {a, b};
    char *dest[2] = {ca, cb};
    for (int i = 0; i < 2; i++) {
        char d[PATH_MAX], n[PATH_MAX], real[PATH_MAX];
        snprintf(d, sizeof d, "%s", paths[i]);
        snprintf(n, sizeof n, "%s", paths[i]);
        const char *dir = dirname(d), *base = basename(n);
        if (!realpath(dir, real)) snprintf(real, sizeof real, "%s", dir);
        snprintf(dest[i], PATH_MAX + 256, "%s/%s", real, base);
    }
    return strcmp(ca, cb) == 0;
}

/* A device, FIFO or socket (what outputs write through): several outputs may name one (/dev/null). */
static bool written_through(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode));
}

int cli_check_outputs(const char *command, const char *const *inputs, int input_count, const char *const *outputs,
                      const char *const *flags, int output_count)
{
    for (int i = 0; i < output_count; i++) {
        if (!outputs[i]) continue;
        for (int j = 0; j < input_count; j++)
            if (inputs[j] && same_file(outputs[i], inputs[j]))
                return cli_usage_error(command, "%s '%s' names the input '%s': it would be overwritten", flags[i],
                                       outputs[i], inputs[j]);
        for (int j = 0; j < i; j++)
            if (outputs[j] && same_file(outputs[i], outputs[j]) && !written_through(outputs[i]))
                return cli_usage_error(command, "%s '%s' and %s '%s' name the same file", flags[j], outputs[j],
                                       flags[i], outputs[i]);
    }
    for (int i = 0; i < output_count; i++)
        if (outputs[i] && lucent_output_check(outputs[i]) != LUCENT_OK) return cli_fail();
    return CLI_OK;
}

int cli_check_folder(const char *dir) { return lucent_output_check_folder(dir) == LUCENT_OK ? CLI_OK : cli_fail(); }

const char *cli_spec_file(const char *spec, char *dest, size_t size)
{
    size_t len = spec ? strlen(spec) : 0;
    if (!spec || !(strchr(spec, '/') || strchr(spec, '#') || (len > 5 && strcasecmp(spec + len - 5, ".json") == 0)))
        return NULL;
    snprintf(dest, size, "%.*s", (int)strcspn(spec, "#"), spec);
    return dest;
}
