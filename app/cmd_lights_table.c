/* cmd_lights_table.c - `passgraph lights-table`: writes a glTF that is the input scene plus N
 * point lights stored in the file: the generated lights of the scene's default set-up (or a
 * scenario's) at --time, as a binary PASSGRAPH_lights_table (default) or as KHR_lights_punctual
 * JSON (--json, for small counts and for comparing the two forms). docs/scenes.md describes the
 * extension. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "app.h"
#include "commands.h"
#include "pg_file.h"

static const char *const lights_table_help =
    "usage: passgraph lights-table --scene IN.gltf --out OUT.gltf [--lights N] [--scenario FILE]\n"
    "                              [--seed S] [--time T] [--radius R] [--intensity I] [--json]\n"
    "                              [--gltf-scene N]\n"
    "Writes OUT.gltf: the glTF IN.gltf (a .gltf file; its buffers and images are referenced, not\n"
    "copied) plus N point lights stored in the file: the lights passgraph would generate for the\n"
    "scene (its default light set-up, a scenario's over it, --radius / --intensity over that) at\n"
    "--time T, frozen. Default: a binary table (extension PASSGRAPH_lights_table, 32 bytes a light,\n"
    "in OUT.lights.bin beside OUT.gltf); --json: KHR_lights_punctual lights and one node each.\n"
    "A light's file colour is its generated colour without the intensity, its intensity (candela)\n"
    "pi times the generated intensity and its range the generated radius, so it is as bright as the\n"
    "generated light (the file's falloff is the extension's: the window squared).\n"
    "With --json the lights join scene N (--gltf-scene N) or the file's default scene. Refused: an\n"
    "input that already holds a table (without --json), an output that is the input or one of its\n"
    "buffers, lights past a file light's limits (intensity or range over 1e30).\n"
    "Exit 0 on success, 1 on a failure (reading, writing), 2 on bad options.\n";

/* the text of a file (NUL-terminated), NULL with a message on failure */
static char *read_text(const char *path, pg_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        pg_fail(err, PG_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 65536 + 1 > cap) {
            cap = cap ? cap * 2 : 65536 * 2;
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(f);
                pg_fail(err, PG_ERR_OOM, "%s: out of memory", path);
                return NULL;
            }
            buf = nb;
        }
        size_t got = fread(buf + n, 1, 65536, f);
        n += got;
        if (got < 65536) break;
    }
    fclose(f);
    buf[n] = 0;
    return buf;
}

/* the directory part of a path ("." when none), canonical */
static bool dir_of(const char *path, char out[PATH_MAX])
{
    char d[PG_PATH_MAX];
    pg_strlcpy(d, path, sizeof d);
    char *slash = strrchr(d, '/');
    if (!slash) pg_strlcpy(d, ".", sizeof d);
    else if (slash == d) d[1] = 0;
    else *slash = 0;
    return realpath(d, out) != NULL;
}

/* uri (relative to from_dir) rewritten relative to to_dir; both canonical directories */
static void rebase_uri(const char *uri, const char *from_dir, const char *to_dir, char *out, size_t size)
{
    char abs[PATH_MAX * 2];
    snprintf(abs, sizeof abs, "%s/%s", from_dir, uri);
    size_t common = 0, i = 0;
    for (; from_dir[i] && to_dir[i] && from_dir[i] == to_dir[i]; i++)
        if (from_dir[i] == '/') common = i;
    if (!to_dir[i] && (from_dir[i] == '/' || !from_dir[i])) common = i; /* to_dir is a prefix */
    if (!from_dir[i] && !to_dir[i]) common = i;
    out[0] = 0;
    for (const char *p = to_dir + common; *p; p++)
        if (*p == '/') strncat(out, "../", size - strlen(out) - 1);
    const char *rest = abs + common + (abs[common] == '/' ? 1 : 0);
    strncat(out, rest, size - strlen(out) - 1);
}

