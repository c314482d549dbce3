#include "cli.h"
#include "pg_cache.h"

#include "ocio.h"
#include "pipeline_paths.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const pg_cli_common_help =
    "  --pipeline FILE      pipeline JSON (default: pipelines/naive.json in the data folder)\n"
    "  --include-dir DIR    a folder the pipeline's includes may come from, besides the\n"
    "                       including file's folder and the data folder (repeatable)\n"
    "  --scene FILE|default glTF 2.0 scene (.gltf/.glb) or the built-in atrium (default)\n"
    "  --gltf-scene N       the glTF scene (scenes[N]) to draw (default: the file's `scene`,\n"
    "                       else scenes[0]); a line says so when a file has several\n"
    "  --variant N|NAME     the glTF material variant to draw (KHR_materials_variants: index or\n"
    "                       name; default: each primitive's own material); a line lists them\n"
    "  --scenario FILE      JSON set-up: camera, light box, count, radius, intensity, motion\n"
    "                       (e.g. assets/scenarios/cis565.json); explicit options override it\n"
    "  --camera N|NAME|auto a glTF camera (index among the scene's camera nodes, camera or node\n"
    "                       name) or auto (frame the bounds); default: the file's first camera,\n"
    "                       else auto (glTF), the interior view (--scene default); a scenario's\n"
    "                       camera fields still apply over it\n"
    "  --lights N           number of point lights, 0..16777216 (default 256)\n"
    "  --radius R           light range in scene units (default: from the scene size)\n"
    "  --intensity I        light colour multiplier (default 1)\n"
    "  --ambient A          constant light times albedo, added to the pipeline's ambient\n"
    "                       (default: 0.02 for a glTF object, 0 for the atrium)\n"
    "  --environment E      environment light: FILE.hdr (Radiance) or FILE.exr (OpenEXR), an\n"
    "                       equirectangular 2:1 image; default\n"
    "                       (the neutral sky) or none; default: the neutral sky for a glTF file\n"
    "                       without lights (and no scenario), none otherwise\n"
    "  --environment-intensity X  its radiance scale, 0..1e6 (default 1; a run-time value)\n"
    "  --environment-rotation D   its rotation about +Y in degrees (default 0; a run-time value)\n"
    "  --size WxH           output size, 1..16384 each (default 640x360)\n"
    "  --time T             animation time in seconds, |T| <= 1e5; fixes the frame (default 0): the\n"
    "                       glTF file's animation (looping) and the generated lights' motion\n"
    "  --animation A        the glTF animation played: N, NAME, all or none (the rest pose);\n"
    "                       default: the first\n"
    "  --seed S             light seed, 0..4294967295 (default 1)\n"
    "  --set KEY=VALUE      override a pipeline parameter (repeatable)\n"
    "  --plugin FILE.so     load pass types from a plug-in (repeatable; docs/plugins.md)\n"
    "  --device N|NAME      Vulkan device index or name substring ('passgraph devices')\n"
    "  --validation         enable the Khronos validation layer + synchronization validation;\n"
    "                       any message makes the command fail\n"
    "  --require-exact      fail (exit 1) when a frame dropped light references (a light\n"
    "                       list past its budget or max_lights): the image is not exact\n"
    "  --no-aliasing        give every transient its own memory (debugging switch)\n"
    "  --no-shader-cache    compile every shader with glslang and use no pipeline cache (also\n"
    "                       PASSGRAPH_NO_SHADER_CACHE=1); caches live in $PASSGRAPH_CACHE_DIR,\n"
    "                       else $XDG_CACHE_HOME/passgraph, else ~/.cache/passgraph\n"
    "  --immediate          debugging mode: passes in declaration order, no aliasing, a full\n"
    "                       barrier (all commands, all memory) before every pass\n"
    "  --async-compute MODE on: run compute passes whose inputs come from no raster pass on a\n"
    "                       second queue (default when the device has one); off: one queue;\n"
    "                       emulate: the two-queue plan on the one graphics queue (test switch)\n"
    "  --explain            print what the compiled graph left out, culled and why\n"
    "  --frames N           frames to render; timings are the median (default 1)\n"
    "  --view NAME          an OCIO view of the display (e.g. \"Standard\", \"Filmic (ACES)\", \"Raw\")\n"
    "                       or else a debug view (the pipeline's 'view' parameter; --debug-view)\n"
    "  --debug-view NAME    debug view instead of lighting: cluster_heat, cluster_x, cluster_y,\n"
    "                       cluster_z, overflow (clustered pipelines), albedo, normal, depth (all)\n"
    "  --ocio-config FILE   OpenColorIO config (default: $OCIO, else assets/ocio/config.ocio)\n"
    "  --display NAME       OCIO display (default: the config's; shipped: sRGB, Rec.1886)\n"
    "  --ocio-view NAME     OCIO view of the display (default: the config's; shipped: Standard,\n"
    "                       Filmic (ACES), Raw); exposure: --set exposure=X (scene-linear multiply)\n";

