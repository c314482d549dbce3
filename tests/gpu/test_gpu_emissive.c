/* test_gpu_emissive.c - emissive materials in every shipped pipeline, on lavapipe with validation +
 * synchronization validation (any message fails the test). Scenes: tests/corpus/gltf/emissive/
 * (gen_emissive.py): 'glow' (left third of the image) emits (1, 0.5, 0.25), 'lamp' (middle third)
 * (0.25, 0.5, 1) x emissiveStrength 4 = (1, 2, 4), 'matte' (right third) and the floor emit nothing;
 * plain.gltf is the same scene without any emission. 320x180, the file's camera 'front'.
 *
 *  1. 0 lights, ambient 0: every pipeline's HDR image holds exactly the emissive colour on the
 *     emissive cubes and 0 everywhere else (the values are exact in rgba16f, so no pipeline may
 *     round them), with the same pixels as naive. Controls: plain.gltf renders all black, and with
 *     ambient 0.3 the matte cube is visible in the right third (so its black above is not empty
 *     space).
 *  2. 200 lights: naive(emissive) - naive(plain) is exactly the emissive colour (to fp32 rounding
 *     of the sum) on the emissive pixels, many of them lit, and bit-identical elsewhere (the
 *     emission is added once, only where a material emits); forward+ is byte-identical to naive,
 *     the reference bit-identical to naive in rgba32f, deferred float/oct16/packed within the
 *     per-pixel bounds of tests/accuracy_bounds.h (see docs/accuracy.md),
 *     and their tiled light path (tile_lights, the default) byte-identical to the per-pixel one.
 *  3. Culling: with plain.gltf every deferred pipeline and the reference cull gb_emissive ("not used
 *     by any pass"), give it no memory block, ask for its size less transient memory (plan and
 *     runtime) than with emissive.gltf, and
 *     their G-buffer and lighting passes say "slot 'emissive' unused: no emissive materials: ...";
 *     no emissive define is compiled. With emissive.gltf the emissive variants are compiled.
 *     Forward passes: PG_EMISSIVE only with emissive.gltf, else the explain line.
 *  4. A pipeline that binds no emissive slot (deferred_without_emissive.json, written before the
 *     target existed) still compiles and renders: no emission, and an explain line says so.
 *  5. hot.gltf: an emission of (1e30, 1, 0) (inf once stored in rgba16f) comes out of every pipeline
 *     as (PG_HDR_MAX, 1, 0): sanitized like every other sum (pg_hdr_sanitize), never non-finite. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy_bounds.h"
#include "gpu_harness.h"
#include "shader.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 320
#define H 180
#define LIT_LIGHTS 200

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef struct pipe {
    const char *name, *path;
    bool deferred;       /* G-buffer + lighting pass with the emissive slot */
    double a, b;         /* bound vs naive with lights; a < 0: byte-identical (same hdr_format) */
    const char *gbuffer, *lighting; /* pass names */
} pipe;

static const pipe k_pipes[] = {
    {"naive", "pipelines/naive.json", false, -1, 0, "shade", NULL},
    {"forward_plus", "pipelines/forward_plus.json", false, -1, 0, "shade", NULL},
    {"deferred", "pipelines/deferred.json", true, FLOAT_PX_A, FLOAT_PX_B, "gbuffer", "lighting"},
    {"deferred_oct16", "pipelines/deferred_oct16.json", true, OCT16_PX_A, OCT16_PX_B, "gbuffer_oct16",
     "lighting_oct16"},
    {"deferred_packed", "pipelines/deferred_packed.json", true, PACKED_PX_A, PACKED_PX_B, "gbuffer_packed",
     "lighting_packed"},
    {"reference", "pipelines/reference.json", true, -1, 0, "surface", "shade"},
};
#define N_PIPES (sizeof k_pipes / sizeof k_pipes[0])

static const float k_glow[3] = {1.0f, 0.5f, 0.25f};
static const float k_lamp[3] = {1.0f, 2.0f, 4.0f};

