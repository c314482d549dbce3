#include "test_util.h"

#include <dirent.h>
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
    /* newer layers (1.4.309) check shader accesses through descriptors only with this on */
    setenv("VK_KHRONOS_VALIDATION_SYNCVAL_SHADER_ACCESSES_HEURISTIC", "true", 0);
    const char *old = getenv("VK_LAYER_ENABLES");
    if (old && strstr(old, q)) return;
    char val[512];
    snprintf(val, sizeof val, "%s%s%s", old && old[0] ? old : "", old && old[0] ? ":" : "", q);
    setenv("VK_LAYER_ENABLES", val, 1);
}

static int name_cmp(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int pg_test_list_files(const char *dir, const char *suffix, char **names, int max)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    const size_t sl = strlen(suffix);
    int n = 0;
    for (struct dirent *e; n < max && (e = readdir(d));) {
        const size_t len = strlen(e->d_name);
        if (len > sl && !strcmp(e->d_name + len - sl, suffix)) names[n++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], name_cmp);
    return n;
}

void pg_test_free_names(char **names, int n)
{
    for (int i = 0; i < n; i++) free(names[i]);
}
