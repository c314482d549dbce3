/* test_util.h - a tiny assertion harness. Each CHECK failure is printed with file:line and
 * counted; pg_test_finish() prints "N passed, M failed" and returns the process exit code. */
#ifndef PG_TEST_UTIL_H
#define PG_TEST_UTIL_H

#include <stdio.h>

extern int pg_test_passed, pg_test_failed;

#define CHECK(cond)                                                                        \
    do {                                                                                   \
        if (cond) {                                                                        \
            pg_test_passed++;                                                              \
        } else {                                                                           \
            pg_test_failed++;                                                              \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);       \
        }                                                                                  \
    } while (0)

#define CHECK_MSG(cond, ...)                                                               \
    do {                                                                                   \
        if (cond) {                                                                        \
            pg_test_passed++;                                                              \
        } else {                                                                           \
            pg_test_failed++;                                                              \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);       \
            fprintf(stderr, __VA_ARGS__);                                                  \
            fprintf(stderr, "\n");                                                         \
        }                                                                                  \
    } while (0)

/* Prints the summary line and returns 0 if nothing failed, 1 otherwise. */
int pg_test_finish(const char *suite);
/* Returns 77 (ctest SKIP) after printing why. */
int pg_test_skip(const char *suite, const char *why);
/* Asks the validation layer (created after this call) to check synchronization across queue
 * submissions too (VK_LAYER_ENABLES += VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT;
 * off by default in layer 1.3.239): hazards between frames in flight. */
void pg_test_queue_submit_validation(void);
/* The names of the files in folder dir that end in suffix and have more before it, sorted; at
 * most max, each malloc'd (pg_test_free_names). -1 when dir does not open. */
int pg_test_list_files(const char *dir, const char *suffix, char **names, int max);
void pg_test_free_names(char **names, int n);

#endif
