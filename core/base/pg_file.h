/* pg_file.h - every path input checked before it is read, every output path before work starts.
 *
 * pg_file_check() stat()s a path (it never opens it): only a regular file passes; a FIFO, a
 * character or block device, a directory or a socket is refused with one line naming the path and
 * what it is ("pipeline 'x.json': is a FIFO, not a regular file"), and a file over the cap of its
 * kind is refused before a byte is read ("scene 'big.gltf': is 2.1 GiB, over the 256 MiB cap for
 * glTF JSON files"). pg_file_read() checks, then opens with O_NONBLOCK|O_CLOEXEC and fstat()s the
 * open descriptor again, so a FIFO swapped in between the two can never block the reader.
 *
 * The caps, one per kind of input (docs/robustness.md, "Path inputs", has the same table):
 */
#ifndef PG_FILE_H
#define PG_FILE_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_MIB (1024ull * 1024ull)
#define PG_FILE_CAP_PIPELINE (16ull * PG_MIB)      /* pipeline JSON and its includes */
#define PG_FILE_CAP_SCENARIO (16ull * PG_MIB)      /* scenario JSON */
#define PG_FILE_CAP_GLTF_JSON (256ull * PG_MIB)    /* a .gltf file */
#define PG_FILE_CAP_GLB (2048ull * PG_MIB)         /* a .glb file (JSON and BIN chunks) */
#define PG_FILE_CAP_GLTF_RESOURCE (2048ull * PG_MIB) /* one external glTF buffer or image; a
                                                      * buffer must also have its byteLength */
#define PG_FILE_CAP_GLTF_TOTAL (4096ull * PG_MIB)  /* all external buffers and images of a scene */
#define PG_FILE_CAP_OCIO (64ull * PG_MIB)          /* an OCIO config and each LUT it names */
#define PG_FILE_CAP_IMAGE (1024ull * PG_MIB)       /* a PNG / EXR given to compare */
#define PG_FILE_CAP_BENCH_RESULTS (64ull * PG_MIB) /* a results.json given to bench-merge */

/* "a FIFO", "a directory", "a character device", "a block device", "a socket", "a symbolic
 * link", "a regular file" or "an unknown kind of file" for a stat st_mode. */
const char *pg_file_kind_name(unsigned mode);

/* Formats a byte count as "512 bytes", "17.0 MiB", "2.1 GiB" into buf. */
void pg_file_fmt_size(uint64_t bytes, char *buf, size_t n);

/* stat() path (never opens it). OK only for a regular file of at most max_bytes (0: no cap);
 * *size (may be NULL) gets its size. kind names the input in messages ("pipeline", "scene").
 * Errors (PG_ERR_IO, PG_ERR_LIMIT for the cap):
 *   KIND 'PATH': cannot open: <strerror>
 *   KIND 'PATH': is a FIFO, not a regular file
 *   KIND 'PATH': is 2.1 GiB, over the 16 MiB cap for KIND files */
pg_result pg_file_check(const char *path, const char *kind, uint64_t max_bytes, uint64_t *size,
                        pg_error *err);

/* pg_file_check, then reads the whole file into a malloc'd NUL-terminated buffer (*out_len may
 * be NULL). The descriptor is opened O_NONBLOCK|O_CLOEXEC and checked again with fstat(). */
pg_result pg_file_read(const char *path, const char *kind, uint64_t max_bytes, char **out_buf,
                       size_t *out_len, pg_error *err);

/* An output path: its folder must exist and be writable (access W_OK) and the path must not be
 * a directory; does not create the file. what names it in the message ("--out"):
 *   WHAT 'PATH': cannot write: <strerror> */
pg_result pg_file_check_writable(const char *path, const char *what, pg_error *err);

/* An output folder (bench --out DIR): exists, is a directory, and is writable; or does not exist
 * and its parent is a writable directory. */
pg_result pg_file_check_writable_dir(const char *path, const char *what, pg_error *err);

/* For a JSON parser that stopped in text at byte n - 1 (the byte it refused, included): " (nested
 * deeper than LIMIT levels, the most passgraph reads)" when the arrays and objects open in the
 * first n bytes (strings skipped) are more than limit deep, so the cause is named instead of a
 * bare syntax error; "" otherwise. Reads at most n bytes. */
const char *pg_json_depth_note(const char *text, size_t n, int limit);

#ifdef __cplusplus
}
#endif
#endif
