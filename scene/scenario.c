/* scenario.c - scenario JSON (assets/scenarios/README.md describes the format), default light
 * set-up for a scene, and applying a scenario over defaults. */
#include "scenario.h"
#include "pg_file.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sc_ctx {
    const char *path;
    pg_error *err;
} sc_ctx;

static pg_result schema(const sc_ctx *c, const char *field, const char *what)
{
    return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s: %s", c->path, field, what);
}

static pg_result get_number(const sc_ctx *c, const cJSON *it, const char *field, float lo,
                            float hi, bool lo_excl, bool hi_excl, const char *expect, float *out)
{
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble))
        return schema(c, field, expect);
    double v = it->valuedouble;
    if (fabs(v) > 3.0e38) {
        char why[160];
        snprintf(why, sizeof why, "%s (of magnitude at most 3e38)", expect);
        return schema(c, field, why);
    }
    if ((lo_excl ? v <= lo : v < lo) || (hi_excl ? v >= hi : v > hi)) return schema(c, field, expect);
    const float f = (float)v; /* 1e-50 > 0 is 0 as a float, 179.9999999 < 180 is 180 */
    /* a number that must be > 0 must stay a normal float (a denormal fov or near draws nothing) */
    if ((lo_excl ? f <= lo : f < lo) || (hi_excl ? f >= hi : f > hi) || (lo_excl && v != 0 && !isnormal(f))) {
        char why[160];
        if (f != 0 && !isnormal(f))
            snprintf(why, sizeof why, "%s (%.15g is below the smallest normal 32-bit float)", expect, v);
        else
            snprintf(why, sizeof why, "%s (%.15g is %.9g as a 32-bit float)", expect, v, (double)f);
        return schema(c, field, why);
    }
    *out = f;
    return PG_OK;
}

static pg_result get_vec3(const sc_ctx *c, const cJSON *it, const char *field, float out[3])
{
    const char *expect = "expected an array of 3 finite numbers (of magnitude at most 3e38)";
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 3) return schema(c, field, expect);
    int k = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, it)
    {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || fabs(e->valuedouble) > 3.0e38)
            return schema(c, field, expect);
        out[k++] = (float)e->valuedouble;
    }
    return PG_OK;
}

/* A corner of the light box: its coordinates within +-1e30, so that the box's extent and the
 * generated positions stay finite floats (3e38 corners overflowed to inf positions). */
static pg_result get_box_corner(const sc_ctx *c, const cJSON *it, const char *field, float out[3])
{
    const char *expect = "expected an array of 3 numbers in [-1e30, 1e30]";
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 3) return schema(c, field, expect);
    const cJSON *e;
    cJSON_ArrayForEach(e, it)
    if (!cJSON_IsNumber(e) || !(fabs(e->valuedouble) <= 1e30)) return schema(c, field, expect);
    return get_vec3(c, it, field, out);
}

static pg_result get_string(const sc_ctx *c, const cJSON *it, const char *field, char *out,
                            size_t out_size)
{
    if (!cJSON_IsString(it) || !it->valuestring) return schema(c, field, "expected a string");
    if (!pg_strlcpy(out, it->valuestring, out_size)) {
        return pg_fail(c->err, PG_ERR_SCHEMA, "%s: %s: longer than %zu characters", c->path,
                       field, out_size - 1);
    }
    return PG_OK;
}

/* Rejects duplicate keys (cJSON keeps both, silently). */
static pg_result check_duplicates(const sc_ctx *c, const cJSON *obj, const char *prefix)
{
    for (const cJSON *a = obj->child; a; a = a->next)
        for (const cJSON *b = a->next; b; b = b->next)
            if (a->string && b->string && strcmp(a->string, b->string) == 0) {
                char f[PG_JSON_PATH_MAX];
                snprintf(f, sizeof f, "%s%s", prefix, a->string);
                return schema(c, f, "duplicate key");
            }
    return PG_OK;
}

