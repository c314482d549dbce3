/* bench_merge.c - `passgraph bench-merge --out DIR SHARD_DIR...`: joins the outputs of
 * `passgraph bench --shard K/N` runs into one sweep's results.csv, results.json and charts.
 *
 * Each shard's results.json keeps in its meta the options that define the sweep (meta.argv) and
 * the shard (meta.shard: k, n); every row keeps its configuration index. The merge checks that
 * the shards belong to one sweep (the same meta apart from shard and elapsed_s, every shard
 * K of 1..N once, every configuration index once), parses meta.argv again as bench does (the
 * same pipelines and variants: run it where the pipeline files are), reads the rows back and
 * writes them in the unsharded run's order with the bench's own writers. */
#include "bench.h"
#include "bench_merge_check.h"
#include "pg_file.h"

static const char *const merge_help =
    "usage: passgraph bench-merge --out DIR SHARD_DIR...\n"
    "Joins the output folders of 'passgraph bench --shard K/N' runs of one sweep into DIR/results.csv,\n"
    "DIR/results.json and the four charts, rows in the order an unsharded run writes them. Refuses\n"
    "(exit 1, naming the folder and the cause) shards of different sweeps (any meta field apart from\n"
    "shard and elapsed_s differs, device included), a shard given twice, a missing shard or\n"
    "configuration, and interrupted shards. Run it where the pipeline files of the sweep are (it\n"
    "parses the sweep's options again); it opens no device. Exit 2 on bad options. A folder of an\n"
    "unsharded run counts as the one shard of 1: 'bench-merge --out DIR RUN_DIR' writes the run's\n"
    "table and charts again (e.g. after the charts were left out).\n";

typedef struct shard_in {
    const char *dir;
    cJSON *root, *meta, *rows;
    uint32_t k, n;
} shard_in;

static double jget_num(const cJSON *o, const char *key)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    if (cJSON_IsNumber(x)) return x->valuedouble;
    if (cJSON_IsString(x) && !strcmp(x->valuestring, "inf")) return INFINITY;
    if (cJSON_IsString(x) && !strcmp(x->valuestring, "-inf")) return -INFINITY;
    return NAN;
}

static const char *jget_str(const cJSON *o, const char *key)
{
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(x) ? x->valuestring : NULL;
}

static void jstats_read(const cJSON *o, pg_sample_stats *s)
{
    double n = jget_num(o, "n");
    s->n = isfinite(n) && n > 0 && n <= UINT32_MAX ? (uint32_t)n : 0; /* past it: the cast is undefined */
    s->median = jget_num(o, "median");
    s->mean = jget_num(o, "mean");
    s->min = jget_num(o, "min");
    s->max = jget_num(o, "max");
    s->p95 = jget_num(o, "p95");
}

static uint64_t ju64(const cJSON *o, const char *key, bool *has)
{
    double v = jget_num(o, key);
    if (has) *has = isfinite(v);
    return isfinite(v) && v >= 0 && v < 18446744073709551616.0 ? (uint64_t)v : 0;
}

