/* bench_output.c - `passgraph bench`: DIR/results.csv, DIR/results.json, all outputs at once
 * (the charts from bench_charts.c) and the output folder. */
#include "bench.h"
#include "image_error_json.h"

/* ---------------------------------------------------------------- output: CSV and JSON */

static void csv_str(FILE *f, const char *s, bool first)
{
    if (!first) fputc(',', f);
    bool quote = strpbrk(s, ",\"\n\r") != NULL;
    if (!quote) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputs("\"\"", f);
        else if (*s == '\n' || *s == '\r') fputc(' ', f);
        else fputc(*s, f);
    }
    fputc('"', f);
}

static void csv_num(FILE *f, double v)
{
    if (isnan(v)) fputs(",", f);
    else if (isinf(v)) fputs(v > 0 ? ",inf" : ",-inf", f);
    else fprintf(f, ",%.6g", v);
}

static void csv_u64(FILE *f, bool has, uint64_t v)
{
    if (has) fprintf(f, ",%llu", (unsigned long long)v);
    else fputs(",", f);
}

static const char *const stat_names[] = {"median", "mean", "min", "max", "p95"};

static double stat_get(const pg_sample_stats *s, int k)
{
    if (!s->n) return NAN;
    switch (k) {
    case 0: return s->median;
    case 1: return s->mean;
    case 2: return s->min;
    case 3: return s->max;
    default: return s->p95;
    }
}

static pg_result write_csv(const bench *B, const char *path, pg_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    pass_union *u = malloc(sizeof *u);
    if (!u) {
        fclose(f);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    pg_bench_union_passes(B, u);
    fputs("scene,pipeline,variant,sets,lights,width,height,status,message,warmup,frames,time,seed", f);
    for (int k = 0; k < 5; k++) fprintf(f, ",gpu_ms_%s", stat_names[k]);
    for (int k = 0; k < 5; k++) fprintf(f, ",cpu_ms_%s", stat_names[k]);
    fputs(",plan_transient_bytes_unaliased,plan_transient_bytes_aliased,device_transient_bytes_unaliased,"
          "device_transient_bytes_aliased,overflow_clusters,overflow_dropped,overflow_clusters_max,light_refs,list_bytes,"
          "grow_events,reference,"
          "rmse_linear,psnr_linear,max_abs_linear,peak_linear,rmse_display,psnr_display,max_abs_display,"
          "share_over_1,nonfinite,error_note,pipeline_path,reference_sets,frames_in_flight,"
          "flip,hdr_flip,ssim,flicker,flicker_frames,accumulate,accumulated_ms_median,light_evals,evals_per_pixel",
          f);
    for (int k = 0; k < 5; k++) fprintf(f, ",wait_ms_%s", stat_names[k]);
    for (uint32_t p = 0; p < u->n; p++)
        for (int k = 0; k < 5; k++) fprintf(f, ",pass_%s_ms_%s", u->names[p], stat_names[k]);
    fputc('\n', f);
    for (uint32_t i = 0; i < B->n_rows; i++) {
        const bench_row *r = &B->rows[i];
        const pipe_entry *pe = &B->pipes[r->pipe];
        const variant *va = &pe->variants[r->variant];
        csv_str(f, B->scene_names[r->scene], true);
        csv_str(f, pe->name, false);
        csv_str(f, va->label, false);
        csv_str(f, va->sets_label, false);
        fprintf(f, ",%u,%u,%u", r->lights, r->width, r->height);
        csv_str(f, status_names[r->status], false);
        csv_str(f, r->message, false);
        fprintf(f, ",%u,%u,%g,%u", B->warmup, r->frames, (double)B->opt.time, B->opt.seed);
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->gpu, k));
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->cpu, k));
        csv_u64(f, r->has_memory, r->plan_unaliased);
        csv_u64(f, r->has_memory, r->plan_aliased);
        csv_u64(f, r->has_memory, r->dev_unaliased);
        csv_u64(f, r->has_memory, r->dev_aliased);
        bool ov_now = r->has_overflow && ROW_RAN(r);
        csv_u64(f, ov_now, r->ov_clusters);
        csv_u64(f, ov_now, r->ov_dropped);
        csv_u64(f, r->has_overflow, r->ov_clusters_max);
        csv_u64(f, ov_now, r->light_refs);
        csv_u64(f, ov_now, r->list_bytes);
        csv_u64(f, ROW_RAN(r) || r->status == ROW_INTERRUPTED, r->grow_events);
        csv_str(f, B->ref_name, false);
        const pg_image_error *e = &r->e;
        bool he = r->has_error;
        csv_num(f, he ? e->rmse_linear : NAN);
        csv_num(f, he ? e->psnr_linear : NAN);
        csv_num(f, he ? e->max_abs_linear : NAN);
        csv_num(f, he ? e->peak_linear : NAN);
        csv_num(f, he ? e->rmse_display : NAN);
        csv_num(f, he ? e->psnr_display : NAN);
        csv_num(f, he ? e->max_abs_display : NAN);
        csv_num(f, he ? e->share_over_threshold : NAN);
        csv_u64(f, r->has_nonfinite, r->nonfinite);
        csv_str(f, r->error_note, false);
        csv_str(f, pe->path, false);
        csv_str(f, B->refs[va->ref].label, false);
        fprintf(f, ",%u", B->frames_in_flight);
        csv_num(f, he ? r->pm.flip : NAN);
        csv_num(f, he ? r->pm.hdr_flip : NAN);
        csv_num(f, he ? r->pm.ssim : NAN);
        csv_num(f, he ? r->flicker : NAN);
        fprintf(f, ",%u,%u", B->flicker_frames, B->accumulate);
        csv_num(f, r->gpu.n ? B->accumulate * r->gpu.median : NAN);
        csv_u64(f, r->has_evals, r->light_evals);
        csv_num(f, r->has_evals ? (double)r->light_evals / ((double)r->width * r->height) : NAN);
        for (int k = 0; k < 5; k++) csv_num(f, stat_get(&r->wait, k));
        for (uint32_t p = 0; p < u->n; p++) {
            const pass_stat *ps = NULL;
            for (uint32_t q = 0; q < r->n_passes && !ps; q++)
                if (!strcmp(r->passes[q].name, u->names[p])) ps = &r->passes[q];
            for (int k = 0; k < 5; k++) csv_num(f, ps ? stat_get(&ps->st, k) : NAN);
        }
        fputc('\n', f);
    }
    free(u);
    bool ok = !ferror(f);
    int saved = errno;
    if (fclose(f)) ok = false, saved = errno;
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(saved));
    return PG_OK;
}

