/* pipeline_paths.h - where a pipeline's `include`s may come from.
 *
 * An include resolves (realpath) inside one of: the including file's folder (or the top-level
 * pipeline's folder, which the user chose), the data folder's pipelines/, and the folders given
 * here (the CLI's --include-dir, repeatable). Anything else, an absolute path or a ../ that
 * leaves those folders, is refused by name before the file is opened:
 *   p.json: include[0]: include '/etc/passwd' is outside the allowed folders (the including
 *   file's folder, the data folder, --include-dir)
 * The top-level pipeline path itself may be anywhere (it is still checked: pg_file.h).
 */
#ifndef PG_PIPELINE_PATHS_H
#define PG_PIPELINE_PATHS_H

#include "pg_common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PG_MAX_INCLUDE_DIRS 16

/* Replaces the extra include folders (process-wide; the CLI sets them once while parsing its
 * options). Each must be an existing directory; n = 0 clears them. */
pg_result pg_pipeline_set_include_dirs(const char *const *dirs, uint32_t n, pg_error *err);

/* A file a pipeline names other than an include (a `shader` pass's GLSL file): rel resolved against
 * from_file's folder (an absolute rel as it is) into out, then held to the include rules above
 * (from_file's folder, top_file's folder, the data folder's pipelines/, --include-dir), decided on
 * the name before the file is touched. The message has no file/JSON prefix (the caller adds it):
 *   "'../../etc/passwd' is outside the allowed folders (...)" or "path too long". */
pg_result pg_pipeline_resolve_file(const char *from_file, const char *top_file, const char *rel, char *out,
                                   size_t out_size, pg_error *err);

#ifdef __cplusplus
}
#endif
#endif