/* One results.json row back into a bench_row, checked against the configuration its index names. */
static pg_result row_read(const bench *B, const char *dir, const cJSON *o, bench_row *r, pg_error *err)
{
    double idx = jget_num(o, "index");
    if (!isfinite(idx) || idx < 0 || idx >= B->n_configs || idx != floor(idx))
        return pg_fail(err, PG_ERR_PARSE, "%s/results.json: a row without a valid configuration index", dir);
    memset(r, 0, sizeof *r);
    config_row(B, (uint32_t)idx, r);
    uint32_t sc = r->scene, p = r->pipe, v = r->variant;
    const char *scene = jget_str(o, "scene"), *pipe = jget_str(o, "pipeline"), *var = jget_str(o, "variant");
    if (!scene || strcmp(scene, B->scene_names[sc]) || !pipe || strcmp(pipe, B->pipes[p].name) || !var ||
        strcmp(var, B->pipes[p].variants[v].label) || jget_num(o, "lights") != r->lights ||
        jget_num(o, "width") != r->width || jget_num(o, "height") != r->height)
        return pg_fail(err, PG_ERR_PARSE,
                       "%s/results.json: row %u (%s %s '%s') is not configuration %u of the sweep its meta.argv "
                       "describes (%s %s '%s' %ux%u lights=%u)",
                       dir, r->index, scene ? scene : "?", pipe ? pipe : "?", var ? var : "?", r->index, B->scene_names[sc],
                       B->pipes[p].name, B->pipes[p].variants[v].label, r->width, r->height, r->lights);
    const char *st = jget_str(o, "status");
    int status = -1;
    for (int k = 0; st && k < (int)(sizeof status_names / sizeof status_names[0]); k++)
        if (!strcmp(st, status_names[k])) status = k;
    if (status < 0) return pg_fail(err, PG_ERR_PARSE, "%s/results.json: row %u: unknown status '%s'", dir, r->index, st ? st : "");
    r->status = (row_status)status;
    pg_strlcpy(r->message, jget_str(o, "message") ? jget_str(o, "message") : "", sizeof r->message);
    r->frames = (uint32_t)ju64(o, "frames", NULL);
    jstats_read(cJSON_GetObjectItemCaseSensitive(o, "gpu_ms"), &r->gpu);
    jstats_read(cJSON_GetObjectItemCaseSensitive(o, "cpu_ms"), &r->cpu);
    jstats_read(cJSON_GetObjectItemCaseSensitive(o, "wait_ms"), &r->wait);
    const cJSON *ps, *x;
    cJSON_ArrayForEach(ps, cJSON_GetObjectItemCaseSensitive(o, "passes"))
    {
        if (r->n_passes >= PG_MAX_PASSES) break;
        pass_stat *q = &r->passes[r->n_passes++];
        pg_strlcpy(q->name, jget_str(ps, "name") ? jget_str(ps, "name") : "", sizeof q->name);
        jstats_read(ps, &q->st);
    }
    if (cJSON_IsObject(x = cJSON_GetObjectItemCaseSensitive(o, "memory"))) {
        r->has_memory = true;
        r->plan_unaliased = ju64(x, "plan_transient_bytes_unaliased", NULL);
        r->plan_aliased = ju64(x, "plan_transient_bytes_aliased", NULL);
        r->dev_unaliased = ju64(x, "device_transient_bytes_unaliased", NULL);
        r->dev_aliased = ju64(x, "device_transient_bytes_aliased", NULL);
    }
    if (cJSON_IsObject(x = cJSON_GetObjectItemCaseSensitive(o, "overflow"))) {
        r->has_overflow = true;
        r->ov_clusters = ju64(x, "clusters", NULL);
        r->ov_dropped = ju64(x, "dropped", NULL);
        r->light_refs = ju64(x, "light_refs", NULL);
        r->list_bytes = ju64(x, "list_bytes", NULL);
        r->ov_clusters_max = ju64(x, "clusters_max", NULL);
    }
    r->grow_events = (uint32_t)ju64(o, "grow_events", NULL);
    r->light_evals = ju64(o, "light_evals", &r->has_evals);
    if (cJSON_IsObject(x = cJSON_GetObjectItemCaseSensitive(o, "error"))) {
        r->has_error = true;
        pg_image_error *e = &r->e;
        e->rmse_linear = jget_num(x, "rmse_linear");
        e->psnr_linear = jget_num(x, "psnr_linear");
        e->max_abs_linear = jget_num(x, "max_abs_linear");
        e->peak_linear = jget_num(x, "peak_linear");
        e->rmse_display = jget_num(x, "rmse_display");
        e->psnr_display = jget_num(x, "psnr_display");
        e->max_abs_display = jget_num(x, "max_abs_display");
        e->share_over_threshold = jget_num(x, "share_over_1");
        e->nonfinite_b = ju64(x, "reference_nonfinite", NULL);
        r->pm.flip = jget_num(x, "flip");
        r->pm.hdr_flip = jget_num(x, "hdr_flip");
        r->pm.hdr.start_exposure = jget_num(x, "hdr_flip_start_exposure");
        r->pm.hdr.stop_exposure = jget_num(x, "hdr_flip_stop_exposure");
        r->pm.hdr.exposures = (uint32_t)ju64(x, "hdr_flip_exposures", NULL);
        r->pm.ssim = jget_num(x, "ssim");
        r->flicker = jget_num(x, "flicker");
    }
    r->nonfinite = ju64(o, "nonfinite", &r->has_nonfinite);
    pg_strlcpy(r->error_note, jget_str(o, "error_note") ? jget_str(o, "error_note") : "", sizeof r->error_note);
    return PG_OK;
}

