/* pipeline_json_internal.h - the pipeline loader's state and the helpers its files share; not
 * part of the graph library's interface (only core/graph/pipeline_json*.c include it).
 *
 *   pipeline_json.c            passes, links, the build into a pg_pipeline, the entry points
 *   pipeline_json_text.c       JSON text (syntax errors as FILE:LINE:COL), unknown and duplicate
 *                              keys, the helpers every message uses
 *   pipeline_json_include.c    source files, includes (missing, cyclic, too deep), per-file keys
 *   pipeline_json_params.c     parameter declarations, --set overrides, "$param", "when"
 *   pipeline_json_resources.c  resource objects
 *   pipeline_json_common.c     what the item parsers share: preamble, duplicate names, name/type
 */
#ifndef PG_PIPELINE_JSON_INTERNAL_H
#define PG_PIPELINE_JSON_INTERNAL_H

#include "pipeline.h"

#include <cjson/cJSON.h>
#include "json_describe.h"

#define PG_MAX_INCLUDE_DEPTH 16  /* include nesting below the top-level file */
#define JP_MAX 512               /* JSON paths inside error messages */

typedef struct src_file {
    char path[PG_PATH_MAX]; /* as written in messages */
    char *canon;            /* realpath (or the path itself): identity for cycle detection */
    cJSON *root;
} src_file;

typedef struct item_ref {
    cJSON *node;          /* the resource / pass object inside its file's tree */
    const src_file *file;
    uint32_t index;       /* position in its own file's array */
    bool omitted;
    uint32_t omit_index;  /* into pipeline->omitted when omitted */
    cJSON *options;       /* passes: the "options" object in the tree, or NULL */
} item_ref;

typedef struct loader {
    pg_pipeline *p;
    pg_error *err;
    src_file **files;
    uint32_t n_files, cap_files;
    const src_file *stack[PG_MAX_INCLUDE_DEPTH + 1]; /* the include chain being loaded */
    uint32_t depth;
    const src_file *param_file[PG_MAX_PARAMS];
    const cJSON *param_decl[PG_MAX_PARAMS];
    uint32_t n_res, n_pass;
    item_ref res[PG_MAX_RESOURCES];
    item_ref pass[PG_MAX_PASSES];
    pg_resource_desc rdesc[PG_MAX_RESOURCES];
    pg_pass_desc pdesc[PG_MAX_PASSES];
    char jp[JP_MAX]; /* scratch JSON path for the recursive walks */
} loader;
/* pipeline_json_text.c */
pg_result pj_fail_at(loader *L, pg_result code, const src_file *f, const char *path,
                  const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
void pj_fmt_double(double v, char *buf, size_t n);
void pj_list_append(char *buf, size_t n, const char *item);
bool pj_json_integer(const cJSON *v, double lo, double hi, double *out);
size_t pj_jp_push(loader *L, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void pj_jp_pop(loader *L, size_t mark);
pg_result pj_check_keys(loader *L, const src_file *f, const cJSON *obj, const char *path,
                     const char *what, const char *const *allowed);
pg_result pj_parse_text(loader *L, src_file *f, const char *text, size_t len);

/* pipeline_json_include.c */
src_file *pj_new_file(loader *L, const char *path);
pg_result pj_process_file(loader *L, const src_file *f);

/* pipeline_json_params.c */
pg_result pj_add_param(loader *L, const src_file *f, const cJSON *decl);
pg_result pj_apply_overrides(loader *L, const pg_param_override *ov, uint32_t n);
pg_result pj_substitute(loader *L, const src_file *f, cJSON *node, bool top);
pg_result pj_eval_when(loader *L, const src_file *f, const cJSON *item, const char *ipath,
                    bool *active, char *why, size_t whyn);

/* pipeline_json_resources.c */
pg_result pj_parse_resource(loader *L, uint32_t idx);

/* pipeline_json_common.c */
pg_result pj_req_ident(loader *L, const src_file *f, const cJSON *obj, const char *ipath,
                    const char *key, char *out);
pg_result pj_opt_description(loader *L, const src_file *f, const cJSON *obj, const char *ipath);
pg_result pj_item_begin(loader *L, const src_file *f, cJSON *o, const char *ip, const char *what,
                        const char *const *keys, char *name);
pg_result pj_item_twice(loader *L, const src_file *f, const char *ip, const char *what,
                        const char *name, const src_file *prev_file, const char *prev_path,
                        const char *prev_json_path);

/* pipeline_json_paths.c: refuses an include that resolves outside the allowed folders */
pg_result pj_include_allowed(loader *L, const src_file *from, const char *ipath, const char *rel,
                             const char *path);

#endif