static bool is_relative_file_uri(const char *u)
{
    return u && u[0] && u[0] != '/' && strncmp(u, "data:", 5) != 0 && !strstr(u, "://");
}

/* every relative uri of buffers[] and images[] made relative to the output's directory */
static void rebase_all(cJSON *root, const char *in_dir, const char *out_dir)
{
    if (!strcmp(in_dir, out_dir)) return;
    const char *arrays[2] = {"buffers", "images"};
    for (int a = 0; a < 2; a++) {
        cJSON *arr = cJSON_GetObjectItemCaseSensitive(root, arrays[a]), *it;
        cJSON_ArrayForEach(it, arr)
        {
            cJSON *u = cJSON_GetObjectItemCaseSensitive(it, "uri");
            if (!cJSON_IsString(u) || !is_relative_file_uri(u->valuestring)) continue;
            char nu[PATH_MAX * 2];
            rebase_uri(u->valuestring, in_dir, out_dir, nu, sizeof nu);
            cJSON_SetValuestring(u, nu);
        }
    }
}

static cJSON *array_of(cJSON *root, const char *key)
{
    cJSON *a = cJSON_GetObjectItemCaseSensitive(root, key);
    if (!cJSON_IsArray(a)) {
        cJSON_DeleteItemFromObjectCaseSensitive(root, key);
        a = cJSON_AddArrayToObject(root, key);
    }
    return a;
}

static void use_extension(cJSON *root, const char *name)
{
    cJSON *used = array_of(root, "extensionsUsed"), *it;
    cJSON_ArrayForEach(it, used) if (cJSON_IsString(it) && !strcmp(it->valuestring, name)) return;
    cJSON_AddItemToArray(used, cJSON_CreateString(name));
}

static cJSON *object_of(cJSON *root, const char *key)
{
    cJSON *o = cJSON_GetObjectItemCaseSensitive(root, key);
    if (!cJSON_IsObject(o)) {
        cJSON_DeleteItemFromObjectCaseSensitive(root, key);
        o = cJSON_AddObjectToObject(root, key);
    }
    return o;
}

/* the binary form: OUT.lights.bin and the extension pointing at a new bufferView */
/* OUT.lights.bin beside OUT.gltf */
static void lights_bin_path(const char *out_path, char *bin, size_t size)
{
    snprintf(bin, size, "%s", out_path);
    char *dot = strrchr(bin, '.');
    if (dot && !strchr(dot, '/')) *dot = 0;
    strncat(bin, ".lights.bin", size - strlen(bin) - 1);
}

static pg_result add_table(cJSON *root, const char *out_path, const float *rec, uint32_t n, pg_error *err)
{
    char bin[PG_PATH_MAX + 16];
    lights_bin_path(out_path, bin, sizeof bin);
    FILE *f = fopen(bin, "wb");
    if (!f) return pg_fail(err, PG_ERR_IO, "%s: cannot write: %s", bin, strerror(errno));
    size_t bytes = (size_t)n * 32;
    bool ok = fwrite(rec, 1, bytes, f) == bytes;
    ok = fclose(f) == 0 && ok;
    if (!ok) return pg_fail(err, PG_ERR_IO, "%s: write failed", bin);
    const char *base = strrchr(bin, '/');
    base = base ? base + 1 : bin;
    cJSON *buffers = array_of(root, "buffers"), *views = array_of(root, "bufferViews");
    cJSON *b = cJSON_CreateObject();
    cJSON_AddStringToObject(b, "uri", base);
    cJSON_AddNumberToObject(b, "byteLength", (double)bytes);
    cJSON_AddItemToArray(buffers, b);
    cJSON *v = cJSON_CreateObject();
    cJSON_AddNumberToObject(v, "buffer", cJSON_GetArraySize(buffers) - 1);
    cJSON_AddNumberToObject(v, "byteLength", (double)bytes);
    cJSON_AddItemToArray(views, v);
    cJSON *t = cJSON_CreateObject();
    cJSON_AddNumberToObject(t, "bufferView", cJSON_GetArraySize(views) - 1);
    cJSON_AddNumberToObject(t, "count", n);
    cJSON_AddItemToObject(object_of(root, "extensions"), "PASSGRAPH_lights_table", t);
    use_extension(root, "PASSGRAPH_lights_table");
    return PG_OK;
}

