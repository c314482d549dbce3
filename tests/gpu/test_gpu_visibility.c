/* test_gpu_visibility.c - the visibility-buffer pipeline (pipelines/visibility.json; passes/
 * visibility.c, deferred_lighting.c packing "visibility", visibility_resolve.c; shaders/
 * visibility.frag, visibility_surface.glsl).
 *
 * No GPU: pg_vis_tri_bits packs (draw, triangle) into 32 bits and refuses scenes that do not fit;
 * compile: resolve=shade runs visibility then shade (no G-buffer resource), resolve=gbuffer runs
 * visibility, resolve, lighting_packed; the visibility pass compiles its alpha-test variant only
 * for a scene with alpha-mask materials, and the G-buffer path's emissive target is culled without
 * emissive materials.
 *
 * Images (lavapipe, validation + synchronization validation: any message fails): the built-in
 * atrium (alpha-masked grille), every generated glTF scene (48) of tests/corpus/gltf/{objects,models,
 * features,emissive,blend} (vertex colours, TEXCOORD_1, texture transforms, emissive, double-sided,
 * mirrored nodes, normal maps ...) with the tools' default view at 128x72, and the Sponza with
 * assets/scenarios/cis565.json at 320x180 (skipped with the reason when absent). Each against naive
 * in the same HDR format (rgba16f), both resolve paths:
 *   - scenes without textures: every pixel within VIS_PX_A |ref| + VIS_PX_B peak (the surface
 *     point and attributes come from the pixel ray instead of the rasterizer's interpolation;
 *     VIS_PBR_PX_* for the glTF scenes, which "auto" renders with the pbr model);
 *   - every scene: RMSE <= VIS_RMSE_REL of the peak, display (8-bit) steps <= VIS_DISPLAY_MAX_STEP
 *     and the share of pixels more than one step off <= VIS_DISPLAY_SHARE (the mip level comes
 *     from analytic derivatives instead of the hardware's 2x2 quads: texture filtering differs
 *     there, tests/accuracy_bounds.h);
 *   - resolve=gbuffer against deferred_packed (the same packed G-buffer written by raster):
 *     within the same texture bounds;
 *   - lit, finite.
 * Control: naive with half the lights must break the bounds (they can fail).
 * raster=compute (the compute rasterizer) against the hardware ids on every scene: at most
 * VIS_RASTER_SHARE (0.02%) of the pixels differ (0 on the corpus, 3 of 57,600 on the Sponza), within the
 * same bounds against naive; objects/ties.gltf puts 144 pixel centres exactly on shared edges (a
 * tie rule that gives them to neither triangle leaves 144 holes); the atrium's alpha-masked grille
 * goes through the compute path's alpha test (1 pixel of 57,600 differs; 398, 0.69%, without it);
 * on the atrium and the Sponza a job list of 4 entries (the overflow path: large triangles drawn by
 * their own invocation) and job rows of 7 groups (the 2D job grid) give the same image byte for byte.
 *
 * The tiled light loop (shading.glsl pg_shade_tile) of visibility and deferred_oct16: with
 * tile_lights=false (the per-pixel loop), with tile_size 16 and with tile_backface=false the HDR
 * image is byte-identical to the default, on the atrium with 5000 lights (cluster lists of
 * thousands: many chunks, and partial last chunks), and the default's back-face test evaluates
 * fewer lights than tile_backface=false (counter light_evals). */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "accuracy_bounds.h"
#include "default_view.h"
#include "gpu_harness.h"
#include "graph.h"
#include "image_util.h"
#include "pass_list.h"
#include "pipeline.h"
#include "scene_gpu.h"
#include "scene_vars.h"
#include "test_util.h"
#include "visibility_common.h"

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static double g_worst_px, g_worst_rmse, g_worst_share;
static size_t g_worst_apart; /* the most pixels normals_apart left out of one scene */
static int g_worst_step;
static uint32_t g_scenes;
static double g_worst_raster; /* share of pixels where raster=compute differs from hardware */
/* raster=compute: the share of pixels allowed to show another triangle than the hardware's */
#define VIS_RASTER_SHARE 0.0002

/* ---- no GPU ---- */

