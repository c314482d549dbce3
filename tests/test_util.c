#include "test_util.h"

int pg_test_passed, pg_test_failed;

int pg_test_finish(const char *suite)
{
    printf("%s: %d passed, %d failed\n", suite, pg_test_passed, pg_test_failed);
    return pg_test_failed ? 1 : 0;
}

int pg_test_skip(const char *suite, const char *why)
{
    printf("%s: skipped: %s\n", suite, why);
    return 77;
}
