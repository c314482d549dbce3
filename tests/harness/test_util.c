#include "test_util.h"
#include <stdlib.h>
#include <string.h>

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

void pg_test_queue_submit_validation(void)
{
    const char *q = "VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT";
    const char *old = getenv("VK_LAYER_ENABLES");
    if (old && strstr(old, q)) return;
    char val[512];
    snprintf(val, sizeof val, "%s%s%s", old && old[0] ? old : "", old && old[0] ? ":" : "", q);
    setenv("VK_LAYER_ENABLES", val, 1);
}
