/* test_gpu_clustered.c - clustered forward+ and clustered deferred (every G-buffer packing)
 * against the naive reference, on lavapipe with validation + synchronization validation.
 *
 * Accuracy sweep: the default scene (its default light set-up and camera) and the Sponza
 * (assets/scenarios/cis565.json) at W x H, time SWEEP_TIME, seed SWEEP_SEED, with the SHIPPED
 * pipeline defaults (no max_lights or other clustering parameter is set), Lambert at every count of
 * k_counts (and the atrium at SWEEP_DENSE_LIGHTS), plus Blinn-Phong and an rgba32f HDR target at
 * SWEEP_EXTRA_LIGHTS. For every frame:
 *   - no clustered pipeline drops a light (overflow_clusters == 0 and overflow_dropped == 0, the
 *     check tagged NO-OVERFLOW-BY-DEFAULT); a frame that dropped lights fails there once and its
 *     accuracy bounds are not asserted (they hold only when every light is shaded).
 *     COUNT_OVER_OLD_CAP needs more than OLD_CAP lights in some cluster (asserted with an explicit
 *     max_lights=OLD_CAP), so the sweep exercises long light lists;
 *   - forward+: the read-back HDR output is byte-identical to naive's (same hdr_format, memcmp);
 *   - deferred float (rgba32f position), oct16, packed, per pixel and channel (R, G, B):
 *       |out - ref| <= A * |ref| + B * peak          peak = the reference's largest RGB value
 *     with (A, B) = FLOAT_PX_*, OCT16_PX_*, PACKED_PX_*;
 *   - oct16, packed: the largest difference of the 8-bit display images (steps) and the share of
 *     pixels whose display differs by more than one step, <= *_DISPLAY_MAX_STEP / *_DISPLAY_SHARE.
 * Each frame prints an "accuracy:" line with its measured values; the end prints a "bound:" line
 * per variant, the worst case next to the bound. tools/accuracy_table.sh turns these lines (and
 * the "far:", "overflow:", "lights:" lines) into the test tables of docs/accuracy.md.
 *
 * Also: far from the origin (~1e5) forward+ stays byte-identical, oct16 and packed (positions
 * rebuilt camera-relative from depth) and forward+ with prepass_test=equal (the EQUAL pre-pass
 * misses a pixel whose depth the two pipelines round differently there) stay within FAR_REL * peak
 * of naive, the float variant's fp32
 * world positions (quantized to ~0.008 there) within FAR_FLOAT_REL, and the rgba16f position
 * variant fails (most pixels); overflow with an explicit small max_lights is counted,
 * deterministic, and the frame stays finite; 0 lights culls the light animation and cluster
 * assignment; 1 light is byte-identical; 1,000,000 lights render. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cluster_windows.h"
#include "gpu_harness.h"
#include "image_compare.h"
#include "image_util.h"
#include "pass_list.h"
#include "scenario.h"
#include "shader.h"
#include "test_util.h"

#define W 320
#define H 180

/* ---- the sweep's frames -------------------------------------------------------------------- */
/* COUNT_OVER_OLD_CAP overflowed the old default cap of 512 lights per cluster: at 320x180, time
 * 1.5, seed 11, 41 clusters (4379 light refs) in the atrium and 4 (119) in the Sponza. */
#define COUNT_OVER_OLD_CAP 5000
#define OLD_CAP "512"
static const uint32_t k_counts[] = {1, 100, 1000, COUNT_OVER_OLD_CAP};
/* The atrium also at this count (209 clusters over 512 there; the Sponza is left out to keep the
 * test's time down: naive at 10000 lights is the slowest frame of the test on lavapipe). */
#define SWEEP_DENSE_LIGHTS 10000
#define SWEEP_EXTRA_LIGHTS 1000 /* also rendered with Blinn-Phong and with an rgba32f HDR target */
#define SWEEP_TIME 1.5f
#define SWEEP_SEED 11
/* The reference must light this share of its pixels (else 1 light compares black images). */
#define MIN_LIT_SHARE 0.001

#include "accuracy_bounds.h"

/* Far from the origin (far_geometry) */
#define FAR_REL 0.03
#define FAR_FLOAT_REL 0.10
#define FAR_F16_FAIL_REL 0.25

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

