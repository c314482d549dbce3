/* pipeline_json_paths.c - the folders a pipeline's includes may resolve into (pipeline_paths.h).
 * Part of the loader (pipeline_json_internal.h). */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* realpath() */
#endif
#include "pipeline_json_internal.h"
#include "pipeline_paths.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char g_dirs[PG_MAX_INCLUDE_DIRS][PATH_MAX];
static uint32_t g_n_dirs;

/* Lexically normalises an absolute path (., .., repeated /) in place. */
static void normalise(char *p)
{
    char out[PATH_MAX];
    size_t n = 0;
    const char *s = p;
    while (*s) {
        while (*s == '/') s++;
        if (!*s) break;
        const char *e = strchr(s, '/');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        if (len == 1 && s[0] == '.') {
            /* skip */
        } else if (len == 2 && s[0] == '.' && s[1] == '.') {
            while (n > 0 && out[n - 1] != '/') n--;
            if (n > 0) n--;
        } else if (n + 1 + len < sizeof out) {
            out[n++] = '/';
            memcpy(out + n, s, len);
            n += len;
        }
        s += len;
    }
    if (n == 0) out[n++] = '/';
    out[n] = 0;
    memcpy(p, out, n + 1);
}

/* The canonical absolute form of p: realpath when it exists, else realpath of its folder plus
 * its name, else a lexical normalisation (relative paths against the working folder). */
static void canon(const char *p, char out[PATH_MAX])
{
    if (realpath(p, out)) return;
    char tmp[PATH_MAX];
    if (p[0] == '/') {
        pg_strlcpy(tmp, p, sizeof tmp);
    } else {
        char cwd[PATH_MAX];
        if (!getcwd(cwd, sizeof cwd)) pg_strlcpy(cwd, "/", sizeof cwd);
        snprintf(tmp, sizeof tmp, "%s/%s", cwd, p);
    }
    normalise(tmp);
    char *slash = strrchr(tmp, '/');
    if (slash && slash != tmp) {
        *slash = 0;
        char dir[PATH_MAX];
        if (realpath(tmp, dir)) {
            char joined[PATH_MAX + 2];
            snprintf(joined, sizeof joined, "%s/%s", strcmp(dir, "/") ? dir : "", slash + 1);
            pg_strlcpy(out, joined, PATH_MAX);
            return;
        }
        *slash = '/';
    }
    pg_strlcpy(out, tmp, PATH_MAX);
}

/* The canonical folder of a file path. */
static void canon_dir(const char *file, char out[PATH_MAX])
{
    char c[PATH_MAX];
    canon(file, c);
    char *slash = strrchr(c, '/');
    if (slash && slash != c) *slash = 0;
    else if (slash) slash[1] = 0;
    pg_strlcpy(out, c, PATH_MAX);
}

static bool inside(const char *path, const char *dir)
{
    size_t n = strlen(dir);
    if (n == 1 && dir[0] == '/') return true;
    return strncmp(path, dir, n) == 0 && path[n] == '/';
}

/* path lies inside from_file's folder, top_file's folder (either may be NULL), the data folder's
 * pipelines/ or an --include-dir (decided on the canonical name). */
static bool path_allowed(const char *path, const char *from_file, const char *top_file)
{
    char target[PATH_MAX], dir[PATH_MAX];
    canon(path, target);
    const char *froms[2] = {from_file, top_file};
    for (int i = 0; i < 2; i++) {
        if (!froms[i]) continue;
        canon_dir(froms[i], dir);
        if (inside(target, dir)) return true;
    }
    char data[PG_PATH_MAX];
    pg_data_path(data, sizeof data, "pipelines");
    canon(data, dir);
    if (inside(target, dir)) return true;
    for (uint32_t i = 0; i < g_n_dirs; i++)
        if (inside(target, g_dirs[i])) return true;
    return false;
}

pg_result pg_pipeline_set_include_dirs(const char *const *dirs, uint32_t n, pg_error *err)
{
    if (n > PG_MAX_INCLUDE_DIRS)
        return pg_fail(err, PG_ERR_LIMIT, "--include-dir: more than %d folders", PG_MAX_INCLUDE_DIRS);
    for (uint32_t i = 0; i < n; i++) {
        struct stat st;
        if (stat(dirs[i], &st) != 0)
            return pg_fail(err, PG_ERR_IO, "--include-dir '%s': %s", dirs[i], strerror(errno));
        if (!S_ISDIR(st.st_mode))
            return pg_fail(err, PG_ERR_IO, "--include-dir '%s': not a directory", dirs[i]);
    }
    for (uint32_t i = 0; i < n; i++) canon(dirs[i], g_dirs[i]);
    g_n_dirs = n;
    return PG_OK;
}

pg_result pj_include_allowed(loader *L, const src_file *from, const char *ipath, const char *rel,
                             const char *path)
{
    if (path_allowed(path, from->path, L->stack[0]->path)) return PG_OK;
    return pj_fail_at(L, PG_ERR_INCLUDE, from, ipath,
                      "include '%s' is outside the allowed folders (the including file's folder, "
                      "the data folder, --include-dir)", rel);
}

pg_result pg_pipeline_resolve_file(const char *from_file, const char *top_file, const char *rel, char *out,
                                   size_t out_size, pg_error *err)
{
    int n;
    if (rel[0] == '/') {
        n = snprintf(out, out_size, "%s", rel);
    } else {
        const char *slash = strrchr(from_file, '/');
        n = slash ? snprintf(out, out_size, "%.*s/%s", (int)(slash - from_file), from_file, rel)
                  : snprintf(out, out_size, "%s", rel);
    }
    if (n < 0 || (size_t)n >= out_size || (size_t)n >= PATH_MAX) return pg_fail(err, PG_ERR_INCLUDE, "path too long");
    if (path_allowed(out, from_file, top_file)) return PG_OK;
    return pg_fail(err, PG_ERR_INCLUDE,
                   "'%s' is outside the allowed folders (the pipeline file's folder, the data folder's "
                   "pipelines/, --include-dir)",
                   rel);
}