static void check_tri_bits(void)
{
    pg_draw draws[3];
    memset(draws, 0, sizeof draws);
    pg_scene_gpu sc;
    memset(&sc, 0, sizeof sc);
    sc.draws = draws;
    sc.n_draws = 3;
    draws[0].index_count = 3 * 1000;
    draws[1].index_count = 3 * 1024;
    draws[2].index_count = 3;
    pg_error err = {0};
    uint32_t bits = 0;
    CHECK_MSG(pg_vis_tri_bits(&sc, &bits, &err) == PG_OK && bits == 10, "1024 triangles: %u bits (%s)", bits, err.msg);
    draws[1].index_count = 3 * 1025;
    CHECK_MSG(pg_vis_tri_bits(&sc, &bits, &err) == PG_OK && bits == 11, "1025 triangles: %u bits", bits);
    /* 3 draws of up to 2^30 triangles: ids up to (2 << 30) | (2^30 - 1) fit */
    draws[0].index_count = 3u * (1u << 30);
    CHECK_MSG(pg_vis_tri_bits(&sc, &bits, &err) == PG_OK && bits == 30, "2^30 triangles: %u bits", bits);
    /* ... 2^30 + 1 need 31 bits: draw 2 << 31 overflows */
    draws[0].index_count = 3u * ((1u << 30) + 1u);
    CHECK_MSG(pg_vis_tri_bits(&sc, &bits, &err) == PG_ERR_LIMIT && strstr(err.msg, "3 draws"),
              "3 draws of 2^30+1 triangles accepted (%s)", err.msg);
    /* BLEND draws are not drawn by the visibility pass: they do not count */
    sc.n_blend_draws = 2;
    CHECK_MSG(pg_vis_tri_bits(&sc, &bits, &err) == PG_OK && bits == 31, "1 drawn draw of 2^30+1: %u bits", bits);
    printf("tri bits: checked\n");
}

static int find_pass(const pg_graph_plan *plan, const char *name)
{
    for (uint32_t i = 0; i < plan->n_passes; i++)
        if (!strcmp(plan->passes[i].name, name)) return (int)i;
    return -1;
}

static bool has_define(const pg_plan_pass *p, const char *d)
{
    for (uint32_t i = 0; i < p->decl.n_defines; i++)
        if (!strcmp(p->decl.defines[i], d)) return true;
    return false;
}

static void check_compile(const char *resolve, bool mask, bool emissive)
{
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, "pipelines/visibility.json");
    pg_param_override set = {"resolve", resolve};
    pg_pipeline *pl = NULL;
    pg_error err = {0};
    CHECK_MSG(pg_pipeline_load(path, &set, 1, &pl, &err) == PG_OK, "load: %s", err.msg);
    if (!pl) return;
    pg_compile_desc d;
    memset(&d, 0, sizeof d);
    d.pipeline = pl;
    d.registry = &g_reg;
    pg_scene_vars_set(&d.vars,
                      &(pg_scene_features){.has_textures = true, .has_alpha_mask = mask, .has_emissive = emissive},
                      1000, NULL);
    d.output_width = 320;
    d.output_height = 180;
    pg_graph_plan *plan = NULL;
    CHECK_MSG(pg_graph_compile(&d, &plan, &err) == PG_OK, "compile: %s", err.msg);
    if (plan) {
        bool shade = !strcmp(resolve, "shade");
        int v = find_pass(plan, "visibility"), s = find_pass(plan, "shade"), r = find_pass(plan, "resolve"),
            l = find_pass(plan, "lighting_packed");
        CHECK_MSG(v >= 0 && !plan->passes[v].culled, "%s: no visibility pass", resolve);
        CHECK_MSG(shade ? (s > v && r < 0 && l < 0) : (s < 0 && r > v && l > r),
                  "resolve=%s: passes visibility %d shade %d resolve %d lighting_packed %d", resolve, v, s, r, l);
        if (v >= 0) {
            CHECK_MSG(has_define(&plan->passes[v], "PG_ALPHA_MASK") == mask, "%s: alpha-test variant %s with mask=%d",
                      resolve, mask ? "missing" : "compiled", mask);
        }
        bool gb_alloc = false, em_alloc = false;
        for (uint32_t i = 0; i < plan->n_resources; i++) {
            if (!strcmp(plan->resources[i].name, "gb_packed")) gb_alloc = !plan->resources[i].culled;
            if (!strcmp(plan->resources[i].name, "gb_emissive")) em_alloc = !plan->resources[i].culled;
        }
        CHECK_MSG(gb_alloc == !shade, "resolve=%s: gb_packed %s", resolve, gb_alloc ? "allocated" : "absent");
        CHECK_MSG(em_alloc == (!shade && emissive), "resolve=%s emissive=%d: gb_emissive %s", resolve, emissive,
                  em_alloc ? "allocated" : "absent");
        printf("compile resolve=%s mask=%d emissive=%d: %u passes, checked\n", resolve, mask, emissive,
               plan->n_passes);
        pg_graph_plan_free(plan);
    }
    pg_pipeline_free(pl);
}