static pg_frame_info frame_for(const pg_scene *scene, uint32_t lights, float t)
{
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(scene, (float)W / H),
        .lights = pg_light_setup_default(scene, lights, 11),
        .time = t,
        .width = W,
        .height = H,
    };
    return fi;
}

/* ---- the accuracy sweep ------------------------------------------------------------------- */

enum { SW_EXACT, SW_FLOAT, SW_PACKED };
typedef struct sweep_variant {
    const char *label, *pipeline;
    int kind;
    double px_a, px_b; /* per-pixel bound (SW_FLOAT, SW_PACKED) */
    int disp_max;      /* display bounds (SW_PACKED) */
    double disp_share;
} sweep_variant;
static const sweep_variant k_sweep[] = {
    {"forward_plus", "pipelines/forward_plus.json", SW_EXACT, 0, 0, 0, 0},
    {"deferred_float", "pipelines/deferred.json", SW_FLOAT, FLOAT_PX_A, FLOAT_PX_B, 0, 0},
    {"deferred_oct16", "pipelines/deferred_oct16.json", SW_PACKED, OCT16_PX_A, OCT16_PX_B, OCT16_DISPLAY_MAX_STEP,
     OCT16_DISPLAY_SHARE},
    {"deferred_packed", "pipelines/deferred_packed.json", SW_PACKED, PACKED_PX_A, PACKED_PX_B,
     PACKED_DISPLAY_MAX_STEP, PACKED_DISPLAY_SHARE},
};
#define N_SWEEP (sizeof k_sweep / sizeof k_sweep[0])

/* Worst measured values of one variant over the frames whose bounds were asserted. */
typedef struct sweep_worst {
    uint32_t frames, identical, not_evaluated;
    double usage, need_a, max_rel_peak, disp_max, disp_share;
    char usage_at[96], disp_max_at[96], disp_share_at[96];
} sweep_worst;
static sweep_worst g_worst[N_SWEEP];

/* Over every pixel and channel (RGB): *usage = max |d| / (A |ref| + B peak) (<= 1: the bound
 * holds; NaN counts as infinite); *need_a = the smallest A that would hold with this B. */
typedef struct sweep_scene {
    const char *name;
    const pg_scene *scene;
    const pg_scene_gpu *sg;
    const pg_scenario *scenario; /* NULL: the scene's default light set-up and camera */
    bool dense;                  /* also SWEEP_DENSE_LIGHTS */
} sweep_scene;

static pg_frame_info sweep_frame(const sweep_scene *ss, uint32_t lights)
{
    pg_frame_info fi = {
        .camera = pg_camera_default_for_scene(ss->scene, (float)W / H),
        .lights = pg_light_setup_default(ss->scene, lights, SWEEP_SEED),
        .time = SWEEP_TIME,
        .width = W,
        .height = H,
    };
    if (ss->scenario) pg_scenario_apply(ss->scenario, &fi.lights, &fi.camera);
    fi.lights.count = lights;
    fi.lights.seed = SWEEP_SEED;
    return fi;
}

static void worst_at(double v, double *worst, char *at, size_t at_size, const char *where)
{
    if (v > *worst || !at[0]) snprintf(at, at_size, "%s", where);
    if (v > *worst) *worst = v;
}

