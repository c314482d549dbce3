/* pg_file.c - path inputs checked before they are read, output paths before work starts
 * (pg_file.h). */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700
#endif
#include "pg_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *pg_file_kind_name(unsigned mode)
{
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "an unknown kind of file";
}

void pg_file_fmt_size(uint64_t bytes, char *buf, size_t n)
{
    if (bytes >= 1024ull * PG_MIB) snprintf(buf, n, "%.1f GiB", (double)bytes / (1024.0 * PG_MIB));
    else if (bytes >= PG_MIB) snprintf(buf, n, "%.1f MiB", (double)bytes / (double)PG_MIB);
    else if (bytes >= 1024) snprintf(buf, n, "%.1f KiB", (double)bytes / 1024.0);
    else snprintf(buf, n, "%llu bytes", (unsigned long long)bytes);
}

static void fmt_cap(uint64_t bytes, char *buf, size_t n)
{
    if (bytes % (1024ull * PG_MIB) == 0) snprintf(buf, n, "%llu GiB", (unsigned long long)(bytes / (1024ull * PG_MIB)));
    else if (bytes % PG_MIB == 0) snprintf(buf, n, "%llu MiB", (unsigned long long)(bytes / PG_MIB));
    else pg_file_fmt_size(bytes, buf, n);
}

/* the checks shared by stat() and fstat() */
static pg_result check_stat(const struct stat *st, const char *path, const char *kind,
                            uint64_t max_bytes, uint64_t *size, pg_error *err)
{
    if (!S_ISREG(st->st_mode))
        return pg_fail(err, PG_ERR_IO, "%s '%s': is %s, not a regular file", kind, path,
                       pg_file_kind_name((unsigned)st->st_mode));
    uint64_t sz = st->st_size > 0 ? (uint64_t)st->st_size : 0;
    if (max_bytes && sz > max_bytes) {
        char got[32], cap[32];
        pg_file_fmt_size(sz, got, sizeof got);
        fmt_cap(max_bytes, cap, sizeof cap);
        return pg_fail(err, PG_ERR_LIMIT, "%s '%s': is %s, over the %s cap for %s files", kind,
                       path, got, cap, kind);
    }
    if (size) *size = sz;
    return PG_OK;
}