/* Finite numbers as numbers, inf as "inf" / "-inf" (like `compare --json`), NaN (unknown) as null
 * (image_error_json.h). */
static cJSON *jnum(double v)
{
    return pg_json_metric(v, true);
}

static cJSON *jstats(const pg_sample_stats *s)
{
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddNumberToObject(o, "n", s->n);
    for (int k = 0; k < 5; k++) cJSON_AddItemToObject(o, stat_names[k], jnum(stat_get(s, k)));
    return o;
}

static cJSON *json_meta(const bench *B)
{
    cJSON *m = cJSON_CreateObject();
    if (!m) return NULL;
    cJSON_AddStringToObject(m, "device", B->device);
    cJSON *sc = cJSON_AddArrayToObject(m, "scenes");
    for (uint32_t i = 0; sc && i < B->n_scenes; i++) cJSON_AddItemToArray(sc, cJSON_CreateString(B->scene_names[i]));
    if (B->opt.scenario) cJSON_AddStringToObject(m, "scenario", B->opt.scenario);
    /* --environment as given ("auto": the neutral sky for a glTF file without lights, else none) */
    cJSON_AddStringToObject(m, "environment", B->opt.environment ? B->opt.environment : "auto");
    cJSON_AddNumberToObject(m, "environment_intensity", B->opt.env_intensity);
    cJSON_AddNumberToObject(m, "environment_rotation_deg", B->opt.env_rotation_deg);
    /* --animation as given ("first": the file's first animation, when it has one) */
    cJSON_AddStringToObject(m, "animation", B->opt.animation ? B->opt.animation : "first");
    cJSON_AddStringToObject(m, "reference", B->ref_name);
    cJSON_AddStringToObject(m, "reference_path", B->ref_path);
    cJSON *rl = cJSON_AddObjectToObject(m, "reference_max_lights");
    if (rl) {
        cJSON_AddStringToObject(rl, "source", B->has_ref_max_lights ? "--reference-max-lights"
                                              : !B->device_known ? "default (no device opened)"
                                              : B->device_cpu   ? "default on a CPU device: a light x pixel budget"
                                                                : "default on a GPU");
        if (!B->has_ref_max_lights && B->device_cpu) cJSON_AddNumberToObject(rl, "budget", CPU_REFERENCE_BUDGET);
        cJSON *bs = cJSON_AddObjectToObject(rl, "by_size");
        for (uint32_t i = 0; bs && i < B->n_sizes; i++) {
            char b[32];
            snprintf(b, sizeof b, "%ux%u", B->widths[i], B->heights[i]);
            cJSON_AddNumberToObject(bs, b, ref_limit(B, B->widths[i], B->heights[i]));
        }
    }
    cJSON *sides = cJSON_AddArrayToObject(m, "sides"); /* what each pipeline and its reference used */
    for (uint32_t p = 0; sides && p < B->n_pipes; p++) {
        const pipe_entry *pe = &B->pipes[p];
        cJSON *o = cJSON_CreateObject();
        if (!o) break;
        cJSON_AddStringToObject(o, "pipeline", pe->name);
        cJSON_AddStringToObject(o, "pipeline_path", pe->path);
        cJSON_AddStringToObject(o, "pipeline_sets", pe->n_variants ? pe->variants[0].sets_label : "");
        cJSON *rs = cJSON_AddArrayToObject(o, "reference_sets"); /* one per distinct set over the variants */
        for (uint32_t v = 0; rs && v < pe->n_variants; v++) {
            bool seen = false;
            for (uint32_t w = 0; w < v && !seen; w++) seen = pe->variants[w].ref == pe->variants[v].ref;
            if (!seen) cJSON_AddItemToArray(rs, cJSON_CreateString(B->refs[pe->variants[v].ref].label));
        }
        cJSON_AddStringToObject(o, "reference", B->ref_name);
        cJSON_AddStringToObject(o, "reference_path", B->ref_path);
        cJSON_AddItemToArray(sides, o);
    }
    cJSON *so = cJSON_AddObjectToObject(m, "pipeline_sets"); /* --pipeline-set and the debug view */
    for (uint32_t i = 0; so && i < B->sides.pipeline.n; i++)
        cJSON_AddStringToObject(so, B->sides.pipeline.ov[i].key, B->sides.pipeline.ov[i].value);
    so = cJSON_AddObjectToObject(m, "reference_sets"); /* --reference-set */
    for (uint32_t i = 0; so && i < B->sides.reference.n; i++)
        cJSON_AddStringToObject(so, B->sides.reference.ov[i].key, B->sides.reference.ov[i].value);
    cJSON_AddStringToObject(m, "reference_sweeps", B->ref_sweeps);
    cJSON_AddNumberToObject(m, "warmup", B->warmup);
    cJSON_AddNumberToObject(m, "warmup_ms", B->warmup_ms);
    cJSON_AddNumberToObject(m, "frames_in_flight", B->frames_in_flight);
    cJSON_AddNumberToObject(m, "accumulate", B->accumulate);
    cJSON_AddNumberToObject(m, "flicker_frames", B->flicker_frames);
    cJSON_AddBoolToObject(m, "hdr_flip", !B->no_hdr_flip);
    cJSON_AddNumberToObject(m, "frames", B->opt.frames);
    cJSON_AddNumberToObject(m, "time", B->opt.time);
    cJSON_AddNumberToObject(m, "time_step", B->time_step);
    cJSON_AddNumberToObject(m, "seed", B->opt.seed);
    cJSON_AddBoolToObject(m, "validation", B->opt.validation);
    cJSON_AddBoolToObject(m, "no_aliasing", B->opt.no_aliasing);
    cJSON_AddBoolToObject(m, "immediate", B->opt.immediate);
    cJSON_AddBoolToObject(m, "interrupted", B->interrupted);
    cJSON *l = cJSON_AddArrayToObject(m, "lights");
    for (uint32_t i = 0; l && i < B->n_lights; i++) cJSON_AddItemToArray(l, cJSON_CreateNumber(B->lights[i]));
    cJSON *sz = cJSON_AddArrayToObject(m, "sizes");
    for (uint32_t i = 0; sz && i < B->n_sizes; i++) {
        char b[32];
        snprintf(b, sizeof b, "%ux%u", B->widths[i], B->heights[i]);
        cJSON_AddItemToArray(sz, cJSON_CreateString(b));
    }
    cJSON *st = cJSON_AddObjectToObject(m, "sets"); /* --set */
    for (uint32_t i = 0; st && i < B->sides.set.n; i++)
        cJSON_AddStringToObject(st, B->sides.set.ov[i].key, B->sides.set.ov[i].value);
    cJSON *sw = cJSON_AddObjectToObject(m, "sweeps");
    for (uint32_t k = 0; sw && k < B->n_sweeps; k++) {
        cJSON *a = cJSON_AddArrayToObject(sw, B->sweeps[k].key);
        for (uint32_t v = 0; a && v < B->sweeps[k].n; v++) cJSON_AddItemToArray(a, cJSON_CreateString(B->sweeps[k].values[v]));
    }
    cJSON_AddItemToObject(m, "elapsed_s", jnum(pg_time_s() - B->t_start));
    cJSON_AddBoolToObject(m, "device_cpu", B->device_cpu);
    cJSON_AddNumberToObject(m, "configs", B->n_configs);
    cJSON *av = cJSON_AddArrayToObject(m, "argv"); /* what bench-merge parses again */
    for (uint32_t i = 0; av && i < B->n_args; i++) cJSON_AddItemToArray(av, cJSON_CreateString(B->args[i]));
    if (B->shard_n) {
        cJSON *sh = cJSON_AddObjectToObject(m, "shard");
        cJSON_AddNumberToObject(sh, "k", B->shard_k);
        cJSON_AddNumberToObject(sh, "n", B->shard_n);
    }
    if (B->merged_shards) cJSON_AddNumberToObject(m, "merged_shards", B->merged_shards);
    return m;
}

