/* view_pipelines.c - `passgraph view`: the pipeline list (pipelines/ and --pipelines DIR),
 * parameter overrides, opening and (re)loading sessions, and the signature of the files watched
 * for hot reload. */
#include <sys/stat.h>

#include "sides.h"
#include "view.h"

/* Entry i's name in the picker and for --at pipeline=: its file name, or, when an earlier entry
 * has that name (a --pipelines DIR file named like a shipped one), "NAME (FOLDER)": both were
 * shown as "naive.json" and the second could not be picked by name. */
static void name_entry(viewer *v, int i)
{
    const char *path = v->paths[i], *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    bool taken = false;
    for (int k = 0; k < i && !taken; k++) taken = !strcmp(v->names[k], base);
    if (!taken) {
        pg_strlcpy(v->names[i], base, PG_NAME_MAX);
    } else {
        char dir[PG_PATH_MAX];
        pg_strlcpy(dir, path, sizeof dir);
        char *slash = strrchr(dir, '/');
        if (slash) *slash = 0;
        const char *parent = strrchr(dir, '/');
        snprintf(v->names[i], PG_NAME_MAX, "%s (%.*s)", base, 40, slash ? (parent ? parent + 1 : dir) : ".");
    }
    v->name_ptrs[i] = v->names[i];
}

/* ---------------------------------------------------------------- pipelines and parameters */

static int cmp_str(const void *a, const void *b)
{
    return strcmp((const char *)a, (const char *)b);
}

static void scan_dir(viewer *v, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    char found[MAX_PIPELINES][PG_PATH_MAX];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < MAX_PIPELINES) {
        size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".json")) continue;
        snprintf(found[n++], PG_PATH_MAX, "%s/%s", dir, e->d_name);
    }
    closedir(d);
    qsort(found, (size_t)n, PG_PATH_MAX, cmp_str);
    for (int i = 0; i < n && v->n_pipelines < MAX_PIPELINES; i++) {
        bool dup = false;
        for (int k = 0; k < v->n_pipelines; k++) dup |= !strcmp(v->paths[k], found[i]);
        if (dup) continue;
        pg_strlcpy(v->paths[v->n_pipelines], found[i], PG_PATH_MAX);
        name_entry(v, v->n_pipelines);
        v->n_pipelines++;
    }
}

/* each folder under dir (pipelines/examples/NAME/: the user passes written in JSON + GLSL) */
static void scan_subdirs(viewer *v, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    char subs[MAX_PIPELINES][PG_PATH_MAX];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < MAX_PIPELINES) {
        if (e->d_name[0] == '.') continue;
        snprintf(subs[n], PG_PATH_MAX, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(subs[n], &st) == 0 && S_ISDIR(st.st_mode)) n++;
    }
    closedir(d);
    qsort(subs, (size_t)n, PG_PATH_MAX, cmp_str);
    for (int i = 0; i < n; i++) scan_dir(v, subs[i]);
}

/* A pipeline file outside the scanned folders joins the list (the caller checked there is room);
 * its index. */
static int add_elsewhere(viewer *v, const char *path)
{
    pg_strlcpy(v->paths[v->n_pipelines], path, PG_PATH_MAX);
    name_entry(v, v->n_pipelines);
    return v->n_pipelines++;
}

void scan_pipelines(viewer *v, const char *current_path)
{
    v->n_pipelines = 0;
    char dir[PG_PATH_MAX];
    pg_data_path(dir, sizeof dir, "pipelines");
    scan_dir(v, dir);
    pg_data_path(dir, sizeof dir, "pipelines/examples");
    scan_subdirs(v, dir);
    if (v->extra_dir[0]) scan_dir(v, v->extra_dir);
    v->current = -1;
    char want[PG_PATH_MAX], have[PG_PATH_MAX];
    for (int i = 0; current_path && i < v->n_pipelines; i++)
        if (realpath(current_path, want) && realpath(v->paths[i], have) && !strcmp(want, have)) v->current = i;
    if (v->current < 0 && current_path && v->n_pipelines < MAX_PIPELINES) v->current = add_elsewhere(v, current_path);
    if (v->current < 0) v->current = 0;
}