static void line_col(const char *text, const char *at, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

#define TRY(x)                                                                                     \
    do {                                                                                           \
        pg_result r_ = (x);                                                                        \
        if (r_ != PG_OK) return r_;                                                                \
    } while (0)

static pg_result parse_camera(const sc_ctx *c, const cJSON *cam, pg_scenario *sc)
{
    if (!cJSON_IsObject(cam)) return schema(c, "camera", "expected an object");
    TRY(check_duplicates(c, cam, "camera."));
    sc->has_camera = true;
    pg_camera *k = &sc->camera;
    const cJSON *it;
    cJSON_ArrayForEach(it, cam)
    {
        const char *key = it->string;
        if (strcmp(key, "position") == 0) {
            TRY(get_vec3(c, it, "camera.position", k->position));
            sc->has_cam_position = true;
        } else if (strcmp(key, "target") == 0) {
            TRY(get_vec3(c, it, "camera.target", k->target));
            sc->has_cam_target = true;
        } else if (strcmp(key, "up") == 0) {
            TRY(get_vec3(c, it, "camera.up", k->up));
            if (!(k->up[0] * k->up[0] + k->up[1] * k->up[1] + k->up[2] * k->up[2] >= 1e-30f)) /* in float */
                return schema(c, "camera.up", "must not be the zero vector (a length of at least 1e-15)");
            sc->has_cam_up = true;
        } else if (strcmp(key, "fov_y") == 0) {
            TRY(get_number(c, it, "camera.fov_y", 0, 180, true, true,
                           "expected a number of degrees in (0, 180)", &k->fov_y_deg));
            sc->has_cam_fov = true;
        } else if (strcmp(key, "near") == 0) {
            TRY(get_number(c, it, "camera.near", 0, 3.0e38f, true, false,
                           "expected a finite number > 0", &k->near_z));
            sc->has_cam_near = true;
        } else if (strcmp(key, "far") == 0) {
            TRY(get_number(c, it, "camera.far", 0, 3.0e38f, true, false,
                           "expected a finite number > 0", &k->far_z));
            sc->has_cam_far = true;
        } else {
            char f[PG_JSON_PATH_MAX];
            snprintf(f, sizeof f, "camera.%s", key);
            return schema(c, f,
                          "unknown key (expected position, target, up, fov_y, near or far)");
        }
    }
    if (sc->has_cam_near && sc->has_cam_far && !(k->far_z > k->near_z))
        return schema(c, "camera.far", "must be greater than camera.near");
    if (sc->has_cam_position && sc->has_cam_target) {
        /* in float, as the view is made: (1e-30, 0, 0) apart squares to 0 */
        float d[3] = {k->target[0] - k->position[0], k->target[1] - k->position[1], k->target[2] - k->position[2]};
        float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (!(d2 >= 1e-30f) || !isfinite(d2))
            return schema(c, "camera.target",
                          !(d2 >= 1e-30f) ? "must differ from camera.position (by at least 1e-15)"
                                          : "too far from camera.position (their distance squared overflows a float)");
    }
    if (sc->has_cam_position && sc->has_cam_target && sc->has_cam_up) {
        float f[3] = {k->target[0] - k->position[0], k->target[1] - k->position[1],
                      k->target[2] - k->position[2]};
        float cx = f[1] * k->up[2] - f[2] * k->up[1], cy = f[2] * k->up[0] - f[0] * k->up[2],
              cz = f[0] * k->up[1] - f[1] * k->up[0];
        float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        float ul = sqrtf(k->up[0] * k->up[0] + k->up[1] * k->up[1] + k->up[2] * k->up[2]);
        if (sqrtf(cx * cx + cy * cy + cz * cz) <= 1e-6f * fl * ul)
            return schema(c, "camera.up", "must not be parallel to the view direction");
    }
    return PG_OK;
}

static pg_result parse_lights(const sc_ctx *c, const cJSON *li, pg_scenario *sc)
{
    if (!cJSON_IsObject(li)) return schema(c, "lights", "expected an object");
    TRY(check_duplicates(c, li, "lights."));
    pg_light_setup *L = &sc->lights;
    bool has_min = false, has_max = false;
    const cJSON *it;
    cJSON_ArrayForEach(it, li)
    {
        const char *key = it->string;
        if (strcmp(key, "count") == 0) {
            if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || it->valuedouble < 0 ||
                it->valuedouble > (double)PG_MAX_LIGHTS ||
                floor(it->valuedouble) != it->valuedouble) {
                char what[96];
                snprintf(what, sizeof what, "expected an integer in 0..%u", PG_MAX_LIGHTS);
                return schema(c, "lights.count", what);
            }
            L->count = (uint32_t)it->valuedouble;
            sc->has_light_count = true;
        } else if (strcmp(key, "box_min") == 0) {
            TRY(get_box_corner(c, it, "lights.box_min", L->box_min));
            has_min = true;
        } else if (strcmp(key, "box_max") == 0) {
            TRY(get_box_corner(c, it, "lights.box_max", L->box_max));
            has_max = true;
        } else if (strcmp(key, "radius") == 0) {
            TRY(get_number(c, it, "lights.radius", 0, (float)PG_LIGHT_MAX_CANDELA, false, false,
                           "expected a number in [0, 1e30]", &L->radius));
            sc->has_radius = true;
        } else if (strcmp(key, "intensity") == 0) {
            TRY(get_number(c, it, "lights.intensity", 0, (float)PG_LIGHT_MAX_CANDELA, false, false,
                           "expected a number in [0, 1e30]", &L->intensity));
            sc->has_intensity = true;
        } else if (strcmp(key, "ambient") == 0) {
            TRY(get_number(c, it, "lights.ambient", 0, 1000, false, false,
                           "expected a number in [0, 1000]", &L->ambient));
            sc->has_ambient = true;
        } else if (strcmp(key, "saturation") == 0) {
            TRY(get_number(c, it, "lights.saturation", 0, 1, false, false,
                           "expected a number in [0, 1]", &L->saturation));
            sc->has_saturation = true;
        } else if (strcmp(key, "motion") == 0) {
            if (!cJSON_IsString(it)) return schema(c, "lights.motion", "expected \"noise\" or \"static\"");
            if (strcmp(it->valuestring, "noise") == 0) L->motion = PG_MOTION_NOISE;
            else if (strcmp(it->valuestring, "static") == 0) L->motion = PG_MOTION_STATIC;
            else return schema(c, "lights.motion", "expected \"noise\" or \"static\"");
            sc->has_motion = true;
        } else if (strcmp(key, "speed") == 0) {
            TRY(get_number(c, it, "lights.speed", 0, 3.0e38f, false, false,
                           "expected a finite number >= 0", &L->speed));
            sc->has_speed = true;
        } else if (strcmp(key, "seed") == 0) {
            if (!cJSON_IsNumber(it) || !(it->valuedouble >= 0) || it->valuedouble > 4294967295.0 ||
                floor(it->valuedouble) != it->valuedouble)
                return schema(c, "lights.seed", "expected an integer in 0..4294967295");
            L->seed = (uint32_t)it->valuedouble;
            sc->has_seed = true;
        } else {
            char f[PG_JSON_PATH_MAX];
            snprintf(f, sizeof f, "lights.%s", key);
            return schema(c, f,
                          "unknown key (expected count, box_min, box_max, radius, intensity, "
                          "ambient, saturation, motion, speed or seed)");
        }
    }
    if (has_min != has_max)
        return schema(c, has_min ? "lights.box_max" : "lights.box_min",
                      "required together with the other box corner");
    if (has_min) {
        static const char axis[3] = {'x', 'y', 'z'};
        for (int k = 0; k < 3; k++)
            if (L->box_min[k] > L->box_max[k]) {
                char what[160];
                snprintf(what, sizeof what, "must be <= lights.box_max in every component (%c: %g > %g)",
                         axis[k], (double)L->box_min[k], (double)L->box_max[k]);
                return schema(c, "lights.box_min", what);
            }
        sc->has_light_box = true;
    }
    return PG_OK;
}

