/* The library's one monotonic clock and the process CPU clock (lucent/base.h). */
#include <time.h>

#include "lucent/base.h"

static double read_clock(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double lucent_clock_seconds(void) { return read_clock(CLOCK_MONOTONIC); }

double lucent_clock_ms(void) { return 1e3 * lucent_clock_seconds(); }

double lucent_cpu_seconds(void) { return read_clock(CLOCK_PROCESS_CPUTIME_ID); }