static pg_result shard_load(shard_in *s, pg_error *err)
{
    char path[PG_PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/results.json", s->dir);
    char *txt = NULL;
    pg_result rr = pg_file_read(path, "bench results", PG_FILE_CAP_BENCH_RESULTS, &txt, NULL, err);
    if (rr) return rr;
    s->root = cJSON_Parse(txt);
    free(txt);
    if (!s->root) return pg_fail(err, PG_ERR_PARSE, "%s/results.json: not valid JSON", s->dir);
    s->meta = cJSON_GetObjectItemCaseSensitive(s->root, "meta");
    s->rows = cJSON_GetObjectItemCaseSensitive(s->root, "rows");
    if (jget_num(s->root, "passgraph_bench") != 1 || !cJSON_IsObject(s->meta) || !cJSON_IsArray(s->rows))
        return pg_fail(err, PG_ERR_PARSE, "%s/results.json: not a passgraph bench result (passgraph_bench 1, meta, rows)",
                       s->dir);
    const cJSON *sh = cJSON_GetObjectItemCaseSensitive(s->meta, "shard");
    double k = 1, n = 1; /* no meta.shard: a whole run, the one shard of 1 */
    if (sh) {
        k = jget_num(sh, "k");
        n = jget_num(sh, "n");
    }
    /* whole numbers within bench's --shard range: a cast of 2^32 gave N 0, and a division by it */
    if ((sh && !cJSON_IsObject(sh)) || !(k >= 1 && n >= k && n <= 100000) || k != floor(k) || n != floor(n))
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "%s/results.json: meta.shard: expected {\"k\": K, \"n\": N}, whole numbers with 1 <= K <= N <= 100000",
                       s->dir);
    s->k = (uint32_t)k;
    s->n = (uint32_t)n;
    if (cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(s->meta, "interrupted")))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: shard %u/%u was interrupted (meta.interrupted): run it again", s->dir,
                       s->k, s->n);
    if (!cJSON_IsArray(cJSON_GetObjectItemCaseSensitive(s->meta, "argv")))
        return pg_fail(err, PG_ERR_PARSE, "%s/results.json: meta.argv missing", s->dir);
    return PG_OK;
}

/* The first meta field (apart from shard and elapsed_s) in which b differs from a, or NULL. */
static const char *meta_diff(const cJSON *a, const cJSON *b)
{
    const cJSON *x;
    cJSON_ArrayForEach(x, a)
    {
        if (!strcmp(x->string, "shard") || !strcmp(x->string, "elapsed_s")) continue;
        const cJSON *y = cJSON_GetObjectItemCaseSensitive(b, x->string);
        if (!y || !cJSON_Compare(x, y, true)) return x->string;
    }
    cJSON_ArrayForEach(x, b)
    {
        if (!strcmp(x->string, "shard") || !strcmp(x->string, "elapsed_s")) continue;
        if (!cJSON_GetObjectItemCaseSensitive(a, x->string)) return x->string;
    }
    return NULL;
}

/* --out DIR and the shard folders; -1 to go on, else the exit code (0 after --help, 2 after a
 * message on stderr) */
static int parse_merge_options(int argc, char **argv, const char **dirs, int *nd, const char **out)
{
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(merge_help, stdout);
            return 0;
        } else if (!strcmp(argv[i], "--out")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "passgraph bench-merge: --out: missing value\n");
                return 2;
            }
            *out = argv[++i];
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "passgraph bench-merge: unknown option '%s' (see passgraph bench-merge --help)\n", argv[i]);
            return 2;
        } else {
            dirs[(*nd)++] = argv[i];
        }
    }
    if (!*out || !*nd) {
        fprintf(stderr, "passgraph bench-merge: %s\n%s", !*out ? "--out DIR is required" : "no shard folder given",
                merge_help);
        return 2;
    }
    char want[PATH_MAX], have[PATH_MAX];
    for (int d = 0; d < *nd && realpath(*out, want); d++) /* the merged files would replace a shard's */
        if (realpath(dirs[d], have) && !strcmp(want, have)) {
            fprintf(stderr, "passgraph bench-merge: --out %s is the shard folder %s: write the merge elsewhere\n", *out,
                    dirs[d]);
            return 2;
        }
    return -1;
}