/* the JSON form: KHR_lights_punctual lights, a node each, added to the drawn scene (gltf_scene
 * >= 0: that one, as --gltf-scene draws it; else the file's default) */
static void add_json(cJSON *root, const float *rec, uint32_t n, int gltf_scene)
{
    cJSON *ext = object_of(object_of(root, "extensions"), "KHR_lights_punctual");
    cJSON *lights = array_of(ext, "lights"), *nodes = array_of(root, "nodes");
    int first_light = cJSON_GetArraySize(lights), first_node = cJSON_GetArraySize(nodes);
    cJSON *scenes = cJSON_GetObjectItemCaseSensitive(root, "scenes");
    cJSON *sc = cJSON_GetObjectItemCaseSensitive(root, "scene");
    int si = gltf_scene >= 0 ? gltf_scene : cJSON_IsNumber(sc) ? sc->valueint : 0;
    cJSON *scene = cJSON_IsArray(scenes) ? cJSON_GetArrayItem(scenes, si) : NULL;
    cJSON *scene_nodes = scene ? array_of(scene, "nodes") : NULL;
    for (uint32_t i = 0; i < n; i++) {
        const float *r = rec + (size_t)i * 8;
        cJSON *l = cJSON_CreateObject();
        cJSON_AddStringToObject(l, "type", "point");
        cJSON_AddItemToObject(l, "color", cJSON_CreateFloatArray(r + 4, 3));
        cJSON_AddNumberToObject(l, "intensity", r[7]);
        if (r[3] > 0) cJSON_AddNumberToObject(l, "range", r[3]);
        cJSON_AddItemToArray(lights, l);
        cJSON *nd = cJSON_CreateObject();
        cJSON_AddItemToObject(nd, "translation", cJSON_CreateFloatArray(r, 3));
        cJSON *ne = cJSON_AddObjectToObject(cJSON_AddObjectToObject(nd, "extensions"), "KHR_lights_punctual");
        cJSON_AddNumberToObject(ne, "light", first_light + (int)i);
        cJSON_AddItemToArray(nodes, nd);
        if (scene_nodes) cJSON_AddItemToArray(scene_nodes, cJSON_CreateNumber(first_node + (int)i));
    }
    use_extension(root, "KHR_lights_punctual");
}

static int fail1(const char *msg)
{
    fprintf(stderr, "passgraph lights-table: %s\n", msg);
    return 1;
}

/* Why the records cannot go into a file passgraph reads back (a light's intensity, range or
 * position past the limits of file lights), or NULL. */
static const char *records_refused(const float *rec, uint32_t n, char *why, size_t size)
{
    for (uint32_t i = 0; i < n; i++) {
        const float *r = rec + (size_t)i * 8;
        if (!(r[7] <= (float)PG_LIGHT_MAX_CANDELA)) {
            snprintf(why, size, "light %u: intensity %g candela (pi x the generated intensity), over the %g a file "
                     "light may have: lower --intensity or the scenario's lights.intensity", i, (double)r[7],
                     PG_LIGHT_MAX_CANDELA);
            return why;
        }
        if (!(r[3] <= (float)PG_LIGHT_MAX_CANDELA)) {
            snprintf(why, size, "light %u: range %g, over the %g a file light may have", i, (double)r[3],
                     PG_LIGHT_MAX_CANDELA);
            return why;
        }
        if (!isfinite(r[0]) || !isfinite(r[1]) || !isfinite(r[2])) {
            snprintf(why, size, "light %u: position (%g, %g, %g) is not finite", i, (double)r[0], (double)r[1], (double)r[2]);
            return why;
        }
    }
    return NULL;
}

