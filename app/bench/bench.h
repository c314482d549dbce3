/* bench.h - what the files of `passgraph bench` share (private to tools/): the run's state
 * (struct bench: options, pipelines x variants, rows of results, progress) and the functions
 * one file calls in another. cmd_bench.c: help, option loop, the run; bench_options.c: option
 * values, pipelines, variants and the reference sets; bench_run.c: progress bar and one row's
 * frames; bench_output.c: results.csv, results.json, the output folder; bench_charts.c: the
 * three SVG charts; bench_table.c: the pass columns both read. */
#ifndef PG_TOOLS_BENCH_H
#define PG_TOOLS_BENCH_H

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <dirent.h>
#include <time.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "app.h"
#include "bench_stats.h"
#include "commands.h"
#include "frame_metrics.h"
#include "image_compare.h"
#include "image_util.h"
#include "shader.h"
#include "sides.h"
#include "svg_plot.h"

#define MAX_LIST 64
#define MAX_SWEEPS 8
#define MAX_SWEEP_VALUES 32
#define MAX_VARIANTS 1024
/* Reference frames on a CPU device (lavapipe) cost about 1e8 light x pixel evaluations a second
 * on two cores; without --reference-max-lights the reference is rendered up to this many per
 * frame (20,000 lights at 320x180, 5,000 at 640x360: about ten seconds a reference frame). */
#define CPU_REFERENCE_BUDGET (20000.0 * 320.0 * 180.0)
#define GPU_REFERENCE_MAX_LIGHTS 1000000u

/* set by the SIGINT handler (cmd_bench.c; defined in bench_run.c): finish the current frame, write
 * what was measured */
extern volatile sig_atomic_t g_interrupted;

typedef struct sweep {
    const char *key;
    uint32_t n;
    const char *values[MAX_SWEEP_VALUES];
} sweep;

typedef struct variant {
    char label[256];                  /* "gbuffer=oct16;max_lights=256"; "" without sweeps */
    char sets_label[256];             /* its overrides besides the swept values (--set, --pipeline-set) */
    pg_ov_list ov;                    /* what the pipeline gets: --set, swept values, --pipeline-set */
    uint32_t ref;                     /* index into bench.refs: what the reference gets for this variant */
    bool ok;                          /* loads with these overrides */
    char msg[PG_ERROR_MSG_MAX];
    uint32_t series;                  /* global index: colour / marker in the charts */
} variant;

typedef struct pipe_entry {
    char path[PG_PATH_MAX];
    char name[PG_NAME_MAX];
    bool is_reference;
    bool loaded;
    char msg[PG_ERROR_MSG_MAX];
    uint32_t n_variants;
    variant *variants;
} pipe_entry;

/* ROW_INEXACT: ran, but its error frame dropped light references (not the exact image) */
typedef enum row_status { ROW_OK = 0, ROW_ERROR, ROW_SKIPPED, ROW_INTERRUPTED, ROW_INEXACT } row_status;
static const char *const status_names[] = {"ok", "error", "skipped", "interrupted", "inexact"};
/* a row whose timed frames and error frame ran */
#define ROW_RAN(r) ((r)->status == ROW_OK || (r)->status == ROW_INEXACT)

typedef struct pass_stat {
    char name[PG_NAME_MAX];
    pg_sample_stats st;
} pass_stat;

typedef struct bench_row {
    uint32_t index;                   /* configuration index (config_index): --shard, bench-merge */
    uint32_t scene, pipe, variant, lights, width, height;
    row_status status;
    char message[PG_ERROR_MSG_MAX];
    uint32_t frames;                  /* timed frames measured */
    pg_sample_stats gpu, cpu, wait;
    uint32_t n_passes;
    pass_stat passes[PG_MAX_PASSES];
    bool has_memory;
    uint64_t plan_unaliased, plan_aliased, dev_unaliased, dev_aliased;
    bool has_overflow;
    uint64_t ov_clusters, ov_dropped, ov_clusters_max;
    /* light lists of clustered pipelines: references stored, bytes of the list buffers, and how
     * often a "grow" buffer was enlarged over the row's frames (each such frame rendered again) */
    uint64_t light_refs, list_bytes;
    bool has_evals;                   /* the error frame counted light evaluations (light_evals) */
    uint64_t light_evals;
    uint32_t grow_events;
    bool has_error;
    pg_image_error e;
    pg_perceptual pm;                 /* with has_error: FLIP, HDR-FLIP, SSIM of the measured image */
    double flicker;                   /* with has_error: NaN when --flicker-frames 0 */
    bool has_nonfinite;
    uint64_t nonfinite;
    char error_note[256];
} bench_row;

typedef struct reference {
    bool tried, ok;
    char msg[PG_ERROR_MSG_MAX];
    float *hdr;
    uint8_t *ldr;
    uint32_t w, h;
} reference;

typedef struct ref_variant {
    pg_ov_list ov;                    /* the reference's overrides */
    char label[256];                  /* "k=v;k=v" as in the results' reference_sets column */
    uint32_t last_use;                /* last (pipeline, variant) in run order that needs it */
} ref_variant;