void pg_cli_defaults(pg_cli_common *c)
{
    memset(c, 0, sizeof *c);
    c->scene = "default";
    c->gltf_scene = -1;
    c->lights = 256;
    c->width = 640;
    c->height = 360;
    c->seed = 1;
    c->env_intensity = 1.0f;
    c->device_index = -1;
    c->frames = 1;
}

pg_result pg_cli_parse_u64(const char *opt, const char *s, uint64_t min, uint64_t max, uint64_t *out, pg_error *err)
{
    if (!s || !*s) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    const char *p = s;
    if (*p == '+') p++;
    if (*p < '0' || *p > '9')
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [%llu, %llu]", opt, s,
                       (unsigned long long)min, (unsigned long long)max);
    errno = 0;
    char *end;
    unsigned long long v = strtoull(p, &end, 10);
    if (errno || *end || v < min || v > max)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a whole number in [%llu, %llu]", opt, s,
                       (unsigned long long)min, (unsigned long long)max);
    *out = v;
    return PG_OK;
}

static pg_result parse_float(const char *opt, const char *s, double min, double max, float *out, pg_error *err)
{
    if (!s || !*s) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", opt);
    errno = 0;
    char *end;
    double v = strtod(s, &end);
    if (errno || *end || !isfinite(v) || v < min || v > max)
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s %s: expected a finite number in [%g, %g]", opt, s, min, max);
    *out = (float)v;
    return PG_OK;
}

/* The last value given to opt anywhere on the command line (NULL if none): the colour options
 * are checked against the config and display the whole command line selects. */
static const char *prescan(int argc, char **argv, const char *opt)
{
    const char *v = NULL;
    for (int k = 0; k + 1 < argc; k++)
        if (!strcmp(argv[k], opt)) v = argv[k + 1];
    return v;
}

static pg_result open_config(int argc, char **argv, pg_ocio_config **cfg, pg_error *err)
{
    char path[PG_PATH_MAX];
    pg_ocio_resolve_path(prescan(argc, argv, "--ocio-config"), path, sizeof path);
    return pg_ocio_open(path, cfg, err);
}

static void rebuild_settings(pg_cli_common *c)
{
    c->n_settings = 0;
    if (c->ocio_config) c->settings[c->n_settings++] = (pg_param_override){"ocio.config", c->ocio_config};
    if (c->display) c->settings[c->n_settings++] = (pg_param_override){"ocio.display", c->display};
    if (c->ocio_view) c->settings[c->n_settings++] = (pg_param_override){"ocio.view", c->ocio_view};
}

static pg_result set_debug_view(pg_cli_common *c, const char *opt, const char *v, pg_error *err)
{
    c->debug_view_option = opt;
    for (uint32_t k = 0; k < c->n_sets; k++) /* one 'view' override from these options */
        if (c->sets[k].key && !strcmp(c->sets[k].key, "view") && c->sets[k].value == c->debug_view) {
            c->sets[k].value = v;
            c->debug_view = v;
            return PG_OK;
        }
    if (c->n_sets >= PG_CLI_MAX_SETS) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: too many overrides", opt);
    c->debug_view = v;
    c->sets[c->n_sets].key = "view";
    c->sets[c->n_sets].value = v;
    c->n_sets++;
    return PG_OK;
}

/* --include-dir folders (process-wide, like the loader's list they feed) */
static const char *g_include_dirs[PG_MAX_INCLUDE_DIRS];
static uint32_t g_n_include_dirs;