bool declared_by_any(const viewer *v, const char *key)
{
    for (int i = 0; i < v->n_pipelines; i++) {
        pg_pipeline *p = NULL;
        pg_error e;
        if (pg_pipeline_load(v->paths[i], NULL, 0, &p, &e)) continue;
        const bool yes = pg_pipeline_find_param(p, key) != NULL;
        pg_pipeline_free(p);
        if (yes) return true;
    }
    return false;
}

pg_result refused_by(const viewer *v, int k, const char *key, const char *value, pg_error *err)
{
    const pg_param_override ov = {key, value};
    pg_pipeline *p = NULL;
    pg_error e = {0};
    if (k < 0 || k >= v->n_pipelines || pg_pipeline_load(v->paths[k], NULL, 0, &p, &e)) return PG_OK;
    const bool declares = pg_pipeline_find_param(p, key) != NULL;
    pg_pipeline_free(p);
    p = NULL;
    if (!declares) return PG_OK; /* an undeclared key is not applied to it */
    pg_result r = pg_pipeline_load(v->paths[k], &ov, 1, &p, &e);
    pg_pipeline_free(p);
    if (r != PG_ERR_PARAM) return PG_OK;
    *err = e;
    return r;
}

pg_result refused_by_all(const viewer *v, const char *key, const char *value, pg_error *err)
{
    const pg_param_override ov = {key, value};
    pg_result refused = PG_OK;
    for (int i = 0; i < v->n_pipelines; i++) {
        pg_pipeline *p = NULL;
        pg_error e = {0};
        if (pg_pipeline_load(v->paths[i], NULL, 0, &p, &e)) continue;
        const bool declares = pg_pipeline_find_param(p, key) != NULL;
        pg_pipeline_free(p);
        p = NULL;
        if (!declares) continue;
        pg_result r = pg_pipeline_load(v->paths[i], &ov, 1, &p, &e);
        pg_pipeline_free(p);
        if (r != PG_ERR_PARAM) return PG_OK; /* one takes it (a debug view only some have) */
        if (!refused) *err = e;
        refused = r;
    }
    return refused;
}

pg_result check_set_values(const viewer *v, const pg_cli_common *opt, pg_error *err)
{
    pg_side_sets sides;
    memset(&sides, 0, sizeof sides);
    if (!pg_sides_from_common(&sides, opt)) return pg_fail(err, PG_ERR_INVALID_ARG, "too many --set values");
    for (uint32_t k = 0; k < sides.set.n + sides.pipeline.n; k++) { /* each value on its own */
        pg_side_sets one;
        memset(&one, 0, sizeof one);
        const bool set = k < sides.set.n;
        const pg_ov_list *from = set ? &sides.set : &sides.pipeline;
        const uint32_t j = set ? k : k - sides.set.n;
        pg_ov_list_put(set ? &one.set : &one.pipeline, from->ov[j].key, from->ov[j].value, from->from[j]);
        bool taken = false;
        pg_error first = {0};
        for (int i = 0; i < v->n_pipelines && !taken; i++) {
            pg_pipeline *p = NULL;
            pg_error e;
            if (pg_pipeline_load(v->paths[i], NULL, 0, &p, &e)) continue; /* reported where it is opened */
            pg_ov_list l;
            pg_sides_pipeline(&one, p, NULL, 0, &l); /* empty when it does not declare the key */
            pg_pipeline_free(p);
            if (l.n == 0) continue;
            pg_error e1 = {0};
            if (pg_sides_check_values(v->paths[i], &l, "pipeline", &e1) != PG_ERR_INVALID_ARG) taken = true;
            else if (!first.msg[0]) first = e1;
        }
        /* refused only when no pipeline that declares the key takes it (the debug views differ:
         * naive has no cluster_heat, forward+ has) */
        if (!taken && first.msg[0]) {
            *err = first;
            return PG_ERR_INVALID_ARG;
        }
    }
    return PG_OK;
}

