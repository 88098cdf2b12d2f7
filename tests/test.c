#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <sys/stat.h>
#include <unistd.h>

#include "lucent/base.h"

int test_failures_;

static char tmpdir_[512];

const char *test_tmpdir(void)
{
    if (!tmpdir_[0]) {
        const char *base = getenv("LUCENT_TEST_TMP");
        snprintf(tmpdir_, sizeof tmpdir_, "%s/lucent-test-XXXXXX", base ? base : "/tmp");
        if (!mkdtemp(tmpdir_)) {
            perror("mkdtemp");
            exit(2);
        }
    }
    return tmpdir_;
}

const char *test_path(const char *name)
{
    static char buf[2][1024];
    static int which;
    which ^= 1;
    snprintf(buf[which], sizeof buf[which], "%s/%s", test_tmpdir(), name);
    return buf[which];
}

int test_run(const test_case *cases, int count, int argc, char **argv)
{
    int passed = 0, failed = 0;
    /* CTest runs the Monte Carlo's tests once per SIMD path (LUCENT_ISA): a path this CPU lacks is
     * reported as skipped (exit 77), not silently replaced by another */
    const char *isa_name = getenv("LUCENT_ISA");
    lucent_isa isa;
    if (isa_name && *isa_name) {
        if (lucent_isa_parse(isa_name, &isa) != LUCENT_OK) {
            fprintf(stderr, "LUCENT_ISA: %s\n", lucent_last_error());
            return 1;
        }
        if (!lucent_isa_supported(isa)) {
            printf("skipped: this CPU has no %s path (LUCENT_ISA=%s)\n", isa_name, isa_name);
            return 77;
        }
        lucent_isa_set(isa);
    }
    for (int i = 0; i < count; i++) {
        if (argc > 1 && !strstr(cases[i].name, argv[1])) continue;
        test_failures_ = 0;
        cases[i].fn();
        if (test_failures_) {
            failed++;
            fprintf(stderr, "FAIL %s (%d checks failed)\n", cases[i].name, test_failures_);
        } else {
            passed++;
            printf("ok   %s\n", cases[i].name);
        }
    }
    printf("%d passed, %d failed\n", passed, failed);
    if (!failed && tmpdir_[0]) { /* keep a failing run's files for inspection */
        char cmd[600];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir_);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir_);
    }
    return failed ? 1 : 0;
}