static cJSON *json_row(const bench *B, const bench_row *r)
{
    const pipe_entry *pe = &B->pipes[r->pipe];
    const variant *va = &pe->variants[r->variant];
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddNumberToObject(o, "index", r->index);
    cJSON_AddStringToObject(o, "scene", B->scene_names[r->scene]);
    cJSON_AddStringToObject(o, "pipeline", pe->name);
    cJSON_AddStringToObject(o, "pipeline_path", pe->path);
    cJSON_AddStringToObject(o, "variant", va->label);
    cJSON_AddStringToObject(o, "sets", va->sets_label);
    cJSON_AddNumberToObject(o, "lights", r->lights);
    cJSON_AddNumberToObject(o, "width", r->width);
    cJSON_AddNumberToObject(o, "height", r->height);
    cJSON_AddStringToObject(o, "status", status_names[r->status]);
    cJSON_AddStringToObject(o, "message", r->message);
    cJSON_AddNumberToObject(o, "frames", r->frames);
    cJSON_AddItemToObject(o, "gpu_ms", jstats(&r->gpu));
    cJSON_AddItemToObject(o, "cpu_ms", jstats(&r->cpu));
    cJSON_AddItemToObject(o, "wait_ms", jstats(&r->wait));
    cJSON *ps = cJSON_AddArrayToObject(o, "passes");
    for (uint32_t p = 0; ps && p < r->n_passes; p++) {
        cJSON *x = jstats(&r->passes[p].st);
        if (x) cJSON_AddStringToObject(x, "name", r->passes[p].name);
        cJSON_AddItemToArray(ps, x);
    }
    if (r->has_memory) {
        cJSON *m = cJSON_AddObjectToObject(o, "memory");
        cJSON_AddNumberToObject(m, "plan_transient_bytes_unaliased", (double)r->plan_unaliased);
        cJSON_AddNumberToObject(m, "plan_transient_bytes_aliased", (double)r->plan_aliased);
        cJSON_AddNumberToObject(m, "device_transient_bytes_unaliased", (double)r->dev_unaliased);
        cJSON_AddNumberToObject(m, "device_transient_bytes_aliased", (double)r->dev_aliased);
    } else {
        cJSON_AddNullToObject(o, "memory");
    }
    if (r->has_overflow) {
        cJSON *m = cJSON_AddObjectToObject(o, "overflow");
        if (ROW_RAN(r)) {
            cJSON_AddNumberToObject(m, "clusters", (double)r->ov_clusters);
            cJSON_AddNumberToObject(m, "dropped", (double)r->ov_dropped);
            cJSON_AddNumberToObject(m, "light_refs", (double)r->light_refs);
            cJSON_AddNumberToObject(m, "list_bytes", (double)r->list_bytes);
        }
        cJSON_AddNumberToObject(m, "clusters_max", (double)r->ov_clusters_max);
    } else {
        cJSON_AddNullToObject(o, "overflow");
    }
    if (ROW_RAN(r) || r->status == ROW_INTERRUPTED) cJSON_AddNumberToObject(o, "grow_events", r->grow_events);
    else cJSON_AddNullToObject(o, "grow_events"); /* as the CSV: a row that did not run counts none */
    if (r->has_evals) cJSON_AddNumberToObject(o, "light_evals", (double)r->light_evals);
    else cJSON_AddNullToObject(o, "light_evals");
    cJSON_AddNumberToObject(o, "accumulate", B->accumulate);
    cJSON_AddStringToObject(o, "reference", B->ref_name);
    cJSON_AddStringToObject(o, "reference_sets", B->refs[va->ref].label);
    if (r->has_error) {
        const pg_image_error *e = &r->e;
        cJSON *m = cJSON_AddObjectToObject(o, "error");
        const pg_image_error_json_style style = {.share_key = "share_over_1", .nan_as_null = true};
        pg_image_error_json_add(m, e, &style);
        cJSON_AddNumberToObject(m, "reference_nonfinite", (double)e->nonfinite_b);
        cJSON_AddItemToObject(m, "flip", jnum(r->pm.flip));
        cJSON_AddItemToObject(m, "hdr_flip", jnum(r->pm.hdr_flip));
        const bool hf = !isnan(r->pm.hdr_flip);
        cJSON_AddItemToObject(m, "hdr_flip_start_exposure", jnum(hf ? r->pm.hdr.start_exposure : NAN));
        cJSON_AddItemToObject(m, "hdr_flip_stop_exposure", jnum(hf ? r->pm.hdr.stop_exposure : NAN));
        cJSON_AddItemToObject(m, "hdr_flip_exposures", jnum(hf ? r->pm.hdr.exposures : NAN));
        cJSON_AddItemToObject(m, "ssim", jnum(r->pm.ssim));
        cJSON_AddItemToObject(m, "flicker", jnum(r->flicker));
    } else {
        cJSON_AddNullToObject(o, "error");
    }
    if (r->has_nonfinite) cJSON_AddNumberToObject(o, "nonfinite", (double)r->nonfinite);
    else cJSON_AddNullToObject(o, "nonfinite");
    cJSON_AddStringToObject(o, "error_note", r->error_note);
    return o;
}

