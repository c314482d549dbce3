/* data_dir.c - where passgraph's data (shaders/, pipelines/, assets/) lives (pg_common.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* dladdr */
#endif
#include "pg_common.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char g_data_dir[PG_PATH_MAX];
static pthread_once_t g_data_once = PTHREAD_ONCE_INIT;

static bool dir_has_shaders(const char *dir)
{
    char p[PG_PATH_MAX + 32];
    snprintf(p, sizeof p, "%s/shaders/common.glsl", dir);
    return access(p, R_OK) == 0;
}

static void find_data_dir(void)
{
    const char *env = getenv("PASSGRAPH_DATA_DIR");
    if (env && env[0]) {
        pg_strlcpy(g_data_dir, env, sizeof g_data_dir);
        return;
    }
    char exe[PG_PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            char cand[PG_PATH_MAX + 32];
            snprintf(cand, sizeof cand, "%s/../share/passgraph", exe);
            if (dir_has_shaders(cand)) {
                pg_strlcpy(g_data_dir, cand, sizeof g_data_dir);
                return;
            }
            snprintf(cand, sizeof cand, "%s", exe);
            if (dir_has_shaders(cand)) {
                pg_strlcpy(g_data_dir, cand, sizeof g_data_dir);
                return;
            }
        }
    }
    /* passgraph as a shared library (libpassgraph.so, docs/embedding.md): <prefix>/share/passgraph
     * next to the library's <prefix>/lib[/multiarch] */
    Dl_info info;
    if (dladdr((void *)&find_data_dir, &info) && info.dli_fname && info.dli_fname[0] == '/') {
        char lib[PG_PATH_MAX];
        pg_strlcpy(lib, info.dli_fname, sizeof lib);
        for (int up = 0; up < 3; up++) {
            char *slash = strrchr(lib, '/');
            if (!slash) break;
            *slash = 0;
            char cand[PG_PATH_MAX + 32];
            snprintf(cand, sizeof cand, "%s/share/passgraph", lib);
            if (up > 0 && dir_has_shaders(cand)) {
                pg_strlcpy(g_data_dir, cand, sizeof g_data_dir);
                return;
            }
        }
    }
    pg_strlcpy(g_data_dir, PG_SOURCE_DIR, sizeof g_data_dir);
}

const char *pg_data_dir(void)
{
    pthread_once(&g_data_once, find_data_dir);
    return g_data_dir;
}

void pg_data_path(char *buf, size_t size, const char *rel)
{
    snprintf(buf, size, "%s/%s", pg_data_dir(), rel);
}