typedef struct bench {
    pg_cli_common opt;
    /* lists */
    uint32_t n_lights, n_sizes, n_scenes, n_sweeps, n_pipes;
    uint32_t lights[MAX_LIST];
    bool lights_given;          /* --lights was on the command line (generated lights added to a
                                   scene file's own; without it such a scene has only its own) */
    uint32_t widths[MAX_LIST], heights[MAX_LIST];
    const char *scenes[MAX_LIST];
    char scene_names[MAX_LIST][PG_PATH_MAX];
    sweep sweeps[MAX_SWEEPS];
    pipe_entry *pipes;
    uint32_t n_series;
    char ref_path[PG_PATH_MAX];
    char ref_name[PG_NAME_MAX];
    pg_side_sets sides;               /* --set, --pipeline-set, --reference-set, the debug view */
    uint32_t n_refs;                  /* distinct reference override sets (one per swept value the
                                       * reference declares), each rendered once per block */
    ref_variant *refs;
    char ref_sweeps[256];             /* the swept keys the reference declares, ","-separated */
    bool has_ref_max_lights;          /* --reference-max-lights (or --naive-max-lights) given */
    uint32_t ref_max_lights;
    bool device_known, device_cpu;    /* VK_PHYSICAL_DEVICE_TYPE_CPU: the default limit is a budget */
    uint32_t warmup;
    uint32_t warmup_ms;               /* --warmup-ms: warm up at least this long too (GPU clocks) */
    uint32_t frames_in_flight;
    uint32_t accumulate;              /* --accumulate N: the measured image is the mean of N frames */
    uint32_t flicker_frames;          /* --flicker-frames K (0: no flicker) */
    bool no_hdr_flip;                 /* --no-hdr-flip */
    double time_step;
    const char *out_dir;
    /* --shard K/N (shard_n 0: the whole sweep); configurations: scenes x sizes x lights x n_vars */
    uint32_t shard_k, shard_n, n_vars, n_configs;
    char **args;                      /* the options that define the sweep (meta.argv) */
    uint32_t n_args;
    uint32_t merged_shards;           /* bench-merge: how many shards the rows came from */
    /* results */
    bench_row *rows;
    uint32_t n_rows, cap_rows, n_failed;
    char device[256];
    uint32_t validation_messages;
    bool interrupted;
    /* progress */
    bool progress, tty;
    double total_work, done_work;
    double t_start, t_last_draw;
    uint32_t rows_total, rows_done;
} bench;

/* the pass columns: every pass name of any row, in first-seen order (bench_table.c) */
typedef struct pass_union {
    uint32_t n;
    char names[PG_MAX_PASSES * 4][PG_NAME_MAX];
} pass_union;

/* cmd_bench.c */
int bench_setup(bench *B, int argc, char **argv);
void bench_free(bench *B);
uint32_t config_index(const bench *B, uint32_t sc, uint32_t si, uint32_t li, uint32_t pipe, uint32_t var);
/* The inverse: fills r's index, scene, pipe, variant, lights, width and height from
 * configuration idx (< B->n_configs); the other fields are left as they are. */
void config_row(const bench *B, uint32_t idx, bench_row *r);

/* bench_options.c */
int pg_bench_split_list(char *s, char sep, char **parts, int max);
pg_result pg_bench_parse_lights(bench *B, char *v, pg_error *err);
pg_result parse_sizes(bench *B, char *v, pg_error *err);
pg_result parse_sweep(bench *B, char *v, pg_error *err);
pg_result parse_u32_opt(const char *opt, const char *v, uint32_t max, uint32_t *out, pg_error *err);
pg_result resolve_pipelines(bench *B, char *list, pg_error *err);
/* A --pipelines or --reference entry as a path: a file or a path as given, else a name of the
 * shipped pipelines/ (NAME or NAME.json) */
void pg_bench_pipeline_path(const char *name, char *path, size_t size);
pg_result pg_bench_plan_variants(bench *B, pg_error *err);
uint32_t ref_limit(const bench *B, uint32_t w, uint32_t h);
void ref_skip_note(const bench *B, uint32_t w, uint32_t h, bool brief, char *buf, size_t size);

/* bench_run.c */
double frame_work(uint32_t w, uint32_t h, uint32_t lights);
void progress_draw(bench *B, const char *what, bool row_done);
void progress_clear(bench *B);
bench_row *new_row(bench *B, pg_error *err);
void reference_free(reference *ref);
void run_row(bench *B, pg_app *app, const pg_frame_info *fi0, reference *refs, bench_row *row, const char *what);
void print_row(const bench *B, const bench_row *r);

/* bench_table.c */
void pg_bench_union_passes(const bench *B, pass_union *u);

/* bench_output.c */
pg_result write_outputs(const bench *B, pg_error *err);
pg_result make_dirs(const char *dir, pg_error *err);

/* bench_charts.c */
void series_label(const bench *B, uint32_t pipe, uint32_t var, char *buf, size_t size);
pg_result pg_bench_chart_time_vs_lights(const bench *B, const char *path, pg_error *err);
pg_result pg_bench_chart_passes(const bench *B, const char *path, pg_error *err);
/* the error axis of pg_bench_chart_error */
typedef enum bench_metric { BENCH_METRIC_RMSE, BENCH_METRIC_FLIP } bench_metric;
pg_result pg_bench_chart_error(const bench *B, const char *path, bench_metric metric, pg_error *err);

#endif