static void sweep_frame_check(const sweep_scene *ss, uint32_t lights, const char *shading, const char *hdr_format)
{
    pg_frame_info fi = sweep_frame(ss, lights);
    pg_param_override sets[2] = {{"shading", shading}, {"hdr_format", hdr_format}};
    char where[96];
    snprintf(where, sizeof where, "%s %u light%s %s %s", ss->name, lights, lights == 1 ? "" : "s", shading,
             hdr_format);
    pg_th_frame ref;
    if (!pg_th_render(g_gpu, &g_reg, ss->sg, "pipelines/naive.json", sets, 2, &fi, 1, false, &ref)) {
        CHECK_MSG(0, "%s: naive failed", where);
        return;
    }
    double peak;
    pg_th_max_abs(&ref, &ref, &peak);
    uint64_t lit = 0;
    for (size_t p = 0; p < (size_t)ref.w * ref.h; p++)
        if (ref.hdr[4 * p] > 0 || ref.hdr[4 * p + 1] > 0 || ref.hdr[4 * p + 2] > 0) lit++;
    double lit_share = (double)lit / ((double)ref.w * ref.h);
    CHECK_MSG(pg_count_nonfinite(ref.hdr, ref.w, ref.h) == 0, "%s: naive has non-finite pixels", where);
    CHECK_MSG(peak > 0 && lit_share >= MIN_LIT_SHARE, "%s: the reference is (almost) black: %.4f%% lit, peak %g",
              where, 100 * lit_share, peak);
    for (size_t v = 0; v < N_SWEEP; v++) {
        const sweep_variant *va = &k_sweep[v];
        sweep_worst *wo = &g_worst[v];
        pg_th_frame f;
        if (!pg_th_render(g_gpu, &g_reg, ss->sg, va->pipeline, sets, 2, &fi, 1, false, &f)) {
            CHECK_MSG(0, "%s: %s failed", where, va->label);
            continue;
        }
        pg_image_error e;
        pg_error err = {0};
        double m = pg_th_max_abs(&f, &ref, NULL);
        bool identical = pg_th_hdr_identical(&f, &ref);
        double usage = 0, need_a = 0;
        if (va->kind != SW_EXACT) pg_th_bound_usage(&f, &ref, peak, va->px_a, va->px_b, &usage, &need_a);
        CHECK(!pg_image_error_compute(f.hdr, ref.hdr, f.ldr, ref.ldr, f.w, f.h, 1.0, &e, &err));
        bool dropped = pg_frame_counter_sum(&f.stats, "overflow_clusters") || pg_frame_counter_sum(&f.stats, "overflow_dropped");
        printf("accuracy: scene=%s size=%ux%u lights=%u shading=%s hdr=%s variant=%s overflow_clusters=%llu "
               "overflow_dropped=%llu identical=%d lit=%.2f%% peak=%.4g max_abs=%.3g max_rel_peak=%.3g "
               "px_usage=%.3g px_need_a=%.3g rmse=%.3g disp_max=%.0f disp_share=%.4f%%%s\n",
               ss->name, f.w, f.h, lights, shading, hdr_format, va->label,
               (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_clusters"),
               (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_dropped"), identical, 100 * lit_share, peak, m, m / peak, usage,
               need_a, e.rmse_linear, e.max_abs_display, 100 * e.share_over_threshold,
               dropped ? " (lights dropped: bounds not asserted)" : "");
        CHECK_MSG(f.hdr_format == ref.hdr_format && f.hdr_format == pg_format_from_name(hdr_format),
                  "%s %s: hdr_format %s vs naive %s", where, va->label, pg_format_get(f.hdr_format)->name,
                  pg_format_get(ref.hdr_format)->name);
        CHECK_MSG(pg_count_nonfinite(f.hdr, f.w, f.h) == 0, "%s %s: non-finite pixels", where, va->label);
        CHECK_MSG(!dropped,
                  "%s %s: NO-OVERFLOW-BY-DEFAULT: %llu clusters overflowed, %llu light refs dropped with the "
                  "shipped defaults (no max_lights set)%s",
                  where, va->label, (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_clusters"),
                  (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_dropped"),
                  lights >= COUNT_OVER_OLD_CAP ? "; this count overflows a cap of " OLD_CAP " lights per cluster" : "");
        if (dropped) {
            wo->not_evaluated++;
            pg_th_release(&f);
            continue;
        }
        wo->frames++;
        if (va->kind == SW_EXACT) {
            CHECK_MSG(identical, "%s %s: HDR output not byte-identical to naive (max |d| %g, peak %g)", where,
                      va->label, m, peak);
            wo->identical += identical;
        } else {
            CHECK_MSG(usage <= 1.0, "%s %s: per-pixel |d| <= %g |ref| + %g peak exceeded %.3gx (needs A %.3g)",
                      where, va->label, va->px_a, va->px_b, usage, need_a);
        }
        if (va->kind == SW_PACKED) {
            CHECK_MSG(e.max_abs_display <= va->disp_max, "%s %s: display differs by %.0f steps > %d", where,
                      va->label, e.max_abs_display, va->disp_max);
            CHECK_MSG(e.share_over_threshold <= va->disp_share,
                      "%s %s: %.4f%% of the pixels differ by more than one step > %.4f%%", where, va->label,
                      100 * e.share_over_threshold, 100 * va->disp_share);
        }
        worst_at(usage, &wo->usage, wo->usage_at, sizeof wo->usage_at, where);
        if (need_a > wo->need_a) wo->need_a = need_a;
        if (m / peak > wo->max_rel_peak) wo->max_rel_peak = m / peak;
        worst_at(e.max_abs_display, &wo->disp_max, wo->disp_max_at, sizeof wo->disp_max_at, where);
        worst_at(e.share_over_threshold, &wo->disp_share, wo->disp_share_at, sizeof wo->disp_share_at, where);
        pg_th_release(&f);
    }
    pg_th_release(&ref);
}

/* COUNT_OVER_OLD_CAP needs more than OLD_CAP lights in some cluster: with that cap set explicitly
 * forward+ overflows (else the sweep would not exercise long light lists). */
static void sweep_count_exceeds_old_cap(const sweep_scene *ss)
{
    pg_frame_info fi = sweep_frame(ss, COUNT_OVER_OLD_CAP);
    pg_param_override sets[1] = {{"max_lights", OLD_CAP}};
    pg_th_frame f;
    if (!pg_th_render(g_gpu, &g_reg, ss->sg, "pipelines/forward_plus.json", sets, 1, &fi, 1, false, &f)) {
        CHECK_MSG(0, "%s: forward+ max_lights=" OLD_CAP " failed", ss->name);
        return;
    }
    printf("capped: scene=%s lights=%u max_lights=" OLD_CAP " overflow_clusters=%llu overflow_dropped=%llu\n",
           ss->name, COUNT_OVER_OLD_CAP, (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_clusters"),
           (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_dropped"));
    CHECK_MSG(pg_frame_counter_sum(&f.stats, "overflow_clusters") > 0 && pg_frame_counter_sum(&f.stats, "overflow_dropped") > 0,
              "%s: %u lights do not exceed %s lights in any cluster: the sweep does not test long lists", ss->name,
              COUNT_OVER_OLD_CAP, OLD_CAP);
    pg_th_release(&f);
}

static void sweep(const sweep_scene *ss)
{
    for (size_t c = 0; c < sizeof k_counts / sizeof k_counts[0]; c++)
        sweep_frame_check(ss, k_counts[c], "lambert", "rgba16f");
    if (ss->dense) sweep_frame_check(ss, SWEEP_DENSE_LIGHTS, "lambert", "rgba16f");
    sweep_frame_check(ss, SWEEP_EXTRA_LIGHTS, "blinn_phong", "rgba16f");
    sweep_frame_check(ss, SWEEP_EXTRA_LIGHTS, "lambert", "rgba32f");
    sweep_count_exceeds_old_cap(ss);
}

static void sweep_summary(void)
{
    for (size_t v = 0; v < N_SWEEP; v++) {
        const sweep_variant *va = &k_sweep[v];
        const sweep_worst *wo = &g_worst[v];
        if (va->kind == SW_EXACT) {
            printf("bound: variant=%s frames=%u not_evaluated=%u bound=byte-identical identical=%u\n", va->label,
                   wo->frames, wo->not_evaluated, wo->identical);
            continue;
        }
        char disp_max[32] = "-", disp_share[32] = "-";
        if (va->kind == SW_PACKED) {
            snprintf(disp_max, sizeof disp_max, "%d", va->disp_max);
            snprintf(disp_share, sizeof disp_share, "%g%%", 100 * va->disp_share);
        }
        printf("bound: variant=%s frames=%u not_evaluated=%u px_a=%g px_b=%g worst_px_usage=%.3g [%s] "
               "worst_need_a=%.3g worst_max_rel_peak=%.3g disp_max_bound=%s worst_disp_max=%.0f [%s] "
               "disp_share_bound=%s worst_disp_share=%.4f%% [%s]\n",
               va->label, wo->frames, wo->not_evaluated, va->px_a, va->px_b, wo->usage, wo->usage_at, wo->need_a,
               wo->max_rel_peak, disp_max, wo->disp_max, wo->disp_max_at, disp_share, 100 * wo->disp_share,
               wo->disp_share_at);
    }
}

/* ---- overflow with an explicit cap, light counts --------------------------------------------- */

/* All lights inside one small box in front of the camera, max_lights=8: the clusters there
 * overflow. */
static void overflow(const pg_scene *scene, const pg_scene_gpu *sg)
{
    pg_frame_info fi = frame_for(scene, 64, 0.0f);
    float c[3];
    for (int k = 0; k < 3; k++) c[k] = fi.camera.position[k] + 0.5f * (fi.camera.target[k] - fi.camera.position[k]);
    for (int k = 0; k < 3; k++) {
        fi.lights.box_min[k] = c[k] - 0.01f;
        fi.lights.box_max[k] = c[k] + 0.01f;
    }
    fi.lights.motion = PG_MOTION_STATIC;
    pg_param_override sets[1] = {{"max_lights", "8"}};
    const char *pipes[] = {"pipelines/forward_plus.json", "pipelines/deferred_packed.json"};
    for (int p = 0; p < 2; p++) {
        pg_th_frame a, b;
        bool ok = pg_th_render(g_gpu, &g_reg, sg, pipes[p], sets, 1, &fi, 1, false, &a);
        if (ok && !pg_th_render(g_gpu, &g_reg, sg, pipes[p], sets, 1, &fi, 1, false, &b)) {
            pg_th_release(&a);
            ok = false;
        }
        CHECK_MSG(ok, "overflow %s renders", pipes[p]);
        if (!ok) continue;
        printf("overflow: pipeline=%s lights=64 max_lights=8 overflow_clusters=%llu overflow_dropped=%llu "
               "deterministic=%d\n",
               pipes[p], (unsigned long long)pg_frame_counter_sum(&a.stats, "overflow_clusters"), (unsigned long long)pg_frame_counter_sum(&a.stats, "overflow_dropped"),
               pg_th_hdr_identical(&a, &b));
        CHECK(pg_frame_counter_sum(&a.stats, "overflow_clusters") > 0);
        /* 64 lights: an overflowing cluster holds 9..64 of them and keeps 8 */
        CHECK(pg_frame_counter_sum(&a.stats, "overflow_dropped") >= pg_frame_counter_sum(&a.stats, "overflow_clusters") &&
              pg_frame_counter_sum(&a.stats, "overflow_dropped") <= pg_frame_counter_sum(&a.stats, "overflow_clusters") * 56);
        CHECK_MSG(pg_th_hdr_identical(&a, &b), "overflow not deterministic");
        CHECK(pg_count_nonfinite(a.hdr, a.w, a.h) == 0);
        pg_th_release(&a);
        pg_th_release(&b);
    }
}

static void light_counts(const pg_scene *scene, const pg_scene_gpu *sg)
{
    /* 0 lights: animation and assignment culled, black image (ambient 0) */
    const char *pipes[] = {"pipelines/forward_plus.json", "pipelines/deferred.json", "pipelines/deferred_oct16.json",
                           "pipelines/deferred_packed.json", "pipelines/naive.json"};
    for (int p = 0; p < 5; p++) {
        pg_frame_info fi = frame_for(scene, 0, 0.0f);
        pg_th_frame f;
        if (!pg_th_render(g_gpu, &g_reg, sg, pipes[p], NULL, 0, &fi, 1, false, &f)) {
            CHECK_MSG(0, "0 lights %s", pipes[p]);
            continue;
        }
        printf("lights: 0 lights: %s runs %s\n", pipes[p], f.order);
        CHECK_MSG(!strstr(f.order, "animate_lights") && !strstr(f.order, "assign_lights"),
                  "%s: light passes not culled: %s", pipes[p], f.order);
        double peak;
        pg_th_frame zero = f;
        zero.hdr = calloc((size_t)f.w * f.h * 4, sizeof(float));
        CHECK(zero.hdr && pg_th_max_abs(&f, &zero, &peak) == 0.0);
        free(zero.hdr);
        pg_th_release(&f);
    }
    /* 1 light (3x the default radius, so it lights a good part of the atrium): byte-identical */
    pg_frame_info fi = frame_for(scene, 1, 2.0f);
    fi.lights.radius *= 3;
    pg_th_frame a, b;
    if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, &fi, 1, false, &a)) {
        if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/forward_plus.json", NULL, 0, &fi, 1, false, &b)) {
            double peak, m = pg_th_max_abs(&b, &a, &peak);
            printf("lights: 1 light: forward+ vs naive identical=%d max_abs=%g peak=%g\n", pg_th_hdr_identical(&b, &a),
                   m, peak);
            CHECK(peak > 0 && pg_th_hdr_identical(&b, &a));
            pg_th_release(&b);
        } else {
            CHECK_MSG(0, "1 light: forward+ renders");
        }
        pg_th_release(&a);
    } else {
        CHECK_MSG(0, "1 light: naive renders");
    }
    /* 1,000,000 lights: a coarse grid and an explicit small cap keep lavapipe's cluster assignment
     * short */
    pg_param_override sets[4] = {{"grid_x", "4"}, {"grid_y", "3"}, {"grid_z", "4"}, {"max_lights", "64"}};
    fi = frame_for(scene, 1000000, 3.0f);
    fi.width = 64;
    fi.height = 36;
    pg_th_frame m;
    if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/forward_plus.json", sets, 4, &fi, 1, false, &m)) {
        printf("lights: 1,000,000 lights: forward+ %ux%u grid 4x3x4 max_lights=64: %.1f ms, %llu of 48 clusters "
               "overflow, %llu light refs dropped\n",
               m.w, m.h, m.stats.gpu_total_ms, (unsigned long long)pg_frame_counter_sum(&m.stats, "overflow_clusters"),
               (unsigned long long)pg_frame_counter_sum(&m.stats, "overflow_dropped"));
        CHECK(pg_frame_counter_sum(&m.stats, "overflow_clusters") > 0);
        CHECK(pg_count_nonfinite(m.hdr, m.w, m.h) == 0);
        pg_th_release(&m);
    } else {
        CHECK_MSG(0, "1M lights renders");
    }
}

/* ---- the light lists in windows ----------------------------------------------------------- */

/* Lists larger than one storage-buffer binding spans are bound as windows of one buffer
 * (renderer/common/cluster_windows.h). PASSGRAPH_LIST_WINDOW_BYTES makes the windows small, so
 * 5000 lights in the atrium (2.2 MiB of lists) take 5 windows of 512 KiB after growing from the
 * initial 2: the writer (cluster_assign), the per-pixel loop (forward+), the tiled loop
 * (visibility, deferred_oct16) must give the same bits as with one binding, with no reference
 * dropped. */
#define WINDOW_BYTES "524288"
static void list_windows(const pg_scene *scene, const pg_scene_gpu *sg)
{
    const char *pipes[] = {"pipelines/forward_plus.json", "pipelines/visibility.json", "pipelines/deferred_oct16.json"};
    pg_frame_info fi = frame_for(scene, COUNT_OVER_OLD_CAP, SWEEP_TIME);
    /* what this device lets the lists take (docs/passes.md quotes lavapipe's line) */
    printf("windows: %s: one binding spans %.0f MiB, a window is %.0f MiB, the lists may take %.0f MiB\n",
           g_gpu->props.deviceName, g_gpu->max_storage_buffer_range / 1048576.0,
           pg_list_window_bytes(g_gpu) / 1048576.0, pg_list_max_bytes(g_gpu) / 1048576.0);
    CHECK(pg_list_window_bytes(g_gpu) <= g_gpu->max_storage_buffer_range &&
          pg_list_max_bytes(g_gpu) >= pg_list_window_bytes(g_gpu));
    for (int p = 0; p < 3; p++) {
        pg_th_frame one, win;
        bool ok1 = pg_th_render(g_gpu, &g_reg, sg, pipes[p], NULL, 0, &fi, 1, false, &one);
        setenv("PASSGRAPH_LIST_WINDOW_BYTES", WINDOW_BYTES, 1);
        bool ok2 = pg_th_render(g_gpu, &g_reg, sg, pipes[p], NULL, 0, &fi, 1, false, &win);
        unsetenv("PASSGRAPH_LIST_WINDOW_BYTES");
        CHECK_MSG(ok1 && ok2, "windows: %s renders", pipes[p]);
        if (!ok1 || !ok2) {
            if (ok1) pg_th_release(&one);
            if (ok2) pg_th_release(&win);
            continue;
        }
        uint64_t bytes = pg_frame_counter_sum(&win.stats, "list_bytes");
        uint64_t windows = (bytes + atoll(WINDOW_BYTES) - 1) / atoll(WINDOW_BYTES);
        printf("windows: %s: %.2f MiB of lists in %llu windows of %s bytes, %llu refs dropped, identical=%d\n",
               pipes[p], bytes / 1048576.0, (unsigned long long)windows, WINDOW_BYTES,
               (unsigned long long)pg_frame_counter_sum(&win.stats, "overflow_dropped"), pg_th_hdr_identical(&one, &win));
        CHECK_MSG(windows >= 4 && win.stats.n_grown > 0, "windows: %s: the case needs several windows and a growth",
                  pipes[p]);
        CHECK(pg_frame_counter_sum(&win.stats, "overflow_dropped") == 0);
        CHECK(pg_frame_counter_sum(&one.stats, "overflow_dropped") == 0);
        CHECK_MSG(pg_th_hdr_identical(&one, &win), "windows: %s differs from one binding", pipes[p]);
        pg_th_release(&one);
        pg_th_release(&win);
    }
    /* a device whose bindings span 1 MiB: the built-in passes take windows by themselves (3 of 1
     * MiB), while a user pass that binds the 2.2 MiB lists as one buffer is refused */
    uint64_t range = g_gpu->max_storage_buffer_range;
    g_gpu->max_storage_buffer_range = 1u << 20;
    pg_th_frame one, small;
    if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/forward_plus.json", NULL, 0, &fi, 1, false, &small)) {
        g_gpu->max_storage_buffer_range = range;
        if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/forward_plus.json", NULL, 0, &fi, 1, false, &one)) {
            printf("windows: 1 MiB bindings: forward+ identical=%d\n", pg_th_hdr_identical(&one, &small));
            CHECK(pg_th_hdr_identical(&one, &small) && pg_frame_counter_sum(&small.stats, "overflow_dropped") == 0);
            pg_th_release(&one);
        }
        pg_th_release(&small);
    } else {
        CHECK_MSG(0, "windows: forward+ with 1 MiB bindings renders");
    }
    g_gpu->max_storage_buffer_range = 1u << 20;
    pg_th_frame user;
    bool user_ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/examples/lighting/lighting.json", NULL, 0, &fi, 1, false,
                                &user);
    g_gpu->max_storage_buffer_range = range;
    printf("windows: 1 MiB bindings: the user lighting example %s\n", user_ok ? "rendered" : "refused");
    CHECK_MSG(!user_ok, "windows: a user pass bound a buffer larger than one binding spans");
    if (user_ok) pg_th_release(&user);
}