/* ---- images ---- */

#define VIS_NORMAL_TOL 1e-3
#define VIS_NORMAL_APART_SHARE 0.02 /* at most this share of a frame's pixels */
#define VIS_NORMAL_APART_FACTOR 4     /* measured 1.68 on an H200 (snowman), 0.45 on lavapipe (desk_lamp) */

typedef struct vis_err {
    double px_usage, apart_usage, rmse_rel, share;
    int max_step;
} vis_err;

/* the per-pixel bound's usage (pbr: VIS_PBR_PX_*) over the pixels p with (skip ? skip[p] : 0) == sel */
static double px_usage(const pg_th_frame *a, const pg_th_frame *ref, double peak, bool pbr, const uint8_t *skip,
                       uint8_t sel)
{
    double usage, need_a;
    pg_th_bound_usage_masked(a, ref, peak, pbr ? VIS_PBR_PX_A : VIS_PX_A, pbr ? VIS_PBR_PX_B : VIS_PX_B, skip, sel,
                             &usage, &need_a);
    return usage;
}

/* pbr: the per-pixel bound of the pbr light model (VIS_PBR_PX_*); skip (NULL: none): the pixels
 * whose normals differ (normals_apart), held to VIS_NORMAL_APART_FACTOR times the per-pixel bound
 * (apart_usage: the usage of that looser bound), the others to it (px_usage) */
static vis_err measure(const pg_th_frame *a, const pg_th_frame *ref, double peak, bool pbr, const uint8_t *skip)
{
    vis_err e = {0};
    size_t n = (size_t)a->w * a->h, over = 0;
    e.px_usage = px_usage(a, ref, peak, pbr, skip, 0);
    e.apart_usage = px_usage(a, ref, peak, pbr, skip, 1) / VIS_NORMAL_APART_FACTOR;
    double sum = 0;
    for (size_t i = 0; i < n * 4; i++) {
        if (i % 4 == 3) continue;
        double d = (double)a->hdr[i] - ref->hdr[i];
        sum += d * d;
    }
    e.rmse_rel = peak > 0 ? sqrt(sum / (3.0 * n)) / peak : INFINITY;
    for (size_t p = 0; p < n; p++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)a->ldr[4 * p + c] - (int)ref->ldr[4 * p + c]);
            if (d > worst) worst = d;
        }
        if (worst > e.max_step) e.max_step = worst;
        if (worst > 1) over++;
    }
    e.share = (double)over / (double)n;
    return e;
}

/* The pbr scenes' per-pixel bound assumes naive and visibility light the same surface: it holds
 * where naive's normal (the rasterizer's interpolation) and visibility's (rebuilt from the pixel's
 * ray) are within VIS_NORMAL_TOL radians, where a glint at roughness 0.2 (a = 0.04) moves by about
 * 2 x VIS_NORMAL_TOL / a = 5% < VIS_PBR_PX_A. On lavapipe the two agree to 1e-5 rad at the 99th
 * percentile; an NVIDIA GPU's interpolation is off by 2e-4 rad (median) to 1.6e-2 (docs/accuracy.md,
 * one image, two devices). skip[p] = 1 where they are further apart (the debug view `normal`,
 * rgba32f: n / 2 + 1/2, in both pipelines); returns how many, or SIZE_MAX when a render failed. */