pg_result find_pipeline(viewer *v, const char *arg, int *index, pg_error *err)
{
    char want[PG_PATH_MAX], have[PG_PATH_MAX];
    const bool is_file = realpath(arg, want) != NULL;
    for (int i = 0; i < v->n_pipelines; i++)
        if (!strcmp(v->names[i], arg) || (is_file && realpath(v->paths[i], have) && !strcmp(want, have))) {
            *index = i;
            return PG_OK;
        }
    struct stat st;
    if (!is_file || stat(want, &st) != 0 || !S_ISREG(st.st_mode))
        return pg_fail(err, PG_ERR_IO, "%s: neither a file nor one of the viewer's %d pipelines (%s, ...)", arg,
                       v->n_pipelines, v->n_pipelines ? v->names[0] : "none");
    if (v->n_pipelines >= MAX_PIPELINES)
        return pg_fail(err, PG_ERR_LIMIT, "%s: the viewer lists %d pipelines already", arg, MAX_PIPELINES);
    *index = add_elsewhere(v, arg);
    return PG_OK;
}

void set_override(viewer *v, const char *key, const char *value)
{
    for (int i = 0; i < v->n_ov; i++)
        if (!strcmp(v->ov_key[i], key)) {
            pg_strlcpy(v->ov_val[i], value, PG_NAME_MAX);
            return;
        }
    if (v->n_ov >= MAX_OVERRIDES) return;
    pg_strlcpy(v->ov_key[v->n_ov], key, PG_NAME_MAX);
    pg_strlcpy(v->ov_val[v->n_ov], value, PG_NAME_MAX);
    v->n_ov++;
}

/* Creates a session for path with the overrides the pipeline declares. */
pg_result open_session(viewer *v, const char *path, bool with_overrides, pg_session **out, pg_error *err)
{
    pg_param_override ov[MAX_OVERRIDES];
    uint32_t n = 0;
    if (with_overrides) {
        pg_pipeline *probe = NULL;
        pg_result r = pg_pipeline_load(path, NULL, 0, &probe, err);
        if (r) return r;
        for (int i = 0; i < v->n_ov; i++)
            if (pg_pipeline_find_param(probe, v->ov_key[i])) ov[n++] = (pg_param_override){v->ov_key[i], v->ov_val[i]};
        pg_pipeline_free(probe);
    }
    pg_session_desc sd = {
        .pipeline_path = path,
        .overrides = ov,
        .n_overrides = n,
        .registry = &v->app.registry,
        .disable_aliasing = v->app.opt.no_aliasing,
        .immediate = v->app.opt.immediate,
        .async_off = v->app.opt.async_compute == PG_ASYNC_OFF,
        .output_stages = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT,
        .settings = v->settings,
        .n_settings = v->n_settings,
    };
    pg_result r = pg_app_session_create(&v->app, &sd, out, err);
    /* the displayed graph keeps two frames in flight; the reference of the diff view reads back */
    if (!r && with_overrides && (r = pg_session_set_frames_in_flight(*out, v->frames_in_flight, err))) {
        pg_session_destroy(*out);
        *out = NULL;
    }
    return r;
}

/* The running session has the viewer's current application settings. */
static bool same_settings(const viewer *v, const pg_session *s)
{
    if (s->desc.n_settings != v->n_settings) return false;
    for (uint32_t i = 0; i < v->n_settings; i++)
        if (strcmp(s->desc.settings[i].key, v->settings[i].key) || strcmp(s->desc.settings[i].value, v->settings[i].value))
            return false;
    return true;
}

/* Reloads the running session in place (pg_session_reload: the runtime re-creates only what the
 * new plan needs, nothing for a run-time option such as exposure or ambient). */
static pg_result reload_in_place(viewer *v, const char *path, pg_error *err)
{
    pg_param_override ov[MAX_OVERRIDES];
    uint32_t n = 0;
    pg_pipeline *probe = NULL;
    pg_result r = pg_pipeline_load(path, NULL, 0, &probe, err);
    if (r) return r;
    for (int i = 0; i < v->n_ov; i++)
        if (pg_pipeline_find_param(probe, v->ov_key[i])) ov[n++] = (pg_param_override){v->ov_key[i], v->ov_val[i]};
    pg_pipeline_free(probe);
    if ((r = pg_plugins_load_listed(&v->app.registry, path, &v->app.plugins, err))) return r;
    return pg_session_reload(v->session, path, ov, n, err);
}

