/* data_dir.c - where passgraph's data (shaders/, pipelines/, assets/) lives (pg_common.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* dladdr */
#endif
#include "pg_common.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdint.h>
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

/* The absolute path of the file mapped at addr (the executable or a shared library), from
 * /proc/self/maps: dladdr gives the name the library was loaded by, which is relative when it
 * was found through a relative LD_LIBRARY_PATH entry or dlopen path. */
static bool module_path(const void *addr, char *out, size_t size)
{
    Dl_info info;
    if (dladdr(addr, &info) && info.dli_fname && info.dli_fname[0] == '/')
        return pg_strlcpy(out, info.dli_fname, size);
    FILE *f = fopen("/proc/self/maps", "r");
    if (!f) return false;
    char line[PG_PATH_MAX + 128];
    bool found = false;
    while (!found && fgets(line, sizeof line, f)) {
        unsigned long lo, hi;
        int at = 0;
        if (sscanf(line, "%lx-%lx %*s %*s %*s %*s %n", &lo, &hi, &at) < 2 || !at) continue;
        if ((uintptr_t)addr < lo || (uintptr_t)addr >= hi || line[at] != '/') continue;
        line[strcspn(line, "\n")] = 0;
        found = pg_strlcpy(out, line + at, size);
    }
    fclose(f);
    return found;
}

/* <dir>/../share/passgraph or <dir> itself (the build tree: the data is the source tree's, found
 * below), for dir the folder of the executable */
static bool data_near_exe(const char *exe_path)
{
    char exe[PG_PATH_MAX];
    pg_strlcpy(exe, exe_path, sizeof exe);
    char *slash = strrchr(exe, '/');
    if (!slash) return false;
    *slash = 0;
    char cand[PG_PATH_MAX + 32];
    snprintf(cand, sizeof cand, "%s/../share/passgraph", exe);
    if (!dir_has_shaders(cand)) snprintf(cand, sizeof cand, "%s", exe);
    if (!dir_has_shaders(cand)) return false;
    return pg_strlcpy(g_data_dir, cand, sizeof g_data_dir);
}

/* <prefix>/share/passgraph next to a library's <prefix>/lib[/multiarch] */
static bool data_near_library(const char *lib_path)
{
    char lib[PG_PATH_MAX];
    pg_strlcpy(lib, lib_path, sizeof lib);
    for (int up = 0; up < 3; up++) {
        char *slash = strrchr(lib, '/');
        if (!slash) break;
        *slash = 0;
        char cand[PG_PATH_MAX + 32];
        snprintf(cand, sizeof cand, "%s/share/passgraph", lib);
        if (up > 0 && dir_has_shaders(cand)) return pg_strlcpy(g_data_dir, cand, sizeof g_data_dir);
    }
    return false;
}

/* The data of the code that runs: passgraph's own executable finds it next to itself; a program
 * that links libpassgraph.so (docs/embedding.md) gets the data next to that library first, not a
 * share/passgraph that happens to lie next to the program. The build tree falls back to the
 * source tree. */
static void find_data_dir(void)
{
    const char *env = getenv("PASSGRAPH_DATA_DIR");
    if (env && env[0]) {
        pg_strlcpy(g_data_dir, env, sizeof g_data_dir);
        return;
    }
    char exe[PG_PATH_MAX] = "", self[PG_PATH_MAX] = "";
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[n > 0 ? n : 0] = 0;
    const bool in_library = module_path((const void *)&find_data_dir, self, sizeof self) && exe[0] &&
                            strcmp(self, exe) != 0;
    if (in_library && data_near_library(self)) return;
    if (exe[0] && data_near_exe(exe)) return;
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