typedef struct loaded {
    pg_scene *scene;
    pg_scene_gpu *sg;
} loaded;

static bool load(const char *file, loaded *out)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/emissive/%s", PG_TEST_DIR, file);
    pg_error err = {0};
    memset(out, 0, sizeof *out);
    if (pg_scene_load(path, &out->scene, &err) || pg_scene_gpu_create(g_gpu, out->scene, &out->sg, &err)) {
        CHECK_MSG(0, "%s: %s", file, err.msg);
        pg_scene_free(out->scene);
        out->scene = NULL;
        return false;
    }
    return true;
}

static void unload(loaded *l)
{
    if (l->sg) pg_scene_gpu_destroy(g_gpu, l->sg);
    pg_scene_free(l->scene);
}

static pg_frame_info frame_for(const pg_scene *scene, uint32_t lights)
{
    pg_frame_info fi = {.lights = pg_light_setup_default(scene, lights, 5), .time = 1.25f, .width = W, .height = H};
    pg_error err = {0};
    CHECK_MSG(pg_camera_from_scene(scene, 0, (float)W / H, &fi.camera, &err) == PG_OK, "camera: %s", err.msg);
    return fi;
}

static bool rgb_is(const float *px, const float *c) { return px[0] == c[0] && px[1] == c[1] && px[2] == c[2]; }
static bool rgb_zero(const float *px) { return px[0] == 0 && px[1] == 0 && px[2] == 0; }

/* 0 = other, 1 = glow, 2 = lamp; counts per kind; *bad: pixels that are neither their third's
 * emissive colour nor black. */
static void classify(const pg_th_frame *f, uint8_t *mask, uint32_t counts[3], uint32_t *bad)
{
    counts[0] = counts[1] = counts[2] = 0;
    *bad = 0;
    for (uint32_t y = 0; y < f->h; y++)
        for (uint32_t x = 0; x < f->w; x++) {
            const float *px = f->hdr + 4 * ((size_t)y * f->w + x);
            uint32_t third = x * 3 / f->w;
            uint8_t k = 0;
            if (third == 0 && rgb_is(px, k_glow)) k = 1;
            else if (third == 1 && rgb_is(px, k_lamp)) k = 2;
            else if (!rgb_zero(px)) (*bad)++;
            if (mask) mask[(size_t)y * f->w + x] = k;
            counts[k]++;
        }
}

static uint32_t nonzero_in_right_third(const pg_th_frame *f)
{
    uint32_t n = 0;
    for (uint32_t y = 0; y < f->h; y++)
        for (uint32_t x = 2 * f->w / 3 + 1; x < f->w; x++) n += !rgb_zero(f->hdr + 4 * ((size_t)y * f->w + x));
    return n;
}

static bool render(const loaded *l, const pipe *p, const pg_param_override *sets, uint32_t n_sets,
                   const pg_frame_info *fi, pg_th_frame *out)
{
    bool ok = pg_th_render(g_gpu, &g_reg, l->sg, p->path, sets, n_sets, fi, 1, false, out);
    CHECK_MSG(ok, "%s renders", p->name);
    if (ok) CHECK_MSG(pg_count_nonfinite(out->hdr, out->w, out->h) == 0, "%s: non-finite pixels", p->name);
    return ok;
}