static pg_result parse_root(const sc_ctx *c, const cJSON *root, pg_scenario *sc)
{
    if (!cJSON_IsObject(root))
        return pg_fail(c->err, PG_ERR_SCHEMA, "%s: expected a JSON object at the top level",
                       c->path);
    TRY(check_duplicates(c, root, ""));
    const cJSON *it;
    cJSON_ArrayForEach(it, root)
    {
        const char *key = it->string;
        if (strcmp(key, "name") == 0) {
            TRY(get_string(c, it, "name", sc->name, sizeof sc->name));
        } else if (strcmp(key, "description") == 0) {
            if (!cJSON_IsString(it)) return schema(c, "description", "expected a string");
        } else if (strcmp(key, "scene") == 0) {
            char rel[PG_PATH_MAX];
            TRY(get_string(c, it, "scene", rel, sizeof rel));
            if (!rel[0]) return schema(c, "scene", "must not be empty");
            const char *slash = strrchr(c->path, '/');
            if (strcmp(rel, "default") == 0 || rel[0] == '/' || !slash) {
                pg_strlcpy(sc->scene, rel, sizeof sc->scene);
            } else {
                int dl = (int)(slash - c->path);
                int n = snprintf(sc->scene, sizeof sc->scene, "%.*s/%s", dl, c->path, rel);
                if (n < 0 || (size_t)n >= sizeof sc->scene)
                    return schema(c, "scene", "resolved path too long");
            }
        } else if (strcmp(key, "camera") == 0) {
            TRY(parse_camera(c, it, sc));
        } else if (strcmp(key, "lights") == 0) {
            TRY(parse_lights(c, it, sc));
        } else if (strcmp(key, "shading") == 0) {
            TRY(get_string(c, it, "shading", sc->shading, sizeof sc->shading));
            if (strcmp(sc->shading, "lambert") != 0 && strcmp(sc->shading, "blinn_phong") != 0 &&
                strcmp(sc->shading, "pbr") != 0)
                return schema(c, "shading", "expected \"lambert\", \"blinn_phong\" or \"pbr\"");
        } else {
            return schema(c, key,
                          "unknown key (expected name, description, scene, camera, lights or "
                          "shading)");
        }
    }
    return PG_OK;
}