static pg_result write_json(const bench *B, const char *path, pg_error *err)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return pg_fail(err, PG_ERR_OOM, "out of memory");
    cJSON_AddNumberToObject(root, "passgraph_bench", 1);
    cJSON_AddItemToObject(root, "meta", json_meta(B));
    cJSON *rows = cJSON_AddArrayToObject(root, "rows");
    for (uint32_t i = 0; rows && i < B->n_rows; i++) cJSON_AddItemToArray(rows, json_row(B, &B->rows[i]));
    char *txt = cJSON_Print(root);
    cJSON_Delete(root);
    if (!txt) return pg_fail(err, PG_ERR_OOM, "out of memory");
    FILE *f = fopen(path, "w");
    bool ok = f && fputs(txt, f) >= 0 && fputc('\n', f) != EOF;
    int saved = errno;
    if (f && fclose(f)) ok = false, saved = errno;
    cJSON_free(txt);
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", path, strerror(saved));
    return PG_OK;
}

pg_result write_outputs(const bench *B, pg_error *err)
{
    char p[PG_PATH_MAX + 64];
    pg_result r;
    snprintf(p, sizeof p, "%s/results.csv", B->out_dir);
    if ((r = write_csv(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/results.json", B->out_dir);
    if ((r = write_json(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/gpu_time_vs_lights.svg", B->out_dir);
    if ((r = pg_bench_chart_time_vs_lights(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/passes_stacked.svg", B->out_dir);
    if ((r = pg_bench_chart_passes(B, p, err))) return r;
    snprintf(p, sizeof p, "%s/error_vs_time.svg", B->out_dir);
    if ((r = pg_bench_chart_error(B, p, BENCH_METRIC_RMSE, err))) return r;
    snprintf(p, sizeof p, "%s/flip_vs_time.svg", B->out_dir);
    return pg_bench_chart_error(B, p, BENCH_METRIC_FLIP, err);
}

/* mkdir -p */
pg_result make_dirs(const char *dir, pg_error *err)
{
    char p[PG_PATH_MAX];
    if (!pg_strlcpy(p, dir, sizeof p)) return pg_fail(err, PG_ERR_INVALID_ARG, "--out %s: path too long", dir);
    for (char *c = p + 1;; c++) {
        if (*c == '/' || !*c) {
            char save = *c;
            *c = 0;
            if (mkdir(p, 0777) && errno != EEXIST)
                return pg_fail(err, PG_ERR_IO, "--out %s: cannot create %s: %s", dir, p, strerror(errno));
            *c = save;
            if (!save) break;
        }
    }
    struct stat st;
    if (stat(dir, &st) || !S_ISDIR(st.st_mode))
        return pg_fail(err, PG_ERR_IO, "--out %s: not a directory", dir);
    return PG_OK;
}