/* ---- 1. 0 lights: exactly the emissive colour ------------------------------------------- */
static void unlit(const loaded *em, const loaded *plain, uint8_t *mask)
{
    printf("0 lights, ambient 0 (HDR read back):\n");
    pg_frame_info fi = frame_for(em->scene, 0);
    pg_th_frame ref = {0};
    bool have_ref = false;
    for (size_t i = 0; i < N_PIPES; i++) {
        const pipe *p = &k_pipes[i];
        pg_th_frame f;
        if (!render(em, p, NULL, 0, &fi, &f)) continue;
        uint32_t counts[3], bad;
        classify(&f, i == 0 ? mask : NULL, counts, &bad);
        printf("  %-16s glow %5u px, lamp %5u px, black %5u px, other %u px\n", p->name, counts[1], counts[2],
               counts[0] - bad, bad);
        CHECK_MSG(bad == 0, "%s: %u pixels are neither the emissive colour of their cube nor black", p->name, bad);
        CHECK_MSG(counts[1] > 2000 && counts[2] > 2000, "%s: emissive cubes cover %u and %u pixels", p->name,
                  counts[1], counts[2]);
        if (i == 0) {
            ref = f;
            have_ref = true;
            continue;
        }
        if (have_ref) {
            size_t diff = 0;
            for (size_t k = 0; k < (size_t)W * H; k++) diff += !rgb_is(f.hdr + 4 * k, ref.hdr + 4 * k);
            CHECK_MSG(diff == 0, "%s: %zu pixels differ from naive at 0 lights", p->name, diff);
        }
        pg_th_release(&f);
    }
    /* controls */
    pg_th_frame f;
    if (render(plain, &k_pipes[3], NULL, 0, &fi, &f)) {
        double peak;
        pg_th_max_abs(&f, &f, &peak);
        printf("  control: plain.gltf in deferred_oct16, peak %g (must be 0)\n", peak);
        CHECK_MSG(peak == 0, "plain.gltf at 0 lights is not black: peak %g", peak);
        pg_th_release(&f);
    }
    pg_param_override amb = {"ambient", "0.3"};
    if (render(em, &k_pipes[0], &amb, 1, &fi, &f)) {
        uint32_t n = nonzero_in_right_third(&f);
        printf("  control: ambient 0.3 lights %u pixels of the right third (the matte cube and the floor)\n", n);
        CHECK_MSG(n > 2000, "the matte cube is not in the right third: %u pixels", n);
        pg_th_release(&f);
    }
    if (have_ref) pg_th_release(&ref);
}

/* ---- 2. with lights ----------------------------------------------------------------------- */
/* the per-pixel bound of accuracy_bounds.h */
static bool within(const pg_th_frame *f, const pg_th_frame *ref, double a, double b, double *usage)
{
    double peak, need_a;
    pg_th_max_abs(ref, ref, &peak);
    pg_th_bound_usage(f, ref, peak, a, b, usage, &need_a);
    return *usage <= 1.0;
}

