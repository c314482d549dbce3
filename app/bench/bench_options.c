/* bench_options.c - `passgraph bench`: option values (lists, sizes, sweeps), the pipelines to run,
 * their variants and the reference's override sets, and the reference's light limit. */
#include "bench.h"

/* ---------------------------------------------------------------- options */

/* Splits s in place at sep; at most max parts. Returns the count, or -1 if there are too many. */
int pg_bench_split_list(char *s, char sep, char **parts, int max)
{
    int n = 0;
    for (;;) {
        if (n >= max) return -1;
        parts[n++] = s;
        char *c = strchr(s, sep);
        if (!c) break;
        *c = 0;
        s = c + 1;
    }
    return n;
}

/* One list element through the common parser, so values are checked exactly like render's. */
static pg_result parse_one_common(const char *opt, char *value, pg_cli_common *scratch, pg_error *err)
{
    char *av[2] = {(char *)opt, value};
    int i = 0;
    bool used;
    return pg_cli_parse_common(scratch, 2, av, &i, &used, err);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

pg_result pg_bench_parse_lights(bench *B, char *v, pg_error *err)
{
    char *parts[MAX_LIST];
    int n = pg_bench_split_list(v, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--lights: at most %d values", MAX_LIST);
    uint32_t tmp[MAX_LIST];
    for (int i = 0; i < n; i++) {
        pg_cli_common c;
        pg_cli_defaults(&c);
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--lights: empty value in the list");
        pg_result r = parse_one_common("--lights", parts[i], &c, err);
        if (r) return r;
        tmp[i] = c.lights;
    }
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_u32);
    B->n_lights = 0;
    for (int i = 0; i < n; i++)
        if (!B->n_lights || B->lights[B->n_lights - 1] != tmp[i]) B->lights[B->n_lights++] = tmp[i];
    return PG_OK;
}

pg_result parse_sizes(bench *B, char *v, pg_error *err)
{
    char *parts[MAX_LIST];
    int n = pg_bench_split_list(v, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--size: at most %d values", MAX_LIST);
    B->n_sizes = 0;
    for (int i = 0; i < n; i++) {
        pg_cli_common c;
        pg_cli_defaults(&c);
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--size: empty value in the list");
        pg_result r = parse_one_common("--size", parts[i], &c, err);
        if (r) return r;
        bool dup = false;
        for (uint32_t k = 0; k < B->n_sizes; k++) dup |= B->widths[k] == c.width && B->heights[k] == c.height;
        if (dup) continue;
        B->widths[B->n_sizes] = c.width;
        B->heights[B->n_sizes] = c.height;
        B->n_sizes++;
    }
    return PG_OK;
}

/* Two sweep values that are the same: the same text, or two equal numbers ("1" and "1.0" would run
 * one configuration twice). */
static bool same_value(const char *a, const char *b)
{
    if (!strcmp(a, b)) return true;
    char *ea = NULL, *eb = NULL;
    const double x = strtod(a, &ea), y = strtod(b, &eb);
    return ea != a && eb != b && !*ea && !*eb && isfinite(x) && x == y;
}

pg_result parse_sweep(bench *B, char *v, pg_error *err)
{
    if (B->n_sweeps >= MAX_SWEEPS) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep: at most %d", MAX_SWEEPS);
    char *eq = strchr(v, '=');
    if (!eq || eq == v || !eq[1])
        return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: expected KEY=VALUE1,VALUE2,...", v);
    *eq = 0;
    sweep *s = &B->sweeps[B->n_sweeps];
    s->key = v;
    for (uint32_t k = 0; k < B->n_sweeps; k++)
        if (!strcmp(B->sweeps[k].key, v)) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: key given twice", v);
    char *parts[MAX_SWEEP_VALUES];
    int n = pg_bench_split_list(eq + 1, ',', parts, MAX_SWEEP_VALUES);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: at most %d values", v, MAX_SWEEP_VALUES);
    s->n = 0;
    for (int i = 0; i < n; i++) {
        if (!parts[i][0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: empty value in the list", v);
        for (uint32_t k = 0; k < s->n; k++)
            if (same_value(s->values[k], parts[i]))
                return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: value '%s' given twice (as '%s')", v, parts[i],
                               s->values[k]);
        s->values[s->n++] = parts[i];
    }
    B->n_sweeps++;
    return PG_OK;
}

pg_result parse_u32_opt(const char *opt, const char *v, uint32_t max, uint32_t *out, pg_error *err)
{
    if (!v || !*v) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    if (*v < '0' || *v > '9')
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [0, %u]", opt, v, max);
    errno = 0;
    char *end;
    unsigned long long u = strtoull(v, &end, 10);
    if (errno || *end || u > max)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [0, %u]", opt, v, max);
    *out = (uint32_t)u;
    return PG_OK;
}

/* ---------------------------------------------------------------- pipelines and variants */

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static bool is_file(const char *p)
{
    struct stat st;
    return !stat(p, &st) && S_ISREG(st.st_mode);
}

static void file_stem(const char *path, char *buf, size_t size)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    pg_strlcpy(buf, b, size);
    char *dot = strrchr(buf, '.');
    if (dot && dot != buf) *dot = 0;
}

static pg_result add_pipe(bench *B, const char *path, pg_error *err)
{
    pipe_entry *p = realloc(B->pipes, (B->n_pipes + 1) * sizeof *p);
    if (!p) return pg_fail(err, PG_ERR_OOM, "out of memory");
    B->pipes = p;
    pipe_entry *e = &p[B->n_pipes++];
    memset(e, 0, sizeof *e);
    pg_strlcpy(e->path, path, sizeof e->path);
    file_stem(path, e->name, sizeof e->name);
    return PG_OK;
}

/* Every top-level *.json of the data folder's pipelines/, sorted by name. */
static pg_result list_all_pipelines(bench *B, pg_error *err)
{
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    DIR *d = opendir(dir);
    if (!d) return pg_fail(err, PG_ERR_IO, "--pipelines all: cannot list %s: %s", dir, strerror(errno));
    char *names[256];
    uint32_t n = 0;
    pg_result r = PG_OK;
    struct dirent *de;
    while ((de = readdir(d))) {
        size_t l = strlen(de->d_name);
        if (l < 6 || strcmp(de->d_name + l - 5, ".json") || de->d_name[0] == '.') continue;
        char full[PG_PATH_MAX];
        snprintf(full, sizeof full, "%s/%s", dir, de->d_name);
        if (!is_file(full)) continue;
        if (n >= 256) {
            r = pg_fail(err, PG_ERR_LIMIT, "--pipelines all: more than 256 files in %s", dir);
            break;
        }
        names[n] = malloc(strlen(full) + 1);
        if (!names[n]) {
            r = pg_fail(err, PG_ERR_OOM, "out of memory");
            break;
        }
        memcpy(names[n], full, strlen(full) + 1);
        n++;
    }
    closedir(d);
    if (!r) {
        qsort(names, n, sizeof *names, cmp_str);
        if (!n) r = pg_fail(err, PG_ERR_IO, "--pipelines all: no .json file in %s", dir);
    }
    for (uint32_t i = 0; i < n; i++) {
        if (!r) r = add_pipe(B, names[i], err);
        free(names[i]);
    }
    return r;
}

static bool same_file(const char *a, const char *b)
{
    char ra[PATH_MAX], rb[PATH_MAX];
    if (!realpath(a, ra) || !realpath(b, rb)) return !strcmp(a, b);
    return !strcmp(ra, rb);
}

void pg_bench_pipeline_path(const char *name, char *path, size_t size)
{
    pg_strlcpy(path, name, size);
    if (is_file(name) || strchr(name, '/')) return;
    char rel[PG_PATH_MAX];
    size_t l = strlen(name);
    snprintf(rel, sizeof rel, "pipelines/%s%s", name, l > 5 && !strcmp(name + l - 5, ".json") ? "" : ".json");
    pg_data_path(path, size, rel);
}

pg_result resolve_pipelines(bench *B, char *list, pg_error *err)
{
    if (!list || !strcmp(list, "all")) return list_all_pipelines(B, err);
    char *parts[MAX_LIST];
    int n = pg_bench_split_list(list, ',', parts, MAX_LIST);
    if (n < 0) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: at most %d entries", MAX_LIST);
    for (int i = 0; i < n; i++) {
        const char *t = parts[i];
        if (!t[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: empty entry in the list");
        if (!strcmp(t, "all")) return pg_fail(err, PG_ERR_INVALID_ARG, "--pipelines: 'all' cannot be combined with names");
        char path[PG_PATH_MAX];
        pg_bench_pipeline_path(t, path, sizeof path); /* also when missing: its row's error names the file tried */
        bool dup = false; /* the same file twice (by name and by path): run once */
        for (uint32_t k = 0; k < B->n_pipes && !dup; k++) dup = same_file(B->pipes[k].path, path);
        if (dup) {
            fprintf(stderr, "passgraph bench: --pipelines: '%s' is listed twice: run once\n", t);
            continue;
        }
        pg_result r = add_pipe(B, path, err);
        if (r) return r;
    }
    return PG_OK;
}

static bool same_ov(const pg_ov_list *a, const pg_ov_list *b)
{
    if (a->n != b->n) return false;
    for (uint32_t k = 0; k < a->n; k++)
        if (strcmp(a->ov[k].key, b->ov[k].key) || strcmp(a->ov[k].value, b->ov[k].value)) return false;
    return true;
}

/* The index of the reference set ov in B->refs, added if new (lists are built in one key order). */
static uint32_t find_or_add_ref(bench *B, const pg_ov_list *ov, pg_error *err, bool *oom)
{
    for (uint32_t k = 0; k < B->n_refs; k++)
        if (same_ov(&B->refs[k].ov, ov)) return k;
    ref_variant *r = realloc(B->refs, (B->n_refs + 1) * sizeof *r);
    if (!r) {
        *oom = true;
        pg_fail(err, PG_ERR_OOM, "out of memory");
        return 0;
    }
    B->refs = r;
    ref_variant *e = &r[B->n_refs];
    memset(e, 0, sizeof *e);
    e->ov = *ov;
    pg_ov_list_format(ov, e->label, sizeof e->label);
    return B->n_refs++;
}

/* which --set, --pipeline-set and --sweep keys some pipeline (or the reference) declares */
typedef struct key_use {
    bool set[PG_SIDES_MAX_OV], pset[PG_SIDES_MAX_OV], sweep[MAX_SWEEPS];
} key_use;

/* a swept key may not be given with --set or --pipeline-set too */
static pg_result check_sweep_keys(const bench *B, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    for (uint32_t k = 0; k < B->n_sweeps; k++) {
        if (pg_ov_list_get(&ss->set, B->sweeps[k].key))
            return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: the same key is given with --set", B->sweeps[k].key);
        for (uint32_t s = 0; s < ss->pipeline.n; s++)
            if (!strcmp(ss->pipeline.ov[s].key, B->sweeps[k].key))
                return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: the same key is given with %s", B->sweeps[k].key,
                               ss->pipeline.from[s]);
    }
    return PG_OK;
}

/* The reference: its declared parameters decide which --set and swept values it takes; its name,
 * and the sweeps it takes (ref_sweeps). One that does not load is a bad option (PG_ERR_INVALID_ARG:
 * it was recorded in every row's note, with exit 0 and every error column empty). */
static pg_result load_reference(bench *B, pg_pipeline **ref, key_use *use, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    pg_error re = {0};
    if (pg_pipeline_load(B->ref_path, NULL, 0, ref, &re)) {
        *ref = NULL;
        return pg_fail(err, PG_ERR_INVALID_ARG, "--reference: %s", re.msg);
    }
    pg_strlcpy(B->ref_name, (*ref)->name, sizeof B->ref_name);
    pg_result r = pg_sides_check_keys(&ss->reference, *ref, "reference", err);
    if (r) return r;
    for (uint32_t s = 0; s < ss->set.n; s++) use->set[s] |= pg_pipeline_find_param(*ref, ss->set.ov[s].key) != NULL;
    size_t l = 0;
    for (uint32_t k = 0; k < B->n_sweeps; k++)
        if (pg_pipeline_find_param(*ref, B->sweeps[k].key) && !pg_ov_list_get(&ss->reference, B->sweeps[k].key)) {
            l += (size_t)snprintf(B->ref_sweeps + l, l < sizeof B->ref_sweeps ? sizeof B->ref_sweeps - l : 0, "%s%s",
                                  l ? "," : "", B->sweeps[k].key);
            if (l >= sizeof B->ref_sweeps) l = sizeof B->ref_sweeps - 1;
        }
    return PG_OK;
}

/* A loaded pipeline: the keys it declares, its fixed overrides (without the swept values), the
 * sweeps it declares and so its variant count (at most MAX_VARIANTS). */
static pg_result pipeline_sweeps(const bench *B, pipe_entry *pe, const pg_pipeline *pl, key_use *use,
                                 bool declares[MAX_SWEEPS], uint32_t *n_var, pg_ov_list *fixed, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    pg_strlcpy(pe->name, pl->name, sizeof pe->name);
    for (uint32_t s = 0; s < ss->set.n; s++) use->set[s] |= pg_pipeline_find_param(pl, ss->set.ov[s].key) != NULL;
    for (uint32_t s = 0; s < ss->pipeline.n; s++)
        use->pset[s] |= pg_pipeline_find_param(pl, ss->pipeline.ov[s].key) != NULL;
    pg_sides_pipeline(ss, pl, NULL, 0, fixed);
    for (uint32_t k = 0; k < B->n_sweeps; k++)
        if (pg_pipeline_find_param(pl, B->sweeps[k].key)) {
            declares[k] = use->sweep[k] = true;
            *n_var *= B->sweeps[k].n;
            if (*n_var > MAX_VARIANTS)
                return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep: more than %d variants of %s", MAX_VARIANTS, pe->path);
        }
    return PG_OK;
}

/* Variant v of a pipeline (pl NULL when it did not load): its swept values (the last declared
 * sweep varies fastest) and label, its overrides and its reference's; whether it loads. */
static pg_result plan_variant(bench *B, pipe_entry *pe, const pg_pipeline *pl, const pg_pipeline *ref,
                              const bool declares[MAX_SWEEPS], const pg_ov_list *fixed, uint32_t v, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    variant *va = &pe->variants[v];
    pg_ov_list_format(fixed, va->sets_label, sizeof va->sets_label);
    pg_param_override swept[MAX_SWEEPS];
    uint32_t n_swept = 0, rest = v, ll = 0;
    for (uint32_t k = 0; k < B->n_sweeps; k++) {
        if (!declares[k]) continue;
        uint32_t div = 1;
        for (uint32_t k2 = k + 1; k2 < B->n_sweeps; k2++)
            if (declares[k2]) div *= B->sweeps[k2].n;
        const char *val = B->sweeps[k].values[(rest / div) % B->sweeps[k].n];
        swept[n_swept++] = (pg_param_override){B->sweeps[k].key, val};
        ll += (uint32_t)snprintf(va->label + ll, ll < sizeof va->label ? sizeof va->label - ll : 0, "%s%s=%s",
                                 ll ? ";" : "", B->sweeps[k].key, val);
        if (ll >= sizeof va->label) ll = sizeof va->label - 1;
    }
    if (pl) pg_sides_pipeline(ss, pl, swept, n_swept, &va->ov); /* else it is never run */
    pg_ov_list rov;
    pg_sides_reference(ss, ref, swept, n_swept, &rov);
    bool oom = false;
    va->ref = find_or_add_ref(B, &rov, err, &oom);
    if (oom) return PG_ERR_OOM;
    if (!pe->loaded) {
        pg_strlcpy(va->msg, pe->msg, sizeof va->msg);
        return PG_OK;
    }
    pg_error ve = {0};
    pg_pipeline *vp = NULL;
    const pg_result lr = pg_pipeline_load(pe->path, va->ov.ov, va->ov.n, &vp, &ve);
    /* a value the pipeline refuses (out of range, not one of its values) is an option error naming
     * the option that gave it (--set, --pipeline-set, --sweep), as in compare: exit 2 before any run */
    if (lr == PG_ERR_PARAM && pg_sides_check_values(pe->path, &va->ov, "pipeline", err) == PG_ERR_INVALID_ARG)
        return PG_ERR_INVALID_ARG;
    if (lr) {
        pg_strlcpy(va->msg, ve.msg, sizeof va->msg);
    } else {
        va->ok = true;
        pg_pipeline_free(vp);
    }
    return PG_OK;
}

/* pipeline pi's variants (one when it declares no swept key or does not load), numbered from
 * *series on */
static pg_result plan_pipeline(bench *B, uint32_t pi, const pg_pipeline *ref, key_use *use, uint32_t *series,
                               bool *any_loaded, pg_error *err)
{
    pipe_entry *pe = &B->pipes[pi];
    pe->is_reference = same_file(pe->path, B->ref_path);
    pg_pipeline *pl = NULL;
    pg_error le = {0};
    uint32_t n_var = 1;
    bool declares[MAX_SWEEPS] = {0};
    pg_ov_list fixed; /* this pipeline's overrides without the swept values */
    memset(&fixed, 0, sizeof fixed);
    pg_result r = PG_OK;
    if (pg_pipeline_load(pe->path, NULL, 0, &pl, &le)) {
        pg_strlcpy(pe->msg, le.msg, sizeof pe->msg);
    } else {
        pe->loaded = *any_loaded = true;
        if ((r = pipeline_sweeps(B, pe, pl, use, declares, &n_var, &fixed, err))) goto out;
    }
    pe->variants = calloc(n_var, sizeof *pe->variants);
    if (!pe->variants) {
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
        goto out;
    }
    pe->n_variants = n_var;
    for (uint32_t v = 0; v < n_var; v++) {
        pe->variants[v].series = (*series)++;
        if ((r = plan_variant(B, pe, pl, ref, declares, &fixed, v, err))) goto out;
    }
out:
    pg_pipeline_free(pl);
    return r;
}

/* every --set, --pipeline-set and --sweep key is declared by some pipeline (or the reference) */
static pg_result check_keys_used(const bench *B, const key_use *use, pg_error *err)
{
    const pg_side_sets *ss = &B->sides;
    for (uint32_t s = 0; s < ss->set.n; s++)
        if (!use->set[s])
            return pg_fail(err, PG_ERR_INVALID_ARG, "--set %s=%s: no selected pipeline (nor the reference) declares '%s'",
                           ss->set.ov[s].key, ss->set.ov[s].value, ss->set.ov[s].key);
    for (uint32_t s = 0; s < ss->pipeline.n; s++)
        if (!use->pset[s])
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s=%s: no selected pipeline declares '%s'", ss->pipeline.from[s],
                           ss->pipeline.ov[s].key, ss->pipeline.ov[s].value, ss->pipeline.ov[s].key);
    for (uint32_t k = 0; k < B->n_sweeps; k++)
        if (!use->sweep[k])
            return pg_fail(err, PG_ERR_INVALID_ARG, "--sweep %s: no selected pipeline declares '%s'", B->sweeps[k].key,
                           B->sweeps[k].key);
    return PG_OK;
}

/* Loads every pipeline once (names, declared parameters), checks that each --set / --pipeline-set /
 * --sweep key is declared somewhere and each --reference-set key by the reference, builds the
 * variants with what each side gets (sides.h) and checks that each loads. Bad keys, and values
 * the reference refuses, and a reference that does not load, are option errors (exit 2, returned as
 * PG_ERR_INVALID_ARG); a pipeline that does not load is recorded in its rows. */
pg_result pg_bench_plan_variants(bench *B, pg_error *err)
{
    key_use use;
    memset(&use, 0, sizeof use);
    bool any_loaded = false;
    pg_result r = check_sweep_keys(B, err);
    if (r) return r;
    pg_pipeline *ref = NULL;
    if ((r = load_reference(B, &ref, &use, err))) goto done;
    uint32_t series = 0;
    for (uint32_t pi = 0; pi < B->n_pipes; pi++)
        if ((r = plan_pipeline(B, pi, ref, &use, &series, &any_loaded, err))) goto done;
    B->n_series = series;
    if (any_loaded && (r = check_keys_used(B, &use, err))) goto done;
    /* a value the reference refuses is a bad option, not a failure of every row */
    for (uint32_t k = 0; ref && k < B->n_refs; k++)
        if (pg_sides_check_values(B->ref_path, &B->refs[k].ov, "reference", err) == PG_ERR_INVALID_ARG) {
            r = PG_ERR_INVALID_ARG;
            goto done;
        }
    /* the last (pipeline, variant) of a block that needs each reference: it is freed after that row */
    for (uint32_t pi = 0, idx = 0; pi < B->n_pipes; pi++)
        for (uint32_t v = 0; v < B->pipes[pi].n_variants; v++, idx++) B->refs[B->pipes[pi].variants[v].ref].last_use = idx;
done:
    pg_pipeline_free(ref);
    return r;
}

/* The most lights the reference is rendered with at w x h: --reference-max-lights; else on a GPU
 * 1,000,000 and on a CPU device (lavapipe) CPU_REFERENCE_BUDGET / pixels. */
uint32_t ref_limit(const bench *B, uint32_t w, uint32_t h)
{
    if (B->has_ref_max_lights) return B->ref_max_lights;
    if (!B->device_cpu) return GPU_REFERENCE_MAX_LIGHTS;
    double n = floor(CPU_REFERENCE_BUDGET / ((double)w * h));
    return n >= GPU_REFERENCE_MAX_LIGHTS ? GPU_REFERENCE_MAX_LIGHTS : (uint32_t)n;
}

/* Why a row above the limit has no error: the limit, and where it came from (brief: one line that
 * fits a chart panel). */
void ref_skip_note(const bench *B, uint32_t w, uint32_t h, bool brief, char *buf, size_t size)
{
    uint32_t n = ref_limit(B, w, h);
    if (B->has_ref_max_lights)
        snprintf(buf, size, "%s skipped above %u lights (--reference-max-lights %u)", B->ref_name, n, n);
    else if (B->device_cpu && brief)
        snprintf(buf, size, "%s skipped above %u lights on a CPU device: set --reference-max-lights", B->ref_name, n);
    else if (B->device_cpu)
        snprintf(buf, size,
                 "%s skipped above %u lights on a CPU device (%.48s) at %ux%u, the default budget of %.4g light x "
                 "pixel evaluations per reference frame: set --reference-max-lights",
                 B->ref_name, n, B->device, w, h, CPU_REFERENCE_BUDGET);
    else
        snprintf(buf, size, "%s skipped above %u lights (the default on a GPU): set --reference-max-lights", B->ref_name, n);
}
