/* sides.h - which parameter overrides each side of a comparison gets: the pipeline under test and
 * the reference it is measured against (`passgraph compare` and `passgraph bench`).
 *
 * The rule, the same for both commands:
 *   --set KEY=VALUE           the pipeline, and the reference too when the reference declares KEY
 *   --pipeline-set KEY=VALUE  the pipeline only (wins over --set there)
 *   --reference-set KEY=VALUE the reference only (wins over --set there)
 *   --view / --debug-view     the pipeline only (a debug view of the pipeline, not of the reference)
 *   --sweep KEY=V1,V2 (bench) each value goes to the pipeline, and to the reference when it declares
 *                             KEY, so that a swept light model is compared with the same light model
 *                             (--reference-set KEY=VALUE pins the reference instead)
 * Every list keeps one entry per key (a later one replaces an earlier one) and remembers which
 * option gave it, for the header line and for error messages. */
#ifndef PG_SIDES_H
#define PG_SIDES_H

#include "cli.h"
#include "pipeline.h"

#define PG_SIDES_MAX_OV (2 * PG_CLI_MAX_SETS + 16)

typedef struct pg_ov_list {
    uint32_t n;
    pg_param_override ov[PG_SIDES_MAX_OV];
    const char *from[PG_SIDES_MAX_OV]; /* the option: "--set", "--pipeline-set", "--debug-view", ... */
} pg_ov_list;

typedef struct pg_side_sets {
    pg_ov_list set;       /* --set */
    pg_ov_list pipeline;  /* --pipeline-set and the debug view (--view NAME of no OCIO view, --debug-view) */
    pg_ov_list reference; /* --reference-set */
} pg_side_sets;

/* Adds key=value (replacing the value of an entry with the same key). False when the list is full. */
bool pg_ov_list_put(pg_ov_list *l, const char *key, const char *value, const char *from);
const char *pg_ov_list_get(const pg_ov_list *l, const char *key);
/* "k=v;k=v" in list order, "" for an empty list (the format of bench's 'sets' column). */
void pg_ov_list_format(const pg_ov_list *l, char *buf, size_t size);

/* Consumes argv[*i] and its value when it is --pipeline-set or --reference-set (KEY=VALUE, split in
 * place: argv strings are writable); *used false for any other option. */
pg_result pg_sides_parse(pg_side_sets *s, int argc, char **argv, int *i, bool *used, pg_error *err);
/* Takes the --set values and the debug view (--view/--debug-view, which common parsing keeps among
 * c->sets as key 'view') from the common options; call after parsing. False if a list is full. */
bool pg_sides_from_common(pg_side_sets *s, const pg_cli_common *c);

/* The pipeline's overrides: --set, then the swept values, then --pipeline-set and the debug view.
 * decl NULL: every key (compare: an undeclared key is an error, see pg_sides_check_keys); else only
 * the keys decl declares (bench: each pipeline takes the values it declares). */
void pg_sides_pipeline(const pg_side_sets *s, const pg_pipeline *decl, const pg_param_override *swept,
                       uint32_t n_swept, pg_ov_list *out);
/* The reference's overrides: the --set and swept values whose key ref declares (ref NULL: none of
 * them), then every --reference-set value. */
void pg_sides_reference(const pg_side_sets *s, const pg_pipeline *ref, const pg_param_override *swept,
                        uint32_t n_swept, pg_ov_list *out);

/* PG_ERR_INVALID_ARG naming the option, key, side and what p declares when an entry of l has a key
 * p does not declare. side: "pipeline" / "reference". */
pg_result pg_sides_check_keys(const pg_ov_list *l, const pg_pipeline *p, const char *side, pg_error *err);
/* Loads path with l's overrides; when a value is refused (PG_ERR_PARAM) returns PG_ERR_INVALID_ARG
 * naming the option that gave it ("--reference-set shading=x: reference naive (FILE): enum ...").
 * Other load failures are returned as they are. */
pg_result pg_sides_check_values(const char *path, const pg_ov_list *l, const char *side, pg_error *err);

/* render and dump: the common options' --set values and debug view against opt's pipeline (or the
 * default, pipelines/naive.json) before a device is made: a key it does not declare or a value it
 * refuses is PG_ERR_INVALID_ARG naming the option that gave it (a bad option, exit 2). A file that
 * does not load gives PG_OK: its error comes where it is opened. */
pg_result pg_sides_check_common(const pg_cli_common *opt, pg_error *err);

#endif