static void lit(const loaded *em, const loaded *plain, const uint8_t *mask)
{
    printf("%u lights:\n", LIT_LIGHTS);
    pg_frame_info fi = frame_for(em->scene, LIT_LIGHTS);
    pg_param_override f32 = {"hdr_format", "rgba32f"};
    pg_th_frame a, b;
    /* naive: emissive - plain = the emission, added once, only where a material emits */
    if (render(em, &k_pipes[0], &f32, 1, &fi, &a)) {
        if (render(plain, &k_pipes[0], &f32, 1, &fi, &b)) {
            uint32_t lit_emissive = 0, wrong = 0, other_diff = 0;
            double worst = 0;
            for (size_t k = 0; k < (size_t)W * H; k++) {
                const float *pa = a.hdr + 4 * k, *pb = b.hdr + 4 * k;
                if (mask[k] == 0) {
                    other_diff += !rgb_is(pa, pb);
                    continue;
                }
                const float *e = mask[k] == 1 ? k_glow : k_lamp;
                lit_emissive += !rgb_zero(pb);
                for (int c = 0; c < 3; c++) {
                    double d = fabs(((double)pa[c] - pb[c]) - e[c]), tol = 2.4e-7 * fabs(pa[c]);
                    if (d > worst) worst = d;
                    wrong += d > tol;
                }
            }
            printf("  naive rgba32f, emissive - plain: %u emissive pixels lit, worst |(a-b) - e| %g, %u channels "
                   "off, %u other pixels differ\n",
                   lit_emissive, worst, wrong, other_diff);
            CHECK_MSG(wrong == 0, "emissive - plain differs from the emissive colour on %u channels (worst %g)", wrong,
                      worst);
            CHECK_MSG(other_diff == 0, "%u non-emissive pixels changed", other_diff);
            CHECK_MSG(lit_emissive > 1000, "only %u emissive pixels are lit: the sum is not tested", lit_emissive);
            pg_th_release(&b);
        }
        /* the reference: bit-identical to naive in rgba32f */
        if (render(em, &k_pipes[5], NULL, 0, &fi, &b)) {
            bool same = pg_th_hdr_identical(&a, &b);
            printf("  %-16s vs naive (rgba32f): %s\n", "reference", same ? "bit-identical" : "DIFFERENT");
            CHECK_MSG(same, "reference differs from naive with emission");
            pg_th_release(&b);
        }
        pg_th_release(&a);
    }
    pg_th_frame ref;
    if (!render(em, &k_pipes[0], NULL, 0, &fi, &ref)) return;
    for (size_t i = 1; i < N_PIPES - 1; i++) {
        const pipe *p = &k_pipes[i];
        pg_th_frame f;
        if (!render(em, p, NULL, 0, &fi, &f)) continue;
        if (p->a < 0) {
            bool same = pg_th_hdr_identical(&f, &ref);
            printf("  %-16s vs naive: %s\n", p->name, same ? "byte-identical" : "DIFFERENT");
            CHECK_MSG(same, "%s differs from naive with emission", p->name);
        } else {
            double usage;
            bool ok = within(&f, &ref, p->a, p->b, &usage);
            printf("  %-16s vs naive: worst pixel uses %.3f of |d| <= %g |ref| + %g peak\n", p->name, usage, p->a,
                   p->b);
            CHECK_MSG(ok, "%s: outside its bound (usage %g)", p->name, usage);
            /* the tiled light path (pg_shade_tile, the default) adds the emission as the per-pixel loop */
            pg_param_override untiled = {"tile_lights", "false"};
            pg_th_frame u;
            if (render(em, p, &untiled, 1, &fi, &u)) {
                bool same = pg_th_hdr_identical(&f, &u);
                printf("  %-16s tile_lights true vs false: %s\n", p->name, same ? "byte-identical" : "DIFFERENT");
                CHECK_MSG(same, "%s: the tiled and per-pixel light paths differ with emission", p->name);
                pg_th_release(&u);
            }
        }
        pg_th_release(&f);
    }
    pg_th_release(&ref);
}

/* ---- 3. culling -------------------------------------------------------------------------- */
static const pg_plan_pass *find_pass(const pg_graph_plan *plan, const char *name)
{
    for (uint32_t i = 0; i < plan->n_passes; i++)
        if (!strcmp(plan->passes[i].name, name)) return &plan->passes[i];
    return NULL;
}

static bool has_define(const pg_plan_pass *pp, const char *def)
{
    for (uint32_t i = 0; pp && i < pp->decl.n_defines; i++)
        if (!strcmp(pp->decl.defines[i], def)) return true;
    return false;
}

static bool has_explain(const pg_plan_pass *pp, const char *line)
{
    for (uint32_t i = 0; pp && i < pp->decl.n_explain; i++)
        if (!strcmp(pp->decl.explain[i], line)) return true;
    return false;
}

/* Renders one frame (0 lights) with a session kept open to read its plan: the plan's gb_emissive
 * (NULL when the pipeline has none) and the device memory the runtime's transients asked for. */
typedef struct planned {
    pg_session *s;
    const pg_plan_resource *em;
    uint64_t memory;
} planned;