/* the shards loaded: one sweep, each shard K of 1..N once */
static pg_result load_shards(shard_in *sh, const char **dirs, int nd, pg_error *err)
{
    for (int d = 0; d < nd; d++) {
        sh[d].dir = dirs[d];
        pg_result r = shard_load(&sh[d], err);
        if (r) return r;
        if (d == 0) continue;
        const char *key = meta_diff(sh[0].meta, sh[d].meta);
        if (key)
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: not the same sweep as %s: meta.%s differs", dirs[d], dirs[0],
                           key);
        if (sh[d].n != sh[0].n)
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: shard %u/%u of a sweep in %u shards, %s is %u/%u", dirs[d],
                           sh[d].k, sh[d].n, sh[d].n, dirs[0], sh[0].k, sh[0].n);
        for (int e = 0; e < d; e++)
            if (sh[e].k == sh[d].k)
                return pg_fail(err, PG_ERR_INVALID_ARG, "%s: shard %u/%u given twice (also %s)", dirs[d], sh[d].k,
                               sh[d].n, dirs[e]);
    }
    for (uint32_t k = 1; k <= sh[0].n; k++) {
        bool found = false;
        for (int d = 0; d < nd && !found; d++) found = sh[d].k == k;
        if (!found)
            return pg_fail(err, PG_ERR_INVALID_ARG, "shard %u/%u missing (have %d of %u shard folders)", k, sh[0].n,
                           nd, sh[0].n);
    }
    return PG_OK;
}

/* the sweep's options (meta.argv of the first shard) with --out OUT: *args has *na + 2 strings
 * (freed by the caller, also on failure) */
static pg_result sweep_args(const shard_in *s0, const char *out, char ***args, int *na, pg_error *err)
{
    const cJSON *av = cJSON_GetObjectItemCaseSensitive(s0->meta, "argv");
    *na = cJSON_GetArraySize(av);
    char **a = *args = calloc((size_t)*na + 3, sizeof *a);
    if (!a) return pg_fail(err, PG_ERR_OOM, "out of memory");
    for (int i = 0; i < *na; i++) {
        const cJSON *x = cJSON_GetArrayItem(av, i);
        if (!cJSON_IsString(x) || !(a[i] = strdup(x->valuestring)))
            return pg_fail(err, PG_ERR_PARSE, "%s/results.json: meta.argv: expected strings", s0->dir);
    }
    a[*na] = strdup("--out");
    a[*na + 1] = strdup(out);
    if (!a[*na] || !a[*na + 1]) return pg_fail(err, PG_ERR_OOM, "out of memory");
    return PG_OK;
}

/* the first shard's meta against the sweep set up again (its configuration count), and its device */
static pg_result adopt_meta(bench *B, const shard_in *s0, pg_error *err)
{
    if (jget_num(s0->meta, "configs") != B->n_configs)
        return pg_fail(err, PG_ERR_INVALID_ARG,
                       "%s: meta.configs is %g but its options give %u configurations here (other pipeline files?)",
                       s0->dir, jget_num(s0->meta, "configs"), B->n_configs);
    B->opt.quiet = true;
    const char *dev = jget_str(s0->meta, "device");
    pg_strlcpy(B->device, dev ? dev : "(no device)", sizeof B->device);
    B->device_known = dev && strcmp(dev, "(no device)");
    B->device_cpu = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(s0->meta, "device_cpu"));
    B->validation_messages = 0;
    B->merged_shards = s0->n;
    return PG_OK;
}

/* shard d's rows into B->rows at their configuration index (each its shard's, each once) */
static pg_result read_shard_rows(bench *B, const shard_in *s, uint8_t *seen_cfg, pg_error *err)
{
    const cJSON *o;
    uint32_t rowno = 0;
    pg_result r;
    cJSON_ArrayForEach(o, s->rows)
    {
        bench_row row;
        char file[PG_PATH_MAX + 32];
        snprintf(file, sizeof file, "%s/results.json", s->dir);
        if ((r = pg_bench_row_check(file, rowno++, o, err))) return r;
        if ((r = row_read(B, s->dir, o, &row, err))) return r;
        if (row.index % s->n != s->k - 1)
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: configuration %u does not belong to shard %u/%u", s->dir,
                           row.index, s->k, s->n);
        if (seen_cfg[row.index])
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: configuration %u given twice", s->dir, row.index);
        seen_cfg[row.index] = 1;
        B->rows[row.index] = row;
    }
    return PG_OK;
}