static size_t normals_apart(const pg_scene_gpu *sg, const pg_frame_info *fi, uint8_t *skip)
{
    pg_param_override sets[2] = {{"view", "normal"}, {"hdr_format", "rgba32f"}};
    pg_th_frame a, b;
    if (!pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", sets, 2, fi, 1, false, &a)) return SIZE_MAX;
    if (!pg_th_render(g_gpu, &g_reg, sg, "pipelines/visibility.json", sets, 2, fi, 1, false, &b)) {
        pg_th_release(&a);
        return SIZE_MAX;
    }
    size_t n = (size_t)a.w * a.h, apart = 0;
    for (size_t p = 0; p < n; p++) {
        double na[3], nb[3], dot = 0, la = 0, lb = 0;
        for (int c = 0; c < 3; c++) {
            na[c] = 2.0 * a.hdr[4 * p + c] - 1.0;
            nb[c] = 2.0 * b.hdr[4 * p + c] - 1.0;
            dot += na[c] * nb[c];
            la += na[c] * na[c];
            lb += nb[c] * nb[c];
        }
        double cosang = la > 0 && lb > 0 ? dot / sqrt(la * lb) : 1.0; /* no surface in either: nothing to skip */
        skip[p] = (uint8_t)(acos(fmin(cosang, 1.0)) > VIS_NORMAL_TOL);
        apart += skip[p];
    }
    pg_th_release(&a);
    pg_th_release(&b);
    return apart;
}

/* true when e is inside the bounds (textured: only the texture bounds apply) */
static bool within(const vis_err *e, bool textured)
{
    return (textured || (e->px_usage <= 1.0 && e->apart_usage <= 1.0)) && e->rmse_rel <= VIS_RMSE_REL && e->max_step <= VIS_DISPLAY_MAX_STEP &&
           e->share <= VIS_DISPLAY_SHARE;
}

/* raster=compute (vc) against the hardware ids (vs): the same triangle at all but a few pixels
 * (VIS_RASTER_SHARE: centres on or within rounding of an edge, where the 8-bit snapping, the tie
 * rule or the interpolated depth can pick the neighbour, and alpha-tested texels where the analytic
 * and the quad derivatives pick other mip levels), so within the same bounds against naive. */
static void check_compute_raster(const char *label, const pg_th_frame *vc, const pg_th_frame *vs, const pg_th_frame *nv,
                                 double peak, bool textured, bool pbr, const uint8_t *skip)
{
    size_t n = (size_t)vc->w * vc->h, differ = 0;
    for (size_t p = 0; p < n; p++)
        if (memcmp(&vc->hdr[4 * p], &vs->hdr[4 * p], 3 * sizeof vc->hdr[0])) differ++;
    double share = (double)differ / (double)n;
    vis_err ec = measure(vc, nv, peak, pbr, skip);
    printf("%s: raster=compute vs hardware: %zu of %zu pixels differ (%.3g%%); vs naive: px usage %.3g, rmse %.3g, "
           "display max %d\n", label, differ, n, 100 * share, ec.px_usage, ec.rmse_rel, ec.max_step);
    if (share > g_worst_raster) g_worst_raster = share;
    CHECK_MSG(share <= VIS_RASTER_SHARE, "%s: raster=compute differs from hardware at %.3g%% of pixels", label,
              100 * share);
    CHECK_MSG(within(&ec, textured), "%s: raster=compute outside its bounds against naive", label);
    CHECK_MSG(pg_count_nonfinite(vc->hdr, vc->w, vc->h) == 0, "%s: raster=compute: non-finite pixels", label);
}

/* The compute rasterizer's job list overflowing (PASSGRAPH_RASTER_JOBS=4: the large triangles past
 * the 4th job are rasterized by their own invocation), and its job dispatch in rows of 7 groups
 * (PASSGRAPH_RASTER_GROUPS_X=7: the 2D grid a list of more than 65,535 jobs needs), give the same
 * ids and depth, so the same HDR image byte for byte (atomicMin does not depend on the order). */
static void check_raster_overflow(const char *label, const pg_scene_gpu *sg, const pg_frame_info *fi,
                                  const pg_th_frame *vc)
{
    pg_param_override compute = {"raster", "compute"};
    pg_th_frame f;
    static const char *const envs[2][2] = {{"PASSGRAPH_RASTER_JOBS", "4"}, {"PASSGRAPH_RASTER_GROUPS_X", "7"}};
    static const char *const what[2] = {"a job list of 4", "job rows 7 groups wide"};
    for (int v = 0; v < 2; v++) {
        setenv(envs[v][0], envs[v][1], 1);
        bool ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/visibility.json", &compute, 1, fi, 1, false, &f);
        unsetenv(envs[v][0]);
        CHECK_MSG(ok, "%s: raster=compute with %s: render failed", label, what[v]);
        if (!ok) continue;
        bool same = pg_th_hdr_identical(&f, vc);
        printf("%s: raster=compute with %s: %s\n", label, what[v], same ? "byte-identical" : "DIFFERENT");
        CHECK_MSG(same, "%s: raster=compute with %s changes the image", label, what[v]);
        pg_th_release(&f);
    }
}

static void check_frame(const char *label, const pg_scene_gpu *sg, const pg_frame_info *fi, bool control)
{
    bool textured = sg->features.has_textures || sg->features.has_normal_maps;
    bool pbr = sg->features.auto_shading == PG_SHADING_PBR; /* the model "auto" renders these with */
    pg_param_override shade = {"resolve", "shade"}, gbuf = {"resolve", "gbuffer"};
    pg_param_override compute = {"raster", "compute"};
    pg_th_frame nv, vs, vg, dp, vc;
    memset(&dp, 0, sizeof dp);
    memset(&vc, 0, sizeof vc);
    bool ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, fi, 1, false, &nv);
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/visibility.json", &shade, 1, fi, 1, false, &vs) && ok;
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/visibility.json", &gbuf, 1, fi, 1, false, &vg) && ok;
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/deferred_packed.json", NULL, 0, fi, 1, false, &dp) && ok;
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/visibility.json", &compute, 1, fi, 1, false, &vc) && ok;
    CHECK_MSG(ok, "%s: render failed", label);
    if (ok) {
        double peak = 0;
        pg_th_max_abs(&vs, &nv, &peak);
        size_t n = (size_t)vs.w * vs.h, apart = 0;
        uint8_t *skip = pbr && !textured ? calloc(n, 1) : NULL;
        if (skip) {
            apart = normals_apart(sg, fi, skip);
            CHECK_MSG(apart != SIZE_MAX, "%s: the normal views failed", label);
            CHECK_MSG(apart == SIZE_MAX || apart <= n * VIS_NORMAL_APART_SHARE,
                      "%s: naive's and visibility's normals more than %g rad apart at %zu of %zu pixels", label,
                      VIS_NORMAL_TOL, apart, n);
            printf("%s: normals more than %g rad apart at %zu of %zu pixels (held to %d x the per-pixel bound)\n",
                   label, VIS_NORMAL_TOL, apart == SIZE_MAX ? 0 : apart, n, VIS_NORMAL_APART_FACTOR);
            if (apart > g_worst_apart && apart != SIZE_MAX) g_worst_apart = apart;
        }
        vis_err es = measure(&vs, &nv, peak, pbr, skip), eg = measure(&vg, &dp, peak, pbr, NULL);
        printf("%s%s%s: peak %.4g; shade vs naive: px usage %.3g (normals apart: %.3g), rmse %.3g of peak, display max %d, "
               "%.3g%% > 1 step; gbuffer vs deferred_packed: px usage %.3g, rmse %.3g, display max %d, %.3g%% > 1; passes %s | %s\n",
               label, textured ? " (textured)" : "", pbr ? " (pbr)" : "", peak, es.px_usage, es.apart_usage, es.rmse_rel,
               es.max_step, 100 * es.share,
               eg.px_usage, eg.rmse_rel, eg.max_step, 100 * eg.share, vs.order, vg.order);
        CHECK_MSG(peak > 0, "%s: the image is black", label);
        CHECK_MSG(pg_count_nonfinite(vs.hdr, vs.w, vs.h) == 0 && pg_count_nonfinite(vg.hdr, vg.w, vg.h) == 0,
                  "%s: non-finite pixels", label);
        CHECK_MSG(within(&es, textured), "%s: resolve=shade outside its bounds", label);
        /* packed vs packed: the texture bounds, and the packed G-buffer's own per-pixel bound
         * without textures (the normal/albedo quantization steps can flip) */
        CHECK_MSG(within(&eg, true), "%s: resolve=gbuffer outside its bounds against deferred_packed", label);
        if (!textured) {
            double u = 0, na = 0;
            pg_th_bound_usage(&vg, &nv, peak, pbr ? VIS_PACKED_PBR_PX_A : PACKED_PX_A, pbr ? VIS_PACKED_PBR_PX_B : PACKED_PX_B,
                              &u, &na);
            CHECK_MSG(u <= 1.0, "%s: resolve=gbuffer outside the packed bound against naive: usage %g", label, u);
        }
        check_compute_raster(label, &vc, &vs, &nv, peak, textured, pbr, skip);
        free(skip);
        if (control || !strcmp(label, "sponza")) check_raster_overflow(label, sg, fi, &vc);
        CHECK_MSG(strstr(vs.order, "visibility,shade") != NULL, "%s: resolve=shade ran %s", label, vs.order);
        CHECK_MSG(strstr(vg.order, "visibility,resolve,lighting_packed") != NULL, "%s: resolve=gbuffer ran %s", label,
                  vg.order);
        if (!textured && es.px_usage > g_worst_px) g_worst_px = es.px_usage;
        if (es.rmse_rel > g_worst_rmse) g_worst_rmse = es.rmse_rel;
        if (es.share > g_worst_share) g_worst_share = es.share;
        if (es.max_step > g_worst_step) g_worst_step = es.max_step;
        if (control) {
            pg_frame_info half = *fi;
            half.lights.count /= 2;
            pg_th_frame h;
            if (pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, &half, 1, false, &h)) {
                vis_err ec = measure(&h, &nv, peak, pbr, NULL);
                CHECK_MSG(!within(&ec, false) && !within(&ec, true), "control: half the lights inside the bounds");
                pg_th_release(&h);
            }
        }
        g_scenes++;
    }
    pg_th_release(&nv);
    pg_th_release(&vs);
    pg_th_release(&vg);
    pg_th_release(&dp);
    pg_th_release(&vc);
}