/* Loads the requested pipeline; on failure keeps the running one and shows the error. */
void reload(viewer *v)
{
    v->reload = false;
    pg_error err = {0};
    pg_session *s = NULL;
    int idx = v->requested;
    if (idx < 0 || idx >= v->n_pipelines) idx = v->current;
    if (v->session && same_settings(v, v->session)) {
        if (reload_in_place(v, v->paths[idx], &err)) {
            snprintf(v->error, sizeof v->error, "%s", err.msg);
            fprintf(stderr, "passgraph view: %s\n", err.msg);
            v->requested = v->current;
            return;
        }
        if (idx != v->current) v->hist_n = 0;
        v->current = idx;
        v->requested = idx;
        v->cycle_tried[0] = 0;
        v->error[0] = 0;
        v->reloads++;
        v->watch_sig = watch_signature(v); /* the new pipeline's files: their folders, as they are now */
        return;
    }
    if (open_session(v, v->paths[idx], true, &s, &err) == PG_OK) {
        /* compile now so a bad combination shows here and the old graph keeps running */
        pg_frame_info fi = pg_app_frame(&v->app);
        if (pg_session_compile(s, (uint32_t)v->light_count, v->win.extent.width, v->win.extent.height, &err)) {
            pg_session_destroy(s);
            s = NULL;
            (void)fi;
        }
    }
    if (!s) {
        snprintf(v->error, sizeof v->error, "%s", err.msg);
        fprintf(stderr, "passgraph view: %s\n", err.msg);
        v->requested = v->current;
        return;
    }
    pg_session_destroy(v->session);
    v->session = s;
    v->current = idx;
    v->requested = idx;
    v->cycle_tried[0] = 0; /* loaded: the cycle goes on from here */
    v->error[0] = 0;
    v->hist_n = 0;
    v->reloads++;
    v->watch_sig = watch_signature(v);
}

/* The modification times and sizes of the regular files in dir, summed. */
static double dir_signature(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    double sig = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char p[PG_PATH_MAX * 2];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(p, &st) == 0 && S_ISREG(st.st_mode))
            sig += (double)st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9 + (double)st.st_size * 1e-3;
    }
    closedir(d);
    return sig;
}

/* Sum of the modification times of everything a pipeline or shader edit touches: the data
 * folder's pipelines, fragments and shaders, --pipelines DIR, and the folder of every listed
 * pipeline (a user pass's GLSL lives next to its pipeline file: pipelines/examples/NAME/). */
double watch_signature(const viewer *v)
{
    char dirs[4 + MAX_PIPELINES + PG_MAX_SOURCE_DIRS][PG_PATH_MAX];
    int n = 0;
    pg_data_path(dirs[n++], PG_PATH_MAX, "pipelines");
    pg_data_path(dirs[n++], PG_PATH_MAX, "pipelines/fragments");
    pg_data_path(dirs[n++], PG_PATH_MAX, "shaders");
    if (v->extra_dir[0]) pg_strlcpy(dirs[n++], v->extra_dir, PG_PATH_MAX);
    for (int i = 0; i < v->n_pipelines + PG_MAX_SOURCE_DIRS; i++) {
        /* the listed pipelines' folders, then those of every file the running pipeline was read
         * from (a fragment included from elsewhere: its edit did not reload) */
        char dir[PG_PATH_MAX];
        if (i < v->n_pipelines) {
            pg_strlcpy(dir, v->paths[i], sizeof dir);
            char *slash = strrchr(dir, '/');
            if (slash) *slash = 0;
            else pg_strlcpy(dir, ".", sizeof dir);
        } else {
            const pg_pipeline *pl = v->session ? v->session->pipeline : NULL;
            const uint32_t k = (uint32_t)(i - v->n_pipelines);
            if (!pl || k >= pl->n_source_dirs) continue;
            pg_strlcpy(dir, pl->source_dirs[k], sizeof dir);
        }
        bool seen = false;
        for (int k = 0; k < n && !seen; k++) seen = !strcmp(dirs[k], dir);
        if (!seen) pg_strlcpy(dirs[n++], dir, PG_PATH_MAX);
    }
    double sig = 0;
    for (int i = 0; i < n; i++) sig += dir_signature(dirs[i]);
    return sig;
}