pg_result pg_scenario_load(const char *path, pg_scenario *out, pg_error *err)
{
    if (!path || !out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scenario_load: NULL argument");
    memset(out, 0, sizeof *out);
    pg_strlcpy(out->path, path, sizeof out->path);
    {
        const char *b = strrchr(path, '/');
        b = b ? b + 1 : path;
        pg_strlcpy(out->name, b, sizeof out->name);
        char *dot = strrchr(out->name, '.');
        if (dot && dot != out->name) *dot = 0;
    }
    /* defaults for fields a file leaves out (never copied unless has_*) */
    out->camera.up[1] = 1.0f;
    out->camera.fov_y_deg = 60.0f;
    out->camera.near_z = 0.1f;
    out->camera.far_z = 1000.0f;
    out->camera.aspect = 1.0f;
    out->lights.intensity = 1.0f;
    out->lights.saturation = 0.8f;
    out->lights.speed = 1.0f;

    char *text = NULL;
    size_t size = 0;
    pg_result r = pg_file_read(path, "scenario", PG_FILE_CAP_SCENARIO, &text, &size, err);
    if (r != PG_OK) return r;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        int line, col;
        const char *at = end ? end : text;
        if (at < text || at > text + size) at = text + size;
        line_col(text, at, &line, &col);
        r = pg_fail(err, PG_ERR_PARSE, "%s:%d:%d: JSON syntax error%s", path, line, col,
                    size == 0 ? " (empty file)" : pg_json_depth_note(text, at < text + size ? (size_t)(at - text) + 1 : size, CJSON_NESTING_LIMIT));
        free(text);
        return r;
    }
    sc_ctx c = {path, err};
    r = parse_root(&c, root, out);
    cJSON_Delete(root);
    free(text);
    if (r != PG_OK) {
        /* leave nothing half-applied behind */
        pg_error keep;
        if (err) keep = *err;
        memset(out, 0, sizeof *out);
        if (err) *err = keep;
    }
    return r;
}

