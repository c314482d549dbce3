/* cli.h - option parsing shared by the passgraph subcommands (render now; view, dump, bench
 * later). Every numeric option is range-checked; errors name the option and the bad value. */
#ifndef PG_CLI_H
#define PG_CLI_H

#include "pg_common.h"
#include "pipeline.h"
#include "scenario.h"

#define PG_CLI_MAX_SETS 32

typedef struct pg_cli_common {
    const char *pipeline;        /* --pipeline FILE */
    const char *scene;           /* --scene FILE|default */
    const char *scenario;        /* --scenario FILE */
    bool has_lights;             /* --lights N given */
    uint32_t lights;
    uint32_t width, height;      /* --size WxH */
    float time;                  /* --time T */
    uint32_t seed;               /* --seed S */
    bool has_radius, has_intensity;
    float radius, intensity;     /* --radius, --intensity */
    const char *out;             /* --out FILE */
    uint32_t n_sets;
    pg_param_override sets[PG_CLI_MAX_SETS]; /* --set key=value (points into argv) */
    int device_index;            /* --device N */
    const char *device_match;    /* --device NAME */
    bool validation;             /* --validation */
    bool no_aliasing;            /* --no-aliasing */
    bool explain;                /* --explain */
    uint32_t frames;             /* --frames N */
    const char *view;            /* --view NAME: the pipeline's debug view parameter */
    bool quiet;
} pg_cli_common;

void pg_cli_defaults(pg_cli_common *c);
/* Tries to consume argv[*i] (and its value). Returns PG_OK and sets *used when it was a
 * common option; PG_ERR_INVALID_ARG with a message for a bad value. */
pg_result pg_cli_parse_common(pg_cli_common *c, int argc, char **argv, int *i, bool *used, pg_error *err);
/* Text block describing the common options, for --help. */
extern const char *const pg_cli_common_help;

#endif
