/* A dependency-free test runner: one registration table per test program, driven by CTest.
 * Each program prints "N passed, N failed" as its closing line and exits non-zero on failure. */
#ifndef LUCENT_TEST_H
#define LUCENT_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct test_case {
    const char *name;
    void (*fn)(void);
} test_case;

extern int test_failures_; /* failures within the running test */

#define TEST(name) static void name(void)
#define TEST_ENTRY(name)                                                                                               \
    {                                                                                                                  \
#name, name                                                                                                    \
    }

#define TEST_FAIL_(...)                                                                                                \
    do {                                                                                                               \
        fprintf(stderr, "  %s:%d: ", __FILE__, __LINE__);                                                              \
        fprintf(stderr, __VA_ARGS__);                                                                                  \
        fputc('\n', stderr);                                                                                           \
        test_failures_++;                                                                                              \
    } while (0)

#define CHECK(cond)                                                                                                    \
    do {                                                                                                               \
        if (!(cond)) TEST_FAIL_("CHECK(%s) failed", #cond);                                                            \
    } while (0)

#define CHECK_MSG(cond, ...)                                                                                           \
    do {                                                                                                               \
        if (!(cond)) TEST_FAIL_(__VA_ARGS__);                                                                          \
    } while (0)

/* |a - b| <= tol, with both values printed on failure. */
#define CHECK_NEAR(a, b, tol)                                                                                          \
    do {                                                                                                               \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                                                 \
        if (!(fabs(a_ - b_) <= t_))                                                                                    \
            TEST_FAIL_("CHECK_NEAR(%s, %s, %s): %.9g vs %.9g (diff %.3g)", #a, #b, #tol, a_, b_, fabs(a_ - b_));       \
    } while (0)

/* expr returns LUCENT_OK; otherwise prints the error message. */
#define CHECK_OK(expr)                                                                                                 \
    do {                                                                                                               \
        lucent_status s_ = (expr);                                                                                     \
        if (s_ != LUCENT_OK) TEST_FAIL_("%s returned %s: %s", #expr, lucent_status_string(s_), lucent_last_error());   \
    } while (0)

/* expr fails with status st and the error message contains every given substring. */
#define CHECK_ERR(expr, st, ...)                                                                                       \
    do {                                                                                                               \
        lucent_status s_ = (expr);                                                                                     \
        const char *subs_[] = {__VA_ARGS__, NULL};                                                                     \
        if (s_ != (st))                                                                                                \
            TEST_FAIL_("%s returned %s, expected %s (message: %s)", #expr, lucent_status_string(s_),                   \
                       lucent_status_string(st), lucent_last_error());                                                 \
        for (int i_ = 0; subs_[i_]; i_++)                                                                              \
            if (!strstr(lucent_last_error(), subs_[i_]))                                                               \
                TEST_FAIL_("%s: message \"%s\" lacks \"%s\"", #expr, lucent_last_error(), subs_[i_]);                  \
    } while (0)

/* Runs every case (or those whose name contains argv[1]); returns the exit status. */
int test_run(const test_case *cases, int count, int argc, char **argv);

/* A fresh empty directory for one test program's files (under the build tree). */
const char *test_tmpdir(void);

/* Joins test_tmpdir() and name into a static buffer that lives until the next call
 * (two buffers rotate, so two paths can be held at once). */
const char *test_path(const char *name);

#define TEST_MAIN(...)                                                                                                 \
    int main(int argc, char **argv)                                                                                    \
    {                                                                                                                  \
        static const test_case cases_[] = {__VA_ARGS__};                                                               \
        return test_run(cases_, (int)(sizeof cases_ / sizeof cases_[0]), argc, argv);                                  \
    }

#endif
