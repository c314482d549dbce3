/* cli.h - option parsing shared by the passgraph subcommands (render now; view, dump, bench
 * later). Every numeric option is range-checked; errors name the option and the bad value. */
#ifndef PG_CLI_H
#define PG_CLI_H

#include "pg_common.h"
#include "pipeline.h"
#include "scenario.h"

#define PG_CLI_MAX_SETS 32
#define PG_CLI_MAX_SETTINGS 8

enum { PG_ASYNC_AUTO = 0, PG_ASYNC_ON, PG_ASYNC_OFF, PG_ASYNC_EMULATE };

typedef struct pg_cli_common {
    const char *pipeline;        /* --pipeline FILE */
    const char *scene;           /* --scene FILE|default */
    const char *scenario;        /* --scenario FILE */
    const char *camera;          /* --camera N|NAME|auto (NULL: the default choice, app.h) */
    int gltf_scene;              /* --gltf-scene N (-1: the file's default scene) */
    const char *variant;         /* --variant N|NAME (KHR_materials_variants; NULL: the defaults) */
    bool has_lights;             /* --lights N given */
    uint32_t lights;
    uint32_t width, height;      /* --size WxH */
    float time;                  /* --time T, |T| <= PG_MAX_TIME_S */
    const char *animation;       /* --animation N|NAME|all|none (NULL: the first animation) */
    uint32_t n_plugins;
    const char *plugins[8];      /* --plugin FILE.so (repeatable; renderer/plugins.h) */
    uint32_t seed;               /* --seed S */
    bool has_seed;               /* --seed given (else a scenario's lights.seed wins over the default) */
    bool has_radius, has_intensity, has_ambient;
    float radius, intensity;     /* --radius, --intensity */
    float ambient;               /* --ambient (the light set-up's run-time ambient) */
    const char *environment;     /* --environment FILE.hdr|default|none (NULL: automatic, app.c) */
    float env_intensity;         /* --environment-intensity (default 1) */
    float env_rotation_deg;      /* --environment-rotation, degrees about +Y (default 0) */
    const char *out;             /* --out FILE */
    uint32_t n_sets;
    pg_param_override sets[PG_CLI_MAX_SETS]; /* --set key=value (points into argv) */
    int device_index;            /* --device N */
    const char *device_match;    /* --device NAME */
    bool validation;             /* --validation */
    bool require_exact;          /* --require-exact: a frame that dropped light references fails */
    bool no_aliasing;            /* --no-aliasing */
    bool immediate;              /* --immediate */
    int async_compute;           /* --async-compute: PG_ASYNC_AUTO (not given), _ON, _OFF, _EMULATE */
    bool explain;                /* --explain */
    uint32_t frames;             /* --frames N */
    const char *view;            /* --view NAME as given: an OCIO view of the display if the config
                                  * has one of that name, else the pipeline's debug view */
    const char *debug_view;      /* the pipeline parameter 'view' set by --debug-view / --view */
    const char *debug_view_option; /* which of the two gave it ("--view": no OCIO view of that name) */
    /* colour management (application settings, not pipeline parameters) */
    const char *ocio_config;     /* --ocio-config FILE (absent: $OCIO, else the shipped config) */
    const char *display;         /* --display NAME */
    const char *ocio_view;       /* --ocio-view NAME, or a --view naming an OCIO view */
    uint32_t n_settings;         /* what the options above give as pg_session_desc.settings: */
    pg_param_override settings[PG_CLI_MAX_SETTINGS]; /* "ocio.config", "ocio.display", "ocio.view" */
    bool quiet;
} pg_cli_common;

void pg_cli_defaults(pg_cli_common *c);
/* s as a whole number in [min, max] (a sign, fraction, exponent or trailing text refused) for option
 * opt; the message names opt, s and the range. */
pg_result pg_cli_parse_u64(const char *opt, const char *s, uint64_t min, uint64_t max, uint64_t *out, pg_error *err);
/* Tries to consume argv[*i] (and its value). Returns PG_OK and sets *used when it was a
 * common option; PG_ERR_INVALID_ARG with a message for a bad value. The colour options are
 * checked against the OCIO config the whole command line selects (wherever --ocio-config and
 * --display appear): an unknown display or view is an error listing the available ones, a bad
 * config an error naming the file. */
pg_result pg_cli_parse_common(pg_cli_common *c, int argc, char **argv, int *i, bool *used, pg_error *err);
/* Text block describing the common options, for --help. */
extern const char *const pg_cli_common_help;

#endif