/* The output would replace a file the input is made of (the input itself, or a buffer it
 * references: the old .lights.bin when writing in place): the message, or NULL. */
static const char *overwrites_input(const cJSON *root, const char *in_path, const char *out_path, const char *in_dir,
                                    char *why, size_t size)
{
    char bin[PG_PATH_MAX + 16], a[PATH_MAX], b[PATH_MAX];
    lights_bin_path(out_path, bin, sizeof bin);
    const char *outs[2] = {out_path, bin};
    for (int k = 0; k < 2; k++) {
        if (!realpath(outs[k], b)) continue; /* does not exist yet */
        if (realpath(in_path, a) && !strcmp(a, b)) {
            snprintf(why, size, "%s is the input file: write the output to another file", outs[k]);
            return why;
        }
        const cJSON *buffers = cJSON_GetObjectItemCaseSensitive(root, "buffers"), *buf;
        cJSON_ArrayForEach(buf, buffers)
        {
            const cJSON *uri = cJSON_GetObjectItemCaseSensitive(buf, "uri");
            if (!cJSON_IsString(uri) || !is_relative_file_uri(uri->valuestring)) continue;
            char p[PATH_MAX + PG_PATH_MAX];
            snprintf(p, sizeof p, "%s/%s", in_dir, uri->valuestring);
            if (realpath(p, a) && !strcmp(a, b)) {
                snprintf(why, size, "%s is a buffer of the input ('%s'): write the output to another file", outs[k],
                         uri->valuestring);
                return why;
            }
        }
    }
    return NULL;
}

/* What would make the output wrong, before anything is written: the input already holding a table
 * (a second one would replace it: its lights were lost), an output that replaces a file of the
 * input (writing in place left a file whose buffer no longer matched), lights a file cannot hold.
 * 0 to go on, else the exit status (said on stderr). */
static int check_output(const cJSON *root, const pg_cli_common *opt, bool json, const float *rec, uint32_t n,
                        const char *in_dir)
{
    char why[PG_PATH_MAX + 256];
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(root, "extensions");
    const cJSON *table = cJSON_GetObjectItemCaseSensitive(ext, "PASSGRAPH_lights_table");
    if (table && !json) {
        snprintf(why, sizeof why, "%s already holds a PASSGRAPH_lights_table: a file has one table (write from a "
                 "file without one, or add these lights as KHR_lights_punctual with --json)", opt->scene);
        return fail1(why);
    }
    if (overwrites_input(root, opt->scene, opt->out, in_dir, why, sizeof why) ||
        records_refused(rec, n, why, sizeof why)) {
        fprintf(stderr, "passgraph lights-table: %s\n", why);
        return 2;
    }
    return 0;
}

/* the records (8 floats a light) of the app's generated lights at time t */
static float *records(const pg_app *app, float t, uint32_t n)
{
    float *rec = malloc((size_t)(n ? n : 1) * 8 * sizeof(float));
    if (!rec) return NULL;
    pg_light_setup s = app->lights;
    float k = s.intensity, unit = 1.0f;
    s.intensity = unit; /* colours without the intensity: the file's intensity carries it */
    for (uint32_t i = 0; i < n; i++) {
        float *r = rec + (size_t)i * 8;
        pg_light_setup_generate(&s, t, i, r, r + 4);
        r[3] = s.radius;
        r[7] = k * 3.14159265358979f; /* colour x intensity / pi on the GPU: the generated colour */
    }
    return rec;
}