pg_light_setup pg_light_setup_default(const pg_scene *scene, uint32_t count, uint32_t seed)
{
    pg_light_setup L;
    memset(&L, 0, sizeof L);
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    if (scene && scene->n_indices > 0 && scene->bounds_min[0] <= scene->bounds_max[0] &&
        scene->bounds_min[1] <= scene->bounds_max[1] && scene->bounds_min[2] <= scene->bounds_max[2]) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    float ext = 0;
    for (int k = 0; k < 3; k++) {
        float e = mx[k] - mn[k];
        if (e > ext) ext = e;
        L.box_min[k] = mn[k] + 0.02f * e;
        L.box_max[k] = mx[k] - 0.02f * e;
    }
    if (!(ext > 0)) ext = 1.0f;
    L.count = count;
    L.radius = 0.12f * ext;
    L.intensity = 1.0f;
    L.saturation = 0.8f;
    L.motion = PG_MOTION_NOISE;
    L.speed = 1.0f;
    L.seed = seed;
    L.env_intensity = 1.0f;
    return L;
}

pg_light_setup pg_light_setup_object(const pg_scene *scene, uint32_t count, uint32_t seed)
{
    pg_light_setup L = pg_light_setup_default(scene, count, seed);
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    if (scene && scene->n_indices > 0 && scene->bounds_min[0] <= scene->bounds_max[0] &&
        scene->bounds_min[1] <= scene->bounds_max[1] && scene->bounds_min[2] <= scene->bounds_max[2]) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    double h2 = 0;
    for (int k = 0; k < 3; k++) h2 += 0.25 * ((double)mx[k] - mn[k]) * ((double)mx[k] - mn[k]);
    double r = sqrt(h2);
    if (!(r > 1e-30)) r = 1.0;
    for (int k = 0; k < 3; k++) {
        L.box_min[k] = (float)(mn[k] - 0.6 * r);
        L.box_max[k] = (float)(mx[k] + 0.6 * r);
    }
    double s = r > PG_LIGHT_MIN_DISTANCE ? r : PG_LIGHT_MIN_DISTANCE;
    L.radius = (float)(1.5 * r);
    L.intensity = (float)(PG_OBJECT_LIGHT_K * s * s * 256.0 / (count > 0 ? count : 1));
    L.saturation = 0.3f;
    L.ambient = PG_OBJECT_AMBIENT;
    L.keep_out = true;
    for (int k = 0; k < 3; k++) {
        L.keep_min[k] = (float)(mn[k] - PG_OBJECT_LIGHT_GAP * r);
        L.keep_max[k] = (float)(mx[k] + PG_OBJECT_LIGHT_GAP * r);
    }
    return L;
}

int pg_scenario_shading(const pg_scenario *sc)
{
    if (!strcmp(sc->shading, "lambert")) return PG_SHADING_LAMBERT;
    if (!strcmp(sc->shading, "blinn_phong")) return PG_SHADING_BLINN_PHONG;
    if (!strcmp(sc->shading, "pbr")) return PG_SHADING_PBR;
    return -1;
}

