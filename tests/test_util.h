/* test_util.h: minimal assertion helpers for the test executables: each failed expectation is
 * printed with its location, and the test ends with "N passed, N failed". */
#ifndef RESTIR_TEST_UTIL_H
#define RESTIR_TEST_UTIL_H

#include <math.h>
#include <stdio.h>

static int test_passed_count;
static int test_failed_count;

#define EXPECT(cond, ...)                                                                       \
    do {                                                                                        \
        if (cond) {                                                                             \
            test_passed_count++;                                                                \
        } else {                                                                                \
            test_failed_count++;                                                                \
            printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                              \
            printf(__VA_ARGS__);                                                                \
            printf("\n");                                                                       \
        }                                                                                       \
    } while (0)

#define EXPECT_NEAR(a, b, tol, what)                                                            \
    EXPECT(fabs((double)(a) - (double)(b)) <= (double)(tol), "%s: %.9g vs %.9g (tol %.3g)",     \
           what, (double)(a), (double)(b), (double)(tol))

/* Exit code ctest reports as "Skipped" (SKIP_RETURN_CODE in CMakeLists.txt). */
#define TEST_SKIP_CODE 77

/* Says why the test cannot run here and returns the skip code; a test that checked something
 * before finding it cannot go on fails instead if anything failed. */
static inline int test_skip(const char *why)
{
    printf("SKIPPED: %s\n", why);
    return test_failed_count == 0 ? TEST_SKIP_CODE : 1;
}

/* Prints the summary line CI reads and returns the process exit code. */
static inline int test_finish(void)
{
    printf("%d passed, %d failed\n", test_passed_count, test_failed_count);
    return test_failed_count == 0 ? 0 : 1;
}

#endif