pg_result pg_file_check(const char *path, const char *kind, uint64_t max_bytes, uint64_t *size,
                        pg_error *err)
{
    if (size) *size = 0;
    if (!kind) kind = "file";
    if (!path || !path[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: no path given", kind);
    struct stat st;
    if (stat(path, &st) != 0)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot open: %s", kind, path, strerror(errno));
    return check_stat(&st, path, kind, max_bytes, size, err);
}

pg_result pg_file_read(const char *path, const char *kind, uint64_t max_bytes, char **out_buf,
                       size_t *out_len, pg_error *err)
{
    *out_buf = NULL;
    if (out_len) *out_len = 0;
    if (!kind) kind = "file";
    uint64_t size = 0;
    pg_result r = pg_file_check(path, kind, max_bytes, &size, err);
    if (r) return r;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return pg_fail(err, PG_ERR_IO, "%s '%s': cannot open: %s", kind, path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot stat: %s", kind, path, strerror(e));
    }
    r = check_stat(&st, path, kind, max_bytes, &size, err);
    if (r) {
        close(fd);
        return r;
    }
    if ((uint64_t)(size_t)size != size || size == SIZE_MAX) {
        close(fd);
        return pg_fail(err, PG_ERR_LIMIT, "%s '%s': too large for this build", kind, path);
    }
    char *buf = malloc((size_t)size + 1);
    if (!buf) {
        close(fd);
        return pg_fail(err, PG_ERR_OOM, "%s '%s': out of memory reading %llu bytes", kind, path,
                       (unsigned long long)size);
    }
    size_t got = 0;
    while (got < (size_t)size) {
        ssize_t k = read(fd, buf + got, (size_t)size - got);
        if (k < 0 && errno == EINTR) continue;
        if (k < 0) {
            int e = errno;
            free(buf);
            close(fd);
            return pg_fail(err, PG_ERR_IO, "%s '%s': cannot read: %s", kind, path, strerror(e));
        }
        if (k == 0) break;
        got += (size_t)k;
    }
    close(fd);
    if (got != (size_t)size) {
        free(buf);
        return pg_fail(err, PG_ERR_IO, "%s '%s': short read (%zu of %llu bytes; changed while read?)",
                       kind, path, got, (unsigned long long)size);
    }
    buf[got] = 0;
    *out_buf = buf;
    if (out_len) *out_len = got;
    return PG_OK;
}

/* the folder part of path ("." when it has none) */
static void dir_of(const char *path, char *buf, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (!slash) snprintf(buf, n, ".");
    else if (slash == path) snprintf(buf, n, "/");
    else snprintf(buf, n, "%.*s", (int)(slash - path), path);
}

/* The folder that holds entry (its parent) must exist and be writable; messages name path. */
static pg_result check_parent_dir(const char *entry, const char *path, const char *what, pg_error *err)
{
    char dir[PG_PATH_MAX];
    dir_of(entry, dir, sizeof dir);
    struct stat st;
    if (stat(dir, &st) != 0)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
    if (!S_ISDIR(st.st_mode))
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(ENOTDIR));
    if (access(dir, W_OK | X_OK) != 0)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
    /* access() answers from the permission bits, which root passes even where the file system
     * refuses new files (/proc, a read-only mount): create and remove a probe file */
    char probe[PG_PATH_MAX + 64];
    snprintf(probe, sizeof probe, "%s/.passgraph-probe-%ld", dir, (long)getpid());
    const int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0 && errno != EEXIST)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
    if (fd >= 0) {
        close(fd);
        unlink(probe);
    }
    return PG_OK;
}

pg_result pg_file_check_writable(const char *path, const char *what, pg_error *err)
{
    if (!what) what = "output";
    if (!path || !path[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: no path given", what);
    size_t len = strlen(path);
    struct stat st;
    if (path[len - 1] == '/' || (stat(path, &st) == 0 && S_ISDIR(st.st_mode)))
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(EISDIR));
    pg_result r = check_parent_dir(path, path, what, err);
    if (r) return r;
    if (access(path, F_OK) == 0 && access(path, W_OK) != 0)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
    return PG_OK;
}

pg_result pg_file_check_writable_dir(const char *path, const char *what, pg_error *err)
{
    if (!what) what = "output folder";
    if (!path || !path[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: no path given", what);
    struct stat st;
    if (stat(path, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(ENOTDIR));
        if (access(path, W_OK | X_OK) != 0)
            return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
        return PG_OK;
    }
    if (errno != ENOENT)
        return pg_fail(err, PG_ERR_IO, "%s '%s': cannot write: %s", what, path, strerror(errno));
    /* to be created: its parent must be a writable folder */
    char trimmed[PG_PATH_MAX];
    pg_strlcpy(trimmed, path, sizeof trimmed);
    size_t n = strlen(trimmed);
    while (n > 1 && trimmed[n - 1] == '/') trimmed[--n] = 0;
    return check_parent_dir(trimmed, path, what, err);
}

const char *pg_json_depth_note(const char *text, size_t n, int limit)
{
    static _Thread_local char note[96];
    long depth = 0, deepest = 0;
    bool in_string = false;
    const char *at = text ? text + n : NULL;
    for (const char *c = text; c && c < at; c++) {
        if (in_string) {
            if (*c == '\\' && c + 1 < at) c++;
            else if (*c == '"') in_string = false;
        } else if (*c == '"') {
            in_string = true;
        } else if (*c == '[' || *c == '{') {
            if (++depth > deepest) deepest = depth;
        } else if (*c == ']' || *c == '}') {
            depth--;
        }
    }
    if (deepest <= limit) return "";
    snprintf(note, sizeof note, " (nested deeper than %d levels, the most passgraph reads)", limit);
    return note;
}