/* --include-dir DIR: one more folder for the pipeline loader's includes */
static pg_result add_include_dir(const char *v, pg_error *err)
{
    if (g_n_include_dirs >= PG_MAX_INCLUDE_DIRS)
        return pg_fail(err, PG_ERR_INVALID_ARG, "--include-dir: more than %d folders", PG_MAX_INCLUDE_DIRS);
    g_include_dirs[g_n_include_dirs] = v;
    pg_result r = pg_pipeline_set_include_dirs(g_include_dirs, g_n_include_dirs + 1, err);
    if (r) {
        if (err) err->code = PG_ERR_INVALID_ARG;
        return PG_ERR_INVALID_ARG;
    }
    g_n_include_dirs++;
    return PG_OK;
}

/* --size WxH, each side 1..16384 */
static pg_result parse_size(pg_cli_common *c, const char *v, pg_error *err)
{
    const char *x = strchr(v, 'x');
    if (!x) return pg_fail(err, PG_ERR_INVALID_ARG, "--size %s: expected WxH, e.g. 640x360", v);
    char wbuf[32];
    size_t wl = (size_t)(x - v);
    if (wl == 0 || wl >= sizeof wbuf) return pg_fail(err, PG_ERR_INVALID_ARG, "--size %s: expected WxH", v);
    memcpy(wbuf, v, wl);
    wbuf[wl] = 0;
    uint64_t w, h;
    pg_result r;
    if ((r = pg_cli_parse_u64("--size width", wbuf, 1, 16384, &w, err))) return r;
    if ((r = pg_cli_parse_u64("--size height", x + 1, 1, 16384, &h, err))) return r;
    c->width = (uint32_t)w;
    c->height = (uint32_t)h;
    return PG_OK;
}

/* --set KEY=VALUE, split in place (argv strings are writable) */
static pg_result add_set(pg_cli_common *c, char *v, pg_error *err)
{
    const char *eq = strchr(v, '=');
    if (!eq || eq == v) return pg_fail(err, PG_ERR_INVALID_ARG, "--set %s: expected KEY=VALUE", v);
    if (c->n_sets >= PG_CLI_MAX_SETS) return pg_fail(err, PG_ERR_INVALID_ARG, "--set: at most %d", PG_CLI_MAX_SETS);
    v[eq - v] = 0;
    c->sets[c->n_sets].key = v;
    c->sets[c->n_sets].value = v + (eq - v) + 1;
    c->n_sets++;
    return PG_OK;
}

/* --device N (a whole number: an index) or NAME (any other text: a part of the device name) */
static pg_result parse_device(pg_cli_common *c, const char *a, const char *v, pg_error *err)
{
    if (v[strspn(v, "0123456789")] == 0 && v[0]) { /* all digits: an index; any other text matches names */
        uint64_t u;
        pg_result r = pg_cli_parse_u64(a, v, 0, 65535, &u, err); /* one not there: "index N of M", exit 1 */
        if (r) return r;
        c->device_index = (int)u;
    } else {
        c->device_match = v;
    }
    return PG_OK;
}

/* --view NAME: an OCIO view of the chosen display, else a debug view; a config that does not load
 * is reported by the display pass (or by --ocio-config / --display), not here */
static pg_result parse_view(pg_cli_common *c, int argc, char **argv, const char *a, const char *v, pg_error *err)
{
    c->view = v;
    pg_ocio_config *cfg = NULL;
    pg_error ignored = {0};
    bool is_ocio = false;
    if (!open_config(argc, argv, &cfg, &ignored)) {
        is_ocio = pg_ocio_has_view(cfg, prescan(argc, argv, "--display"), v);
        pg_ocio_close(cfg);
    }
    if (!is_ocio) return set_debug_view(c, a, v, err);
    c->ocio_view = v;
    rebuild_settings(c);
    return PG_OK;
}