static void check_file(const char *label, const char *path, const char *scenario, uint32_t w, uint32_t h,
                       uint32_t lights, bool control)
{
    pg_th_scene ts;
    if (!pg_th_scene_open(g_gpu, label, path, scenario, w, h, lights, &ts)) {
        CHECK_MSG(0, "%s: scene", label);
        return;
    }
    pg_error err = {0};
    char cw[256], lw[256];
    if (!scenario && strcmp(path, "default") && /* a corpus file: the tools' view (its camera, object lights) */
        pg_scene_default_view(ts.scene, NULL, (float)w / h, lights, 5, &ts.fi.camera, &ts.fi.lights, cw, sizeof cw, lw,
                            sizeof lw, &err)) {
        CHECK_MSG(0, "%s: default view: %s", label, err.msg);
    } else {
        ts.fi.lights.count = lights;
        check_frame(label, ts.sg, &ts.fi, control);
    }
    pg_th_scene_close(g_gpu, &ts);
}

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && !strcmp(s + n - k, suffix);
}

static int name_cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static void check_corpus_dir(const char *sub)
{
    char dir[PG_PATH_MAX];
    snprintf(dir, sizeof dir, "%s/corpus/gltf/%s", PG_TEST_DIR, sub);
    DIR *dh = opendir(dir);
    if (!dh) return;
    char *names[256];
    uint32_t n = 0;
    for (struct dirent *e; (e = readdir(dh)) && n < 256;)
        if ((ends_with(e->d_name, ".gltf") || ends_with(e->d_name, ".glb")) && strncmp(e->d_name, "bad_", 4))
            names[n++] = strdup(e->d_name);
    closedir(dh);
    qsort(names, n, sizeof names[0], name_cmp);
    for (uint32_t i = 0; i < n; i++) {
        char path[PG_PATH_MAX], label[PG_PATH_MAX];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        snprintf(label, sizeof label, "%s/%s", sub, names[i]);
        pg_scene *probe = NULL;
        pg_error err = {0};
        if (pg_scene_load(path, &probe, &err) == PG_OK) /* the loader's error cases: test_scene */
            check_file(label, path, NULL, 128, 72, 48, false);
        pg_scene_free(probe);
        free(names[i]);
    }
}