/* ---- far from the origin -------------------------------------------------------------------- */

typedef struct far_variant {
    const char *label, *pipeline;
    pg_param_override set;
    uint32_t n_sets;
} far_variant;
static const far_variant k_far[] = {
    {"forward_plus", "pipelines/forward_plus.json", {0}, 0},
    {"forward_plus_prepass_equal", "pipelines/forward_plus.json", {"prepass_test", "equal"}, 1},
    {"deferred_float", "pipelines/deferred.json", {0}, 0},
    {"deferred_float_rgba16f_position", "pipelines/deferred.json", {"position_format", "rgba16f"}, 1},
    {"deferred_oct16", "pipelines/deferred_oct16.json", {0}, 0},
    {"deferred_packed", "pipelines/deferred_packed.json", {0}, 0},
};

/* The default scene moved to ~1e5 from the origin. */
static void far_geometry(void)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    if (pg_scene_create_default(&scene, &err)) {
        CHECK_MSG(0, "%s", err.msg);
        return;
    }
    const float off[3] = {1.0e5f, 0.0f, 1.0e5f};
    for (uint32_t v = 0; v < scene->n_vertices; v++)
        for (int k = 0; k < 3; k++) scene->vertices[v].position[k] += off[k];
    pg_scene_finalize(scene);
    pg_scene_gpu *sg = NULL;
    if (pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s", err.msg);
        pg_scene_free(scene);
        return;
    }
    pg_frame_info fi = frame_for(scene, 256, 1.5f);
    pg_th_frame ref;
    if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, &fi, 1, false, &ref)) {
        for (size_t v = 0; v < sizeof k_far / sizeof k_far[0]; v++) {
            const far_variant *va = &k_far[v];
            pg_th_frame f;
            if (!pg_th_render(g_gpu, &g_reg, sg, va->pipeline, &va->set, va->n_sets, &fi, 1, false, &f)) {
                CHECK_MSG(0, "far %s", va->label);
                continue;
            }
            pg_image_error e;
            double peak, m = pg_th_max_abs(&f, &ref, &peak);
            CHECK(!pg_image_error_compute(f.hdr, ref.hdr, f.ldr, ref.ldr, f.w, f.h, 1.0, &e, &err));
            if (peak <= 0) peak = 1;
            double mrel = m / peak;
            printf("far: offset=1e5 lights=256 size=%ux%u variant=%s identical=%d peak=%.4g max_abs=%.3g "
                   "max_rel_peak=%.3g rmse=%.3g disp_max=%.0f disp_share=%.4f%% overflow_dropped=%llu\n",
                   f.w, f.h, va->label, pg_th_hdr_identical(&f, &ref), peak, m, mrel, e.rmse_linear, e.max_abs_display,
                   100 * e.share_over_threshold, (unsigned long long)pg_frame_counter_sum(&f.stats, "overflow_dropped"));
            if (!strcmp(va->label, "forward_plus"))
                CHECK_MSG(pg_th_hdr_identical(&f, &ref), "far forward_plus: not byte-identical (max rel %g)", mrel);
            else if (!strcmp(va->label, "deferred_float_rgba16f_position"))
                CHECK_MSG(mrel > FAR_F16_FAIL_REL, "rgba16f position should fail far from the origin (max rel %g)",
                          mrel);
            else if (!strcmp(va->label, "deferred_float"))
                CHECK_MSG(mrel <= FAR_FLOAT_REL, "far %s: max rel %g > %g", va->label, mrel, FAR_FLOAT_REL);
            else
                CHECK_MSG(mrel <= FAR_REL, "far %s: max rel %g > %g", va->label, mrel, FAR_REL);
            pg_th_release(&f);
        }
        pg_th_release(&ref);
    } else {
        CHECK_MSG(0, "far naive");
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

static void run_scene(const char *name, const char *path, const char *scenario, bool extras)
{
    pg_error err = {0};
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    pg_scenario sc;
    char sc_path[PG_PATH_MAX];
    if (scenario) pg_data_path(sc_path, sizeof sc_path, scenario);
    if ((scenario && pg_scenario_load(sc_path, &sc, &err)) || pg_scene_load(path, &scene, &err) ||
        pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        CHECK_MSG(0, "%s: %s", name, err.msg);
        pg_scene_free(scene);
        return;
    }
    sweep_scene ss = {name, scene, sg, scenario ? &sc : NULL, extras};
    sweep(&ss);
    if (extras) {
        overflow(scene, sg);
        light_counts(scene, sg);
        list_windows(scene, sg);
    }
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0); /* keep the measured lines next to the failures on stderr */
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_clustered: %s\n", err.msg);
        return 1;
    }
    printf("device: %s\n", g_gpu->props.deviceName);
    printf("sweep: size=%dx%d time=%g seed=%d\n", W, H, (double)SWEEP_TIME, SWEEP_SEED);
    run_scene("default", "default", NULL, true);
    char sponza[PG_PATH_MAX];
    snprintf(sponza, sizeof sponza, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    if (access(sponza, R_OK) == 0) run_scene("sponza", sponza, "assets/scenarios/cis565.json", false);
    else printf("test_gpu_clustered: Sponza skipped: %s not found\n", sponza);
    far_geometry();
    sweep_summary();
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_clustered");
}