static bool plan_of(const loaded *l, const char *pipeline, planned *out)
{
    memset(out, 0, sizeof *out);
    char path[PG_PATH_MAX];
    pg_data_path(path, sizeof path, pipeline);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg};
    pg_error err = {0};
    pg_frame_info fi = frame_for(l->scene, 0);
    pg_frame_stats st;
    if (pg_session_create(g_gpu, l->sg, &sd, &out->s, &err) || pg_session_render(out->s, &fi, false, &st, &err)) {
        CHECK_MSG(0, "%s: %s", pipeline, err.msg);
        if (out->s) pg_session_destroy(out->s);
        out->s = NULL;
        return false;
    }
    for (uint32_t r = 0; r < out->s->plan->n_resources; r++)
        if (!strcmp(out->s->plan->resources[r].name, "gb_emissive")) out->em = &out->s->plan->resources[r];
    out->memory = pg_runtime_get_stats(out->s->runtime).memory_bytes_unaliased;
    return true;
}

static void culling(const loaded *em, const loaded *plain)
{
    printf("gb_emissive culling:\n");
    const char *unused = "slot 'emissive' unused: no emissive materials: emissive target not allocated";
    for (size_t i = 0; i < N_PIPES; i++) {
        const pipe *p = &k_pipes[i];
        planned a, b;
        if (!plan_of(em, p->path, &a)) continue;
        if (!plan_of(plain, p->path, &b)) {
            pg_session_destroy(a.s);
            continue;
        }
        const pg_plan_pass *ga = find_pass(a.s->plan, p->gbuffer), *gb = find_pass(b.s->plan, p->gbuffer);
        CHECK_MSG(ga && gb, "%s: pass %s", p->name, p->gbuffer);
        if (!p->deferred) {
            CHECK_MSG(has_define(ga, "PG_EMISSIVE"), "%s: PG_EMISSIVE not compiled for emissive.gltf", p->name);
            CHECK_MSG(!has_define(gb, "PG_EMISSIVE") &&
                          has_explain(gb, "no emissive materials: emissive term compiled out"),
                      "%s: plain.gltf: PG_EMISSIVE compiled or no explain line", p->name);
            printf("  %-16s PG_EMISSIVE with emissive.gltf only\n", p->name);
        } else {
            const pg_plan_pass *la = find_pass(a.s->plan, p->lighting), *lb = find_pass(b.s->plan, p->lighting);
            const char *ldef = i == N_PIPES - 1 ? "PG_REFERENCE_EMISSIVE" : "PG_DEFERRED_EMISSIVE";
            CHECK_MSG(a.em && b.em, "%s: no gb_emissive resource", p->name);
            if (a.em && b.em) {
                printf("  %-16s emissive.gltf: gb_emissive %s, transients %llu B of memory; plain.gltf: %s (%s), "
                       "block %d, %llu B\n",
                       p->name, a.em->culled ? "culled" : "allocated", (unsigned long long)a.memory,
                       b.em->culled ? "culled" : "kept", b.em->cull_reason, b.em->block, (unsigned long long)b.memory);
                CHECK_MSG(!a.em->culled && a.em->block >= 0, "%s: emissive.gltf: gb_emissive culled", p->name);
                CHECK_MSG(b.em->culled && !strcmp(b.em->cull_reason, "not used by any pass") && b.em->block < 0,
                          "%s: plain.gltf: gb_emissive culled=%d (%s) block %d", p->name, b.em->culled,
                          b.em->cull_reason, b.em->block);
                uint64_t bytes = (uint64_t)W * H * (i == N_PIPES - 1 ? 16 : 8);
                CHECK_MSG(a.memory >= b.memory + bytes, "%s: transient memory %llu B with emission, %llu B without",
                          p->name, (unsigned long long)a.memory, (unsigned long long)b.memory);
                CHECK_MSG(a.s->plan->transient_bytes_unaliased ==
                              b.s->plan->transient_bytes_unaliased + bytes,
                          "%s: transient bytes %llu with emission, %llu without", p->name,
                          (unsigned long long)a.s->plan->transient_bytes_unaliased,
                          (unsigned long long)b.s->plan->transient_bytes_unaliased);
            }
            CHECK_MSG(has_define(ga, "PG_GBUFFER_EMISSIVE") && has_define(la, ldef),
                      "%s: emissive.gltf: the emissive variants are not compiled", p->name);
            CHECK_MSG(!has_define(gb, "PG_GBUFFER_EMISSIVE") && !has_define(gb, "PG_EMISSIVE") &&
                          !has_define(lb, ldef),
                      "%s: plain.gltf: an emissive variant is compiled", p->name);
            CHECK_MSG(has_explain(gb, unused) && has_explain(lb, unused),
                      "%s: plain.gltf: no \"%s\" line in %s and %s", p->name, unused, p->gbuffer, p->lighting);
        }
        pg_session_destroy(a.s);
        pg_session_destroy(b.s);
    }
}

