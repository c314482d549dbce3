/* render_session.h - the whole path from a pipeline file to pixels, shared by the tools and
 * the tests: load the pipeline (with --set overrides), compile it against a scene's features
 * and the light count, and run it. Re-compiles (and the runtime re-creates resources) only when
 * the light count, the size or the pipeline changes. */
#ifndef PG_RENDER_SESSION_H
#define PG_RENDER_SESSION_H

#include "frame.h"
#include "graph.h"
#include "graph_execute.h"
#include "pipeline.h"
#include "scene_gpu.h"
#include "scene_vars.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_session_desc {
    const char *pipeline_path;
    const pg_param_override *overrides;
    uint32_t n_overrides;
    const pg_pass_registry *registry;
    bool disable_aliasing;
    bool immediate;               /* see pg_compile_desc.immediate (--immediate) */
    uint64_t output_stages;       /* see pg_compile_desc.output_stages */
    bool async_off;               /* --async-compute off: plan for one queue (pg_queue_caps);
                                   * otherwise the runtime's device decides */
    /* Application settings (key/value strings, not pipeline parameters) handed to every pass's
     * create as pg_pass_create_ctx.settings; the graph core does not read them. Copied by
     * pg_session_create. Keys in use: "ocio.config" (an OpenColorIO config file), "ocio.display",
     * "ocio.view" (see passes/display_ocio.c). */
    const pg_param_override *settings;
    uint32_t n_settings;
    /* Test-only (NULL otherwise): called with every freshly compiled plan before the runtime is
     * built from it; it may edit the plan (tests/test_gpu_canary.c removes one barrier to prove
     * synchronization validation reports the hazard). */
    void (*test_edit_plan)(pg_graph_plan *plan, void *user);
    void *test_edit_user;
} pg_session_desc;

typedef struct pg_session {
    pg_gpu *gpu;                  /* borrowed */
    const pg_scene_gpu *scene;    /* borrowed */
    pg_session_desc desc;         /* desc.settings points to the session's own copy */
    pg_param_override *settings;  /* owned copy of desc.settings (keys and values) */
    pg_pipeline *pipeline;
    pg_graph_plan *plan;
    pg_runtime *runtime;
    uint32_t width, height, light_count;
    uint32_t compiles;            /* how many times the plan was compiled */
} pg_session;

pg_result pg_session_create(pg_gpu *gpu, const pg_scene_gpu *scene, const pg_session_desc *desc,
                            pg_session **out, pg_error *err);
/* Compiles for (lights, width, height) if they changed, then renders one frame. */
pg_result pg_session_render(pg_session *s, const pg_frame_info *info, bool readback,
                            pg_frame_stats *stats, pg_error *err);
/* Frames in flight of the session's runtime (1 or 2; pg_runtime_set_frames_in_flight). */
pg_result pg_session_set_frames_in_flight(pg_session *s, uint32_t n, pg_error *err);
/* Loads pipeline_path again with these overrides (the path and overrides are not kept) and
 * compiles it for the current light count and size on the same runtime, so pg_runtime_set_plan
 * re-creates only what the new plan needs (pg_rebuild_kind; a slider on a run-time option
 * re-creates nothing). Before the first compile it only loads. On failure the session keeps its
 * pipeline and plan and still renders. */
pg_result pg_session_reload(pg_session *s, const char *pipeline_path, const pg_param_override *overrides,
                            uint32_t n_overrides, pg_error *err);
/* Compiles without rendering (for --explain and dumps). */
pg_result pg_session_compile(pg_session *s, uint32_t light_count, uint32_t width, uint32_t height,
                             pg_error *err);
void pg_session_destroy(pg_session *s);

#ifdef __cplusplus
}
#endif
#endif
