/* scenario.h - a reproducible set-up in JSON: camera, light box, light count, radius, intensity,
 * motion, shading. See assets/scenarios/README.md. Every field is optional; absent fields keep
 * the command line's or the scene's defaults. */
#ifndef PG_SCENARIO_H
#define PG_SCENARIO_H

#include "pg_common.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pg_light_motion { PG_MOTION_NOISE = 0, PG_MOTION_STATIC = 1 } pg_light_motion;

/* Smallest light-to-surface distance used by the attenuation (world units): the 1/d^2 term is
 * evaluated as 1/max(d^2, PG_LIGHT_MIN_DISTANCE^2), so one light contributes at most
 * intensity / PG_LIGHT_MIN_DISTANCE^2 = intensity * 1e4. */
#define PG_LIGHT_MIN_DISTANCE 0.01f
#define PG_MAX_LIGHTS 16777216u /* hard upper bound for --lights and scenario light counts (16M) */
/* bound of |--time| (and passgraph_set_lights' time), seconds: time is a float, which past 1e5 s
 * (27.8 hours) steps by more than 1/128 s, and by a whole second past 2^23 */
#define PG_MAX_TIME_S 1e5

typedef struct pg_light_setup {
    uint32_t count;
    float box_min[3], box_max[3]; /* lights stay inside this box */
    float radius;                 /* light range R */
    float intensity;              /* colour multiplier */
    float saturation;             /* 0 = white, 1 = pure random hue (cis565: 0.8) */
    float ambient;                /* constant light on every surface (times albedo), a run-time
                                     value added to the pipeline's `ambient` parameter: 0 for the
                                     atrium, PG_OBJECT_AMBIENT for objects */
    pg_light_motion motion;
    float speed;                  /* noise frequency scale (1 = default) */
    uint32_t seed;
    bool keep_out;                /* true: lights are kept out of keep_min..keep_max (a box inside
                                     box_min..box_max with the same centre): light_animate maps the
                                     light box onto the shell between the two, so no light comes
                                     near the surfaces inside (pg_light_setup_object) */
    float keep_min[3], keep_max[3];
    uint32_t file_count;          /* the first file_count of `count` are the scene file's
                                     KHR_lights_punctual lights (scene->lights); the rest generated */
    float env_intensity;          /* the environment light's run-time knobs (scene->environment):
                                     radiance scale (1 in pg_light_setup_default) and rotation about +Y in radians (environment.h) */
    float env_rotation;
} pg_light_setup;

typedef struct pg_scenario {
    char name[PG_NAME_MAX];
    char path[PG_PATH_MAX];
    char scene[PG_PATH_MAX];      /* optional scene: "" when absent; "default" as is; a path
                                     written relative to the scenario file is stored resolved
                                     (joined with the scenario's directory) */
    bool has_camera;              /* any camera field present */
    bool has_cam_position, has_cam_target, has_cam_up, has_cam_fov, has_cam_near, has_cam_far;
    pg_camera camera;             /* aspect is ignored (taken from the output size) */
    bool has_light_count, has_light_box, has_radius, has_intensity, has_saturation,
         has_motion, has_speed, has_seed, has_ambient;
    pg_light_setup lights;
    char shading[PG_NAME_MAX];    /* optional: "lambert" / "blinn_phong" / "pbr": the model a
                                     pipeline's shading "auto" picks (pg_scenario_shading) */
} pg_scenario;

/* Errors: PG_ERR_IO (missing file), PG_ERR_PARSE (JSON syntax, with line:column),
 * PG_ERR_SCHEMA (unknown key, wrong type, out-of-range value), each as
 * "FILE: lights.radius: expected a finite number >= 0". `name` defaults to the file stem. */
pg_result pg_scenario_load(const char *path, pg_scenario *out, pg_error *err);

/* Defaults for a scene: box = scene bounds shrunk by 2% of each extent per side; radius =
 * 0.12 * the largest extent of the bounds; intensity 1; saturation 0.8; motion noise; speed 1;
 * ambient 0.
 * A NULL or empty scene uses the box (-1,-1,-1)..(1,1,1). */
pg_light_setup pg_light_setup_default(const pg_scene *scene, uint32_t count, uint32_t seed);
/* Defaults for an object (every loaded glTF, README "Scenes"): with r = half the diagonal of the
 * scene bounds (1 when empty), s = max(r, PG_LIGHT_MIN_DISTANCE): box = the bounds grown by 0.6 r
 * on every side (so lights surround the object, not only its inside); radius = 1.5 r; intensity
 * = PG_OBJECT_LIGHT_K * s^2 * 256 / max(count, 1) (the point-light falloff is 1/d^2 in scene
 * units and d ~ r here, so brightness does not depend on the object's size, and the total over
 * all lights does not depend on the count); saturation 0.3; motion noise; speed 1; ambient
 * PG_OBJECT_AMBIENT (so no surface of an object is pure black, whatever the lights reach); keep_out
 * the bounds grown by PG_OBJECT_LIGHT_GAP r on every side (no light nearer than that to the
 * object's surfaces: no hot spots). A scenario's light box turns keep_out off. */
#define PG_OBJECT_LIGHT_GAP 0.15f
#define PG_OBJECT_LIGHT_K 0.014f
#define PG_OBJECT_AMBIENT 0.02f
pg_light_setup pg_light_setup_object(const pg_scene *scene, uint32_t count, uint32_t seed);
/* The CPU twin of shaders/light_animate.comp: generated light i of the set-up at `time` (its
 * position, its colour already times the intensity, its range = setup->radius). Float arithmetic
 * in the shader's order, so the values agree with the GPU's to a few ulp (not bit for bit: GPUs
 * may fuse and reorder). `passgraph lights-table` writes these into a file. */
void pg_light_setup_generate(const pg_light_setup *setup, float time, uint32_t i, float pos[3], float color[3]);
/* Applies the scenario's fields over setup/camera (either may be NULL): only fields present in
 * the file (has_*) are copied; camera fields one by one. If the result has far_z <= near_z,
 * far_z becomes near_z * 1000. The light count from a scenario is a default: callers apply a
 * command-line --lights AFTER this call so that it wins. */
void pg_scenario_apply(const pg_scenario *sc, pg_light_setup *setup, pg_camera *camera);
/* The scenario's "shading" as PG_SHADING_* (scene_features.h), or -1 when it gives none: the tools
 * put it in the scene's features.auto_shading, the model a pipeline's shading "auto" picks. */
int pg_scenario_shading(const pg_scenario *sc);

#ifdef __cplusplus
}
#endif
#endif