/* the rows, each configuration once, in index order; *elapsed the longest shard's elapsed_s */
static pg_result read_rows(bench *B, const shard_in *sh, int nd, double *elapsed, pg_error *err)
{
    B->rows = calloc(B->n_configs ? B->n_configs : 1, sizeof *B->rows);
    uint8_t *seen_cfg = calloc(B->n_configs ? B->n_configs : 1, 1);
    pg_result r = PG_OK;
    if (!B->rows || !seen_cfg) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
        goto out;
    }
    B->cap_rows = B->n_configs;
    for (int d = 0; d < nd; d++) {
        double el = jget_num(sh[d].meta, "elapsed_s");
        if (isfinite(el) && el > *elapsed) *elapsed = el;
        if ((r = read_shard_rows(B, &sh[d], seen_cfg, err))) goto out;
    }
    for (uint32_t i = 0; i < B->n_configs; i++)
        if (!seen_cfg[i]) {
            int d = 0;
            while (d < nd && sh[d].k - 1 != i % sh[0].n) d++;
            r = pg_fail(err, PG_ERR_INVALID_ARG, "%s: configuration %u (shard %u/%u) missing from its results.json",
                        d < nd ? sh[d].dir : "?", i, i % sh[0].n + 1, sh[0].n);
            goto out;
        }
    B->n_rows = B->n_configs;
    for (uint32_t i = 0; i < B->n_rows; i++) B->n_failed += B->rows[i].status == ROW_ERROR;
out:
    free(seen_cfg);
    return r;
}

int pg_cmd_bench_merge(int argc, char **argv)
{
    const char *out = NULL;
    const char **dirs = calloc((size_t)argc + 1, sizeof *dirs);
    shard_in *sh = calloc((size_t)argc + 1, sizeof *sh);
    bench *B = calloc(1, sizeof *B);
    char **args = NULL;
    int nd = 0, rc = 2, na = 0;
    pg_error err = {0};
    if (!dirs || !sh || !B) {
        fprintf(stderr, "passgraph bench-merge: out of memory\n");
        rc = 1;
        goto done;
    }
    rc = parse_merge_options(argc, argv, dirs, &nd, &out);
    if (rc >= 0) goto done;
    rc = 1;
    if (load_shards(sh, dirs, nd, &err) || sweep_args(&sh[0], out, &args, &na, &err)) goto fail;
    /* the sweep again, from the options the shards ran with */
    if (bench_setup(B, na + 2, args) >= 0) {
        fprintf(stderr, "passgraph bench-merge: %s: the sweep's options (meta.argv) do not parse here (see above)\n",
                dirs[0]);
        goto done;
    }
    double elapsed = 0;
    if (adopt_meta(B, &sh[0], &err) || read_rows(B, sh, nd, &elapsed, &err)) goto fail;
    B->t_start = pg_time_s() - elapsed; /* meta.elapsed_s: the longest shard's */
    if (make_dirs(B->out_dir, &err) || write_outputs(B, &err)) goto fail;
    printf("bench-merge: %u rows (%u failed) from %u shards -> %s/results.csv, results.json, gpu_time_vs_lights.svg, "
           "passes_stacked.svg, error_vs_time.svg, flip_vs_time.svg\n",
           B->n_rows, B->n_failed, sh[0].n, B->out_dir);
    rc = 0;
    if (B->n_failed) { /* as the sweep run whole exits (it said 0) */
        fprintf(stderr, "passgraph bench-merge: %u configuration(s) failed (see 'status' and 'message' in results.csv)\n",
                B->n_failed);
        rc = 1;
    }
    goto done;
fail:
    fprintf(stderr, "passgraph bench-merge: %s\n", err.msg);
    rc = 1;
done:
    if (sh)
        for (int d = 0; d < nd; d++) cJSON_Delete(sh[d].root);
    if (args)
        for (int i = 0; i < na + 2; i++) free(args[i]);
    free(args);
    if (B) bench_free(B);
    free(B);
    free(sh);
    free(dirs);
    return rc;
}