static void check_light_loop(void)
{
    pg_th_scene ts;
    if (!pg_th_scene_open(g_gpu, "light loop", "default", NULL, 320, 180, 5000, &ts)) {
        CHECK_MSG(0, "light loop: scene");
        return;
    }
    const pg_scene_gpu *sg = ts.sg;
    const pg_frame_info fi = ts.fi;
    static const char *const pipes[] = {"pipelines/visibility.json", "pipelines/deferred_oct16.json"};
    static const pg_param_override variants[][1] = {
        {{"tile_size", "16"}}, {{"tile_lights", "false"}}, {{"tile_backface", "false"}}};
    for (size_t p = 0; p < 2; p++) {
        pg_th_frame base;
        if (!pg_th_render(g_gpu, &g_reg, sg, pipes[p], NULL, 0, &fi, 1, false, &base)) {
            CHECK_MSG(0, "%s renders", pipes[p]);
            continue;
        }
        uint64_t refs = (uint64_t)pg_frame_counter_sum(&base.stats, "total_refs");
        uint64_t evals = (uint64_t)pg_frame_counter_sum(&base.stats, "light_evals");
        for (size_t v = 0; v < 3; v++) {
            pg_th_frame f;
            if (!pg_th_render(g_gpu, &g_reg, sg, pipes[p], variants[v], 1, &fi, 1, false, &f)) {
                CHECK_MSG(0, "%s %s=%s renders", pipes[p], variants[v][0].key, variants[v][0].value);
                continue;
            }
            bool same = pg_th_hdr_identical(&f, &base);
            printf("light loop: %s %s=%s vs default: %s (%llu light references)\n", pipes[p], variants[v][0].key,
                   variants[v][0].value, same ? "byte-identical" : "DIFFERENT", (unsigned long long)refs);
            CHECK_MSG(same, "%s: %s=%s changes the image", pipes[p], variants[v][0].key, variants[v][0].value);
            if (v == 2) {
                uint64_t all = (uint64_t)pg_frame_counter_sum(&f.stats, "light_evals");
                printf("light loop: %s light evaluations %llu, %llu without the back-face test\n", pipes[p],
                       (unsigned long long)evals, (unsigned long long)all);
                CHECK_MSG(evals > 0 && evals < all, "%s: the back-face test drops no light (%llu vs %llu)", pipes[p],
                          (unsigned long long)evals, (unsigned long long)all);
            }
            pg_th_release(&f);
        }
        pg_th_release(&base);
    }
    pg_th_scene_close(g_gpu, &ts);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    pg_register_builtin_passes(&g_reg);
    check_tri_bits();
    check_compile("shade", false, false);
    check_compile("shade", true, true);
    check_compile("gbuffer", false, false);
    check_compile("gbuffer", true, true);
    if (getenv("PG_TEST_NO_GPU")) {
        printf("test_gpu_visibility: image checks skipped: PG_TEST_NO_GPU set\n");
        return pg_test_finish("test_gpu_visibility");
    }
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_visibility: %s\n", err.msg);
        return 1;
    }
    check_light_loop();
    check_file("default", "default", NULL, 320, 180, 64, true);