int pg_cmd_lights_table(int argc, char **argv)
{
    pg_cli_common opt;
    pg_cli_defaults(&opt);
    opt.quiet = true;
    bool json = false;
    pg_error err = {0};
    for (int i = 0; i < argc; i++) {
        bool used;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(lights_table_help, stdout);
            return 0;
        }
        if (!strcmp(argv[i], "--json")) {
            json = true;
            continue;
        }
        if (pg_cli_parse_common(&opt, argc, argv, &i, &used, &err)) {
            fprintf(stderr, "passgraph lights-table: %s\n", err.msg);
            return 2;
        }
        if (!used) {
            fprintf(stderr, "passgraph lights-table: unknown option '%s' (see passgraph lights-table --help)\n",
                    argv[i]);
            return 2;
        }
    }
    if (!opt.out || !opt.scene || !strcmp(opt.scene, "default")) {
        fprintf(stderr, "passgraph lights-table: --scene IN.gltf and --out OUT.gltf are required\n");
        return 2;
    }
    size_t sl = strlen(opt.scene), ol = strlen(opt.out);
    if (sl < 5 || strcmp(opt.scene + sl - 5, ".gltf") || ol < 5 || strcmp(opt.out + ol - 5, ".gltf")) {
        fprintf(stderr, "passgraph lights-table: --scene and --out must be .gltf files (a .glb is not rewritten)\n");
        return 2;
    }
    if (ol >= PG_PATH_MAX) { /* OUT.lights.bin beside it was cut to a prefix of OUT, and written */
        fprintf(stderr, "passgraph lights-table: --out: path longer than %d bytes\n", PG_PATH_MAX - 1);
        return 2;
    }
    if (pg_file_check_writable(opt.out, "--out", &err)) { /* before any file is written */
        fprintf(stderr, "passgraph lights-table: %s\n", err.msg);
        return 2;
    }
    pg_app app;
    memset(&app, 0, sizeof app);
    if (pg_app_open(&app, &opt, false, &err)) return fail1(err.msg);
    uint32_t n = app.lights.count - app.lights.file_count;
    const char *refuse = n == 0 ? "no light to write (--lights 0, or a scenario's count of 0): a table holds at least one"
                         : !(app.lights.radius > 0)
                             ? "a radius of 0 (--radius or the scenario's): generated lights of radius 0 add no light, and "
                               "in the file a range of 0 means none, infinite reach: give a radius > 0"
                             : NULL;
    if (refuse) {
        fprintf(stderr, "passgraph lights-table: %s\n", refuse);
        pg_app_close(&app);
        return 2;
    }
    float *rec = records(&app, opt.time, n);
    char *text = rec ? read_text(opt.scene, &err) : NULL;
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    char in_dir[PATH_MAX], out_dir[PATH_MAX];
    int rc = 0;
    if (!rec) rc = fail1("out of memory");
    else if (!text) rc = fail1(err.msg);
    else if (!root) {
        snprintf(err.msg, sizeof err.msg, "%s: JSON syntax error", opt.scene);
        rc = fail1(err.msg);
    } else if (!dir_of(opt.scene, in_dir) || !dir_of(opt.out, out_dir)) {
        snprintf(err.msg, sizeof err.msg, "%s: the folder of the input or output does not exist", opt.out);
        rc = fail1(err.msg);
    } else if ((rc = check_output(root, &opt, json, rec, n, in_dir)) != 0) {
        /* said */
    } else {
        rebase_all(root, in_dir, out_dir);
        if (json) add_json(root, rec, n, opt.gltf_scene);
        else if (add_table(root, opt.out, rec, n, &err)) rc = fail1(err.msg);
        char *out = rc ? NULL : cJSON_PrintUnformatted(root);
        FILE *f = out ? fopen(opt.out, "wb") : NULL;
        bool wrote = f && fputs(out, f) >= 0;
        if (f && fclose(f) != 0) wrote = false;
        if (!rc && !wrote) {
            snprintf(err.msg, sizeof err.msg, "%s: cannot write: %s", opt.out, strerror(errno));
            rc = fail1(err.msg);
        } else if (!rc) {
            printf("lights-table: %u point lights of %s (%s) -> %s\n", n, opt.scene,
                   json ? "KHR_lights_punctual JSON" : "PASSGRAPH_lights_table", opt.out);
        }
        free(out);
    }
    cJSON_Delete(root);
    free(text);
    free(rec);
    pg_app_close(&app);
    return rc;
}