/* ---- 5. an emission past the half-float range is clamped like any other sum ---------------- */
static void hot(const uint8_t *mask)
{
    loaded h;
    if (!load("hot.gltf", &h)) return;
    pg_frame_info fi = frame_for(h.scene, 0);
    for (size_t i = 0; i < N_PIPES; i++) {
        pg_th_frame f;
        if (!render(&h, &k_pipes[i], NULL, 0, &fi, &f)) continue;
        /* an rgba16f output holds PG_HDR_MAX (65000) as the nearest half, 64992 (steps of 32 there) */
        const float want[3] = {f.hdr_format == PG_FMT_RGBA16F ? 64992.0f : PG_HDR_MAX, 1.0f, 0.0f};
        uint32_t glow = 0, wrong = 0;
        for (size_t k = 0; k < (size_t)W * H; k++) {
            if (mask[k] != 1) continue;
            glow++;
            wrong += !rgb_is(f.hdr + 4 * k, want);
        }
        printf("  %-16s emissive (1e30, 1, 0): %u of %u glow pixels are (%g, 1, 0)\n", k_pipes[i].name,
               glow - wrong, glow, want[0]);
        CHECK_MSG(glow > 2000 && wrong == 0, "%s: %u of %u glow pixels not clamped to (PG_HDR_MAX, 1, 0)",
                  k_pipes[i].name, wrong, glow);
        pg_th_release(&f);
    }
    unload(&h);
}

/* ---- 4. a pipeline without the emissive slot --------------------------------------------- */
static void without_slot(const loaded *em)
{
    const pipe old = {"deferred_without_emissive", "tests/corpus/gltf/emissive/deferred_without_emissive.json",
                      true, 0, 0, "gbuffer_oct16", "lighting_oct16"};
    pg_frame_info fi = frame_for(em->scene, 0);
    pg_th_frame f;
    if (render(em, &old, NULL, 0, &fi, &f)) {
        double peak;
        pg_th_max_abs(&f, &f, &peak);
        printf("pipeline without an emissive slot: renders, peak %g (no emission drawn)\n", peak);
        CHECK_MSG(peak == 0, "%s: emission drawn without the slot? peak %g", old.name, peak);
        pg_th_release(&f);
    }
    planned p;
    if (plan_of(em, old.path, &p)) {
        CHECK(has_explain(find_pass(p.s->plan, old.gbuffer),
                          "no emissive slot bound (writes[3]): emissive materials are not drawn"));
        CHECK(has_explain(find_pass(p.s->plan, old.lighting),
                          "no emissive slot bound (reads[6]): emissive materials are not drawn"));
        pg_session_destroy(p.s);
    }
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_emissive", "PG_TEST_NO_GPU is set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_emissive: %s\n", err.msg);
        return 1;
    }
    loaded em, plain;
    bool ok = load("emissive.gltf", &em);
    ok = load("plain.gltf", &plain) && ok;
    if (ok) {
        CHECK(em.scene->features.has_emissive && !plain.scene->features.has_emissive);
        uint8_t *mask = calloc((size_t)W * H, 1);
        unlit(&em, &plain, mask);
        lit(&em, &plain, mask);
        printf("emission past the rgba16f range, 0 lights:\n");
        hot(mask);
        culling(&em, &plain);
        without_slot(&em);
        free(mask);
    }
    unload(&em);
    unload(&plain);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_emissive");
}
