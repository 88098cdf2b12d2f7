/* Where a compare run was made: the machine and the date, for the reports' provenance. */
#include <stdio.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "eval/internal.h"

/* The processor's model name from /proc/cpuinfo ("" when it has none). */
static void cpu_model(char *dest, size_t size)
{
    dest[0] = '\0';
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) != 0) continue;
        const char *v = strchr(line, ':');
        if (!v) continue;
        v++;
        while (*v == ' ' || *v == '\t') v++;
        snprintf(dest, size, "%.*s", (int)strcspn(v, "\n"), v);
        break;
    }
    fclose(f);
}

void eval_machine(char *dest, size_t size, int *cores)
{
    struct utsname u;
    char cpu[256];
    cpu_model(cpu, sizeof cpu);
    if (uname(&u) == 0)
        snprintf(dest, size, "%.60s %.60s %.40s%s%.200s", u.sysname, u.release, u.machine, cpu[0] ? ", " : "", cpu);
    else
        snprintf(dest, size, "%s", cpu[0] ? cpu : "unknown");
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    *cores = n > 0 ? (int)n : 0;
}

void eval_date(char *dest, size_t size)
{
    time_t t = time(NULL);
    struct tm tm;
    if (gmtime_r(&t, &tm))
        strftime(dest, size, "%Y-%m-%dT%H:%M:%SZ", &tm);
    else
        snprintf(dest, size, "unknown");
}