void pg_scenario_apply(const pg_scenario *sc, pg_light_setup *setup, pg_camera *camera)
{
    if (!sc) return;
    if (setup) {
        const pg_light_setup *s = &sc->lights;
        if (sc->has_light_count) setup->count = s->count;
        if (sc->has_light_box) {
            memcpy(setup->box_min, s->box_min, sizeof setup->box_min);
            memcpy(setup->box_max, s->box_max, sizeof setup->box_max);
            setup->keep_out = false; /* the scenario's box is the user's: lights fill all of it */
        }
        if (sc->has_radius) setup->radius = s->radius;
        if (sc->has_intensity) setup->intensity = s->intensity;
        if (sc->has_saturation) setup->saturation = s->saturation;
        if (sc->has_ambient) setup->ambient = s->ambient;
        if (sc->has_motion) setup->motion = s->motion;
        if (sc->has_speed) setup->speed = s->speed;
        if (sc->has_seed) setup->seed = s->seed;
    }
    if (camera) {
        const pg_camera *c = &sc->camera;
        if (sc->has_cam_position) memcpy(camera->position, c->position, sizeof c->position);
        if (sc->has_cam_target) memcpy(camera->target, c->target, sizeof c->target);
        if (sc->has_cam_up) memcpy(camera->up, c->up, sizeof c->up);
        if (sc->has_cam_fov) camera->fov_y_deg = c->fov_y_deg;
        if (sc->has_cam_near) camera->near_z = c->near_z;
        if (sc->has_cam_far) camera->far_z = c->far_z;
        if (!(camera->far_z > camera->near_z)) camera->far_z = camera->near_z * 1000.0f;
    }
}

/* ---- the CPU twin of shaders/light_animate.comp ---- */
static uint32_t la_hash(uint32_t x)
{
    uint32_t state = x * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

static float la_rand(uint32_t seed, uint32_t i, uint32_t k)
{
    return (float)(la_hash(la_hash(seed ^ la_hash(i * 16u + k)) + k) >> 8) * (1.0f / 16777216.0f);
}

static float la_clamp01(float x) { return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x; }

void pg_light_setup_generate(const pg_light_setup *s, float time, uint32_t i, float pos[3], float color[3])
{
    bool moving = s->motion != PG_MOTION_STATIC;
    float p[3];
    for (uint32_t a = 0; a < 3; a++) {
        float phase = la_rand(s->seed, i, a), u = phase;
        if (moving) {
            float freq = 0.02f + 0.08f * la_rand(s->seed, i, 3u + a);
            float x = phase + freq * s->speed * time;
            float tri = 1.0f - fabsf(2.0f * (x - floorf(x)) - 1.0f);
            u = tri * tri * (3.0f - 2.0f * tri);
        }
        p[a] = u;
    }
    for (int a = 0; a < 3; a++) pos[a] = s->box_min[a] + (s->box_max[a] - s->box_min[a]) * p[a];
    if (s->keep_out) { /* pg_keep_out */
        float c[3], h[3], ka[3], q[3], n = 0;
        for (int a = 0; a < 3; a++) {
            c[a] = 0.5f * (s->box_min[a] + s->box_max[a]);
            h[a] = fmaxf(0.5f * (s->box_max[a] - s->box_min[a]), 1e-30f);
            ka[a] = fminf(0.5f * (s->keep_max[a] - s->keep_min[a]) / h[a], 0.999f);
            q[a] = (pos[a] - c[a]) / h[a];
            n = fmaxf(n, fabsf(q[a]));
        }
        float u[3], t_in = 3e38f;
        for (int a = 0; a < 3; a++) {
            u[a] = n > 0.0f ? q[a] / n : (a == 1 ? 1.0f : 0.0f);
            t_in = fminf(t_in, ka[a] / fmaxf(fabsf(u[a]), 1e-30f));
        }
        float t = t_in + (1.0f - t_in) * n;
        for (int a = 0; a < 3; a++) pos[a] = c[a] + h[a] * u[a] * t;
    }
    float hue = la_rand(s->seed, i, 6u);
    for (int k = 0; k < 3; k++) {
        float off = k == 0 ? 0.0f : k == 1 ? 4.0f : 2.0f, x = hue * 6.0f + off;
        float m = x - 6.0f * floorf(x / 6.0f);
        float rgb = la_clamp01(fabsf(m - 3.0f) - 1.0f);
        color[k] = (1.0f + (rgb - 1.0f) * s->saturation) * s->intensity;
    }
}