/* --ocio-config FILE, --display NAME, --ocio-view NAME: checked against the config now */
static pg_result parse_ocio_option(pg_cli_common *c, int argc, char **argv, const char *a, const char *v,
                                   pg_error *err)
{
    if (!v[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: empty name", a);
    pg_ocio_config *cfg = NULL;
    pg_result r;
    if ((r = open_config(argc, argv, &cfg, err))) return pg_error_prefix(err, "%s", a);
    const char *display = prescan(argc, argv, "--display");
    if (!strcmp(a, "--display")) r = pg_ocio_resolve(cfg, v, NULL, NULL, 0, NULL, 0, err);
    else if (!strcmp(a, "--ocio-view")) r = pg_ocio_resolve(cfg, display, v, NULL, 0, NULL, 0, err);
    pg_ocio_close(cfg);
    if (r) return pg_error_prefix(err, "%s %s", a, v);
    if (!strcmp(a, "--ocio-config")) c->ocio_config = v;
    else if (!strcmp(a, "--display")) c->display = v;
    else c->ocio_view = v;
    rebuild_settings(c);
    return PG_OK;
}

/* --async-compute on|off|emulate */
static pg_result parse_async_compute(pg_cli_common *c, const char *v, pg_error *err)
{
    if (!strcmp(v, "on")) c->async_compute = PG_ASYNC_ON;
    else if (!strcmp(v, "off")) c->async_compute = PG_ASYNC_OFF;
    else if (!strcmp(v, "emulate")) c->async_compute = PG_ASYNC_EMULATE;
    else return pg_fail(err, PG_ERR_INVALID_ARG, "--async-compute: '%s': expected on, off or emulate", v);
    return PG_OK;
}

/* The common options, one branch each (the longer ones in the helpers above). */
/* --plugin FILE (repeatable) and --animation N|NAME|all|none (checked against the scene later) */
static pg_result parse_plugin_or_animation(pg_cli_common *c, const char *a, const char *v, pg_error *err)
{
    if (!strcmp(a, "--animation")) {
        if (!v[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--animation: empty (N, NAME, all or none)");
        c->animation = v;
        return PG_OK;
    }
    if (c->n_plugins >= sizeof c->plugins / sizeof c->plugins[0])
        return pg_fail(err, PG_ERR_INVALID_ARG, "--plugin %s: at most %zu plug-ins", v,
                       sizeof c->plugins / sizeof c->plugins[0]);
    c->plugins[c->n_plugins++] = v;
    return PG_OK;
}

/* --gltf-scene N, --variant N|NAME: what a glTF file draws */
static pg_result parse_scene_choice(pg_cli_common *c, const char *a, const char *v, pg_error *err)
{
    if (!strcmp(a, "--variant")) {
        if (!v[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "--variant: empty (an index or a variant name)");
        c->variant = v;
        return PG_OK;
    }
    uint64_t u;
    pg_result r = pg_cli_parse_u64(a, v, 0, 1000000, &u, err);
    if (!r) c->gltf_scene = (int)u;
    return r;
}

/* The field of an option whose value is a path or name kept as given (an empty one is refused). */
static const char **path_option(pg_cli_common *c, const char *a)
{
    return !strcmp(a, "--pipeline") ? &c->pipeline
           : !strcmp(a, "--scene")    ? &c->scene
           : !strcmp(a, "--scenario") ? &c->scenario
           : !strcmp(a, "--camera")   ? &c->camera
           : !strcmp(a, "--out")      ? &c->out
                                      : NULL;
}

pg_result pg_cli_parse_common(pg_cli_common *c, int argc, char **argv, int *i, bool *used, pg_error *err)
{
    const char *a = argv[*i];
    const char *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    *used = true;
    uint64_t u;
    pg_result r = PG_OK;
#define NEED_VALUE()                                                                        \
    do {                                                                                    \
        if (!v) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value", a);            \
        if (v[0] == '-' && v[1] == '-' && isalpha((unsigned char)v[2])) /* "--lights --out" */ \
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: missing value (followed by the option %s)", a, v); \
        (*i)++;                                                                             \
    } while (0)
    const char **path_field = path_option(c, a);
    if (path_field) {
        NEED_VALUE();
        if (!v[0]) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: empty %s", a, !strcmp(a, "--camera") ? "name" : "path");
        *path_field = v;
    } else if (!strcmp(a, "--include-dir")) {
        NEED_VALUE();
        if ((r = add_include_dir(v, err))) return r;
    } else if (!strcmp(a, "--gltf-scene") || !strcmp(a, "--variant")) {
        NEED_VALUE();
        if ((r = parse_scene_choice(c, a, v, err))) return r;
    } else if (!strcmp(a, "--lights")) {
        NEED_VALUE();
        if (v[0] == '-') return pg_fail(err, PG_ERR_INVALID_ARG, "--lights %s: must not be negative", v);
        if ((r = pg_cli_parse_u64(a, v, 0, PG_MAX_LIGHTS, &u, err))) return r;
        c->lights = (uint32_t)u;
        c->has_lights = true;
    } else if (!strcmp(a, "--seed")) {
        NEED_VALUE();
        if ((r = pg_cli_parse_u64(a, v, 0, UINT32_MAX, &u, err))) return r;
        c->seed = (uint32_t)u;
        c->has_seed = true;
    } else if (!strcmp(a, "--frames")) {
        NEED_VALUE();
        if ((r = pg_cli_parse_u64(a, v, 1, 100000, &u, err))) return r;
        c->frames = (uint32_t)u;
    } else if (!strcmp(a, "--plugin") || !strcmp(a, "--animation")) {
        NEED_VALUE();
        if ((r = parse_plugin_or_animation(c, a, v, err))) return r;
    } else if (!strcmp(a, "--time")) {
        NEED_VALUE();
        /* a float of seconds: past 1e5 (27.8 hours) it holds less than a 60 Hz frame (1/128 s there) */
        if ((r = parse_float(a, v, -PG_MAX_TIME_S, PG_MAX_TIME_S, &c->time, err))) return r;
    } else if (!strcmp(a, "--radius")) {
        NEED_VALUE();
        if ((r = parse_float(a, v, 0, 1e7, &c->radius, err))) return r;
        c->has_radius = true;
    } else if (!strcmp(a, "--intensity")) {
        NEED_VALUE();
        if ((r = parse_float(a, v, 0, 1e7, &c->intensity, err))) return r;
        c->has_intensity = true;
    } else if (!strcmp(a, "--ambient")) {
        NEED_VALUE();
        if ((r = parse_float(a, v, 0, 1000, &c->ambient, err))) return r;
        c->has_ambient = true;
    } else if (!strcmp(a, "--environment")) {
        NEED_VALUE();
        c->environment = v;
    } else if (!strcmp(a, "--environment-intensity")) {
        NEED_VALUE();
        if ((r = parse_float(a, v, 0, 1e6, &c->env_intensity, err))) return r;
    } else if (!strcmp(a, "--environment-rotation")) {
        NEED_VALUE();
        if ((r = parse_float(a, v, -36000, 36000, &c->env_rotation_deg, err))) return r;
    } else if (!strcmp(a, "--size")) {
        NEED_VALUE();
        if ((r = parse_size(c, v, err))) return r;
    } else if (!strcmp(a, "--set")) {
        NEED_VALUE();
        if ((r = add_set(c, argv[*i], err))) return r;
    } else if (!strcmp(a, "--device")) {
        NEED_VALUE();
        if ((r = parse_device(c, a, v, err))) return r;
    } else if (!strcmp(a, "--view")) {
        NEED_VALUE();
        if ((r = parse_view(c, argc, argv, a, v, err))) return r;
    } else if (!strcmp(a, "--debug-view")) {
        NEED_VALUE();
        if ((r = set_debug_view(c, a, v, err))) return r;
    } else if (!strcmp(a, "--ocio-config") || !strcmp(a, "--display") || !strcmp(a, "--ocio-view")) {
        NEED_VALUE();
        if ((r = parse_ocio_option(c, argc, argv, a, v, err))) return r;
    } else if (!strcmp(a, "--validation")) {
        c->validation = true;
    } else if (!strcmp(a, "--require-exact")) {
        c->require_exact = true;
    } else if (!strcmp(a, "--no-aliasing")) {
        c->no_aliasing = true;
    } else if (!strcmp(a, "--no-shader-cache")) {
        pg_cache_set_enabled(false); /* process-wide: the caches are per process */
    } else if (!strcmp(a, "--immediate")) {
        c->immediate = true;
    } else if (!strcmp(a, "--async-compute")) {
        NEED_VALUE();
        if ((r = parse_async_compute(c, v, err))) return r;
    } else if (!strcmp(a, "--explain")) {
        c->explain = true;
    } else if (!strcmp(a, "--quiet")) {
        c->quiet = true;
    } else {
        *used = false;
    }
#undef NEED_VALUE
    return PG_OK;
}