#if defined(__SANITIZE_ADDRESS__)
    /* the sanitizer suite (tools/sanitize.sh) checks memory, not images: the feature files reach
     * every code path of the rebuild (vertex colours, TEXCOORD_1, transforms, samplers), and the
     * other folders and the Sponza only add frames (the normal suite renders them all) */
    static const char *const dirs[] = {"features"};
    const bool sponza = false;
    printf("test_gpu_visibility: AddressSanitizer build: only tests/corpus/gltf/features and the atrium\n");
#else
    static const char *const dirs[] = {"objects", "models", "features", "emissive", "blend"};
    const bool sponza = true;
#endif
    for (size_t d = 0; d < sizeof dirs / sizeof dirs[0]; d++) check_corpus_dir(dirs[d]);
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    if (!sponza) printf("test_gpu_visibility: Sponza skipped under AddressSanitizer\n");
    else if (getenv("PG_TEST_NO_SPONZA")) printf("test_gpu_visibility: Sponza skipped: PG_TEST_NO_SPONZA is set\n");
    else if (access(path, R_OK) == 0) check_file("sponza", path, "assets/scenarios/cis565.json", 320, 180, 256, false);
    else printf("test_gpu_visibility: Sponza skipped: %s not found\n", path);
    printf("scenes: %u; worst: untextured px usage %.3g, rmse %.3g of peak, display step %d, share > 1 step %.3g%%; "
           "raster=compute differs at %.3g%% of pixels; pbr normals apart at %zu pixels of one scene at most\n",
           g_scenes, g_worst_px, g_worst_rmse, g_worst_step, 100 * g_worst_share, 100 * g_worst_raster, g_worst_apart);
    CHECK_MSG(g_scenes >= 10, "only %u scenes", g_scenes); /* features alone: 24 */
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_visibility");
}
