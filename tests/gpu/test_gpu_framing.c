/* test_gpu_framing.c - any glTF renders framed and lit with the default options: the
 * generated objects of tests/corpus/gltf/objects/ (cube, sphere, long rod, 1e-3 and 1e4 cubes, a
 * standing box, and the flat ones: a floor quad, three side-by-side panels, a panel and a wall
 * facing -Z / -X) are rendered on the Vulkan device (lavapipe) with the default view of the tools
 * (pg_scene_default_view: auto framing + object lights) at 160x90, with the validation layer and
 * synchronization validation on (zero messages). The object's pixels come from the albedo debug
 * view; they must lie fully inside the image and fill 75-92% of its width or of its height
 * (whichever the object meets first: framing fits 90%), the median object's box at least 80% of
 * the shorter image axis (docs/scenes.md), and be lit (>= 90% of them with luma > 10, mean luma
 * 40..220 of 255) without hot spots (no more than 0.5% of them with a channel >= 250: the object
 * lights keep PG_OBJECT_LIGHT_GAP away from the surfaces). The glTF camera is the default for a
 * file that has one: its image equals a render with the camera given explicitly, and differs
 * from --camera auto, which frames the object. The object default ambient (PG_OBJECT_AMBIENT, a
 * run-time value of the light set-up): with 0 lights every object pixel is albedo x 0.02 (within 0.2%: oct16 stores the albedo in sRGB8)
 * in HDR (nothing pure black), and with the ambient set to 0 it is black. */
#include <math.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

#include "default_view.h"
#include "accuracy_bounds.h"
#include "gpu_harness.h"
#include "image_util.h"
#include "pass_list.h"
#include "test_util.h"

#define W 160
#define H 90

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;

typedef struct shot {
    bool ok;
    uint32_t n_obj;                /* object pixels (albedo view not black) */
    int x0, y0, x1, y1;            /* their bounding box */
    double lit_fraction, mean_luma;/* over the object pixels, in the lit image */
    double hot_fraction;           /* object pixels with a channel >= 250 */
    uint8_t *ldr;                  /* the lit image */
} shot;

static double luma(const uint8_t *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static shot take(const char *label, const pg_scene_gpu *sg, const pg_frame_info *fi)
{
    shot s;
    memset(&s, 0, sizeof s);
    pg_param_override albedo = {"view", "albedo"};
    pg_th_frame a, l;
    if (!pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", &albedo, 1, fi, 1, false, &a)) {
        CHECK_MSG(0, "%s: albedo render", label);
        return s;
    }
    if (!pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, fi, 1, false, &l)) {
        CHECK_MSG(0, "%s: lit render", label);
        pg_th_release(&a);
        return s;
    }
    s.x0 = W;
    s.y0 = H;
    s.x1 = s.y1 = -1;
    uint32_t lit = 0;
    double sum = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            const uint8_t *pa = a.ldr + ((size_t)y * W + x) * 4, *pl = l.ldr + ((size_t)y * W + x) * 4;
            if (pa[0] + pa[1] + pa[2] == 0) continue;
            s.n_obj++;
            if ((int)x < s.x0) s.x0 = (int)x;
            if ((int)y < s.y0) s.y0 = (int)y;
            if ((int)x > s.x1) s.x1 = (int)x;
            if ((int)y > s.y1) s.y1 = (int)y;
            double lu = luma(pl);
            sum += lu;
            if (pl[0] >= 250 || pl[1] >= 250 || pl[2] >= 250) s.hot_fraction += 1;
            if (lu > 10) lit++;
        }
    s.lit_fraction = s.n_obj ? (double)lit / s.n_obj : 0;
    s.hot_fraction = s.n_obj ? s.hot_fraction / s.n_obj : 0;
    s.mean_luma = s.n_obj ? sum / s.n_obj : 0;
    s.ldr = malloc((size_t)W * H * 4);
    if (s.ldr) memcpy(s.ldr, l.ldr, (size_t)W * H * 4);
    s.ok = s.ldr != NULL;
    pg_th_release(&a);
    pg_th_release(&l);
    return s;
}

/* returns the object box's larger side over the shorter image axis; auto_framed: the default
 * framing's fill is checked (a file's camera frames as its author chose: 20-90% of the shorter
 * axis) */
static double check_framed_lit(const char *label, const shot *s, bool auto_framed)
{
    CHECK_MSG(s->ok && s->n_obj > 0, "%s: object not visible", label);
    if (!s->ok || !s->n_obj) return 0;
    double span = fmax(s->x1 - s->x0 + 1, s->y1 - s->y0 + 1) / (double)(W < H ? W : H);
    double fill = fmax((s->x1 - s->x0 + 1) / (double)W, (s->y1 - s->y0 + 1) / (double)H);
    printf("%s: object %u px, box x %d..%d y %d..%d (%.0f%% of the shorter axis, fills %.0f%%), lit %.1f%%, mean "
           "luma %.1f, hot %.2f%%\n",
           label, s->n_obj, s->x0, s->x1, s->y0, s->y1, 100 * span, 100 * fill, 100 * s->lit_fraction, s->mean_luma,
           100 * s->hot_fraction);
    CHECK_MSG(s->x0 > 0 && s->y0 > 0 && s->x1 < W - 1 && s->y1 < H - 1, "%s: object touches the border", label);
    if (auto_framed)
        CHECK_MSG(fill >= 0.75 && fill <= 0.92, "%s: object fills %.0f%% of the image", label, 100 * fill);
    else
        CHECK_MSG(span >= 0.2 && span <= 0.9, "%s: object spans %.0f%% of the shorter axis", label, 100 * span);
    CHECK_MSG(s->hot_fraction <= 0.005, "%s: %.2f%% of the object saturated (hot spots)", label,
              100 * s->hot_fraction);
    CHECK_MSG(s->lit_fraction >= 0.9, "%s: only %.1f%% of the object lit", label, 100 * s->lit_fraction);
    CHECK_MSG(s->mean_luma >= 40 && s->mean_luma <= 220, "%s: mean luma %.1f", label, s->mean_luma);
    return span;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static bool open_scene(const char *file, pg_scene **sc, pg_scene_gpu **sg)
{
    char path[PG_PATH_MAX];
    snprintf(path, sizeof path, "%s/corpus/gltf/objects/%s", PG_TEST_DIR, file);
    pg_error err = {0};
    *sc = NULL;
    *sg = NULL;
    if (pg_scene_load(path, sc, &err) || pg_scene_gpu_create(g_gpu, *sc, sg, &err)) {
        CHECK_MSG(0, "%s: %s", file, err.msg);
        pg_scene_free(*sc);
        *sc = NULL;
        return false;
    }
    return true;
}

static pg_frame_info view_of(const pg_scene *sc, const char *spec, char *why, size_t why_size)
{
    pg_frame_info fi = {.time = 0, .width = W, .height = H};
    pg_error err = {0};
    char lw[256];
    if (pg_scene_default_view(sc, spec, (float)W / H, 256, 1, &fi.camera, &fi.lights, why, why_size, lw, sizeof lw, &err))
        CHECK_MSG(0, "default view: %s", err.msg);
    return fi;
}

static void check_objects(void)
{
    const char *files[] = {"cube.gltf", "sphere.gltf", "quad.gltf",   "rod.gltf",        "tiny.gltf",  "huge.gltf",
                           "tall.gltf", "panels.gltf", "panel_back.gltf", "wall_x.gltf", "panel_tilted.gltf"};
    enum { N_FILES = sizeof files / sizeof files[0] };
    double spans[N_FILES];
    size_t n_spans = 0;
    for (size_t i = 0; i < N_FILES; i++) {
        pg_scene *sc;
        pg_scene_gpu *sg;
        if (!open_scene(files[i], &sc, &sg)) continue;
        char why[256];
        pg_frame_info fi = view_of(sc, NULL, why, sizeof why);
        CHECK_MSG(strstr(why, "auto framing") != NULL, "%s: %s", files[i], why);
        shot s = take(files[i], sg, &fi);
        spans[n_spans++] = check_framed_lit(files[i], &s, true);
        free(s.ldr);
        pg_scene_gpu_destroy(g_gpu, sg);
        pg_scene_free(sc);
    }
    if (n_spans == N_FILES) {
        qsort(spans, n_spans, sizeof spans[0], cmp_double);
        printf("objects: median box %.0f%% of the shorter axis, smallest %.0f%%\n", 100 * spans[n_spans / 2],
               100 * spans[0]);
        CHECK_MSG(spans[n_spans / 2] >= 0.8, "median object box %.0f%% of the shorter axis", 100 * spans[n_spans / 2]);
    }
}

static void check_ambient(void)
{
    pg_scene *sc;
    pg_scene_gpu *sg;
    if (!open_scene("cube.gltf", &sc, &sg)) return;
    char why[256];
    pg_frame_info fi = view_of(sc, NULL, why, sizeof why);
    CHECK_MSG(fi.lights.ambient == PG_OBJECT_AMBIENT, "object ambient %g", fi.lights.ambient);
    fi.lights.count = 0;
    pg_param_override albedo = {"view", "albedo"};
    pg_th_frame a, amb, none;
    memset(&a, 0, sizeof a);
    memset(&amb, 0, sizeof amb);
    memset(&none, 0, sizeof none);
    bool ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", &albedo, 1, &fi, 1, false, &a);
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/deferred_oct16.json", NULL, 0, &fi, 1, false, &amb) && ok;
    fi.lights.ambient = 0;
    ok = pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", NULL, 0, &fi, 1, false, &none) && ok;
    CHECK_MSG(ok, "ambient renders");
    if (ok) {
        uint32_t n_obj = 0, bad = 0, lit_none = 0;
        for (size_t i = 0; i < (size_t)W * H; i++) {
            const float *al = a.hdr + i * 4, *c = amb.hdr + i * 4, *z = none.hdr + i * 4;
            if (al[0] + al[1] + al[2] == 0) continue;
            n_obj++;
            for (int k = 0; k < 3; k++)
                if (fabsf(c[k] - PG_OBJECT_AMBIENT * al[k]) > 2e-3f * al[k] + 1e-6f) bad++;
            if (z[0] + z[1] + z[2] != 0) lit_none++;
        }
        printf("ambient: %u object pixels, %u channels off albedo x %.2f, %u lit with ambient 0\n", n_obj, bad,
               PG_OBJECT_AMBIENT, lit_none);
        CHECK_MSG(n_obj > 100 && bad == 0, "0 lights: %u of %u object pixels are not albedo x ambient", bad, n_obj);
        CHECK_MSG(lit_none == 0, "ambient 0, 0 lights: %u object pixels not black", lit_none);
    }
    pg_th_release(&a);
    pg_th_release(&amb);
    pg_th_release(&none);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(sc);
}

/* Every shipped pipeline under an orthographic camera: forward+ is bit-identical to naive (the
 * orthographic cluster bounds lose no light) and so is the reference, the deferred ones (depth
 * reconstruction through the orthographic twins) keep their shipped per-pixel bounds
 * (accuracy_bounds.h), with
 * Blinn-Phong on (the view direction is the view axis). 200 lights of a small radius so that
 * the clusters matter. */
static void check_ortho_pipelines(const pg_scene_gpu *sg, const pg_frame_info *fi0)
{
    pg_frame_info fi = *fi0;
    fi.lights.count = 200;
    fi.lights.radius *= 0.4f;
    fi.lights.intensity *= 4;
    pg_param_override sets[2] = {{"shading", "blinn_phong"}, {"hdr_format", "rgba32f"}};
    pg_th_frame ref;
    if (!pg_th_render(g_gpu, &g_reg, sg, "pipelines/naive.json", sets, 2, &fi, 1, false, &ref)) {
        CHECK_MSG(0, "orthographic: naive");
        return;
    }
    static const char *const pipes[] = {"pipelines/forward_plus.json", "pipelines/reference.json",
                                        "pipelines/deferred.json", "pipelines/deferred_oct16.json",
                                        "pipelines/deferred_packed.json"};
    static const double bound_a[] = {0, 0, FLOAT_PX_A, OCT16_PX_A, PACKED_PX_A};
    static const double bound_b[] = {0, 0, FLOAT_PX_B, OCT16_PX_B, PACKED_PX_B};
    for (size_t i = 0; i < sizeof pipes / sizeof pipes[0]; i++) {
        pg_th_frame f;
        bool exact = i <= 1;
        if (!pg_th_render(g_gpu, &g_reg, sg, pipes[i], sets, exact ? 2 : 1, &fi, 1, false, &f)) {
            CHECK_MSG(0, "orthographic: %s", pipes[i]);
            continue;
        }
        double peak = 0, d = pg_th_max_abs(&f, &ref, &peak), usage = 0, need_a = 0;
        if (!exact) pg_th_bound_usage(&f, &ref, peak, bound_a[i], bound_b[i], &usage, &need_a);
        printf("orthographic: %-32s max |d| %.3g of peak %.3g%s", pipes[i], d, peak,
               exact ? (pg_th_hdr_identical(&f, &ref) ? " (bit-identical)\n" : " (DIFFERENT)\n") : "");
        if (!exact) printf(", bound usage %.3g\n", usage);
        CHECK_MSG(peak > 0, "orthographic: %s is black", pipes[i]);
        if (exact) CHECK_MSG(pg_th_hdr_identical(&f, &ref), "orthographic: %s != naive (max |d| %g)", pipes[i], d);
        else CHECK_MSG(usage <= 1.0, "orthographic: %s outside its bound (usage %g)", pipes[i], usage);
        pg_th_release(&f);
    }
    pg_th_release(&ref);
}

static void check_cameras(void)
{
    pg_scene *sc;
    pg_scene_gpu *sg;
    if (!open_scene("camera.gltf", &sc, &sg)) return;
    char why[256];
    pg_frame_info def = view_of(sc, NULL, why, sizeof why);
    CHECK_MSG(strstr(why, "glTF camera 0 'front'") != NULL, "camera.gltf default: %s", why);
    pg_frame_info expl = def;
    pg_error err = {0};
    CHECK(pg_camera_from_scene(sc, 0, (float)W / H, &expl.camera, &err) == PG_OK);
    pg_frame_info by_name = view_of(sc, "front", why, sizeof why);
    pg_frame_info autof = view_of(sc, "auto", why, sizeof why);
    CHECK_MSG(strstr(why, "auto framing") != NULL, "camera.gltf auto: %s", why);
    shot a = take("camera.gltf default", sg, &def), b = take("camera.gltf explicit", sg, &expl),
         c = take("camera.gltf --camera front", sg, &by_name), d = take("camera.gltf --camera auto", sg, &autof);
    if (a.ok && b.ok && c.ok && d.ok) {
        CHECK_MSG(memcmp(a.ldr, b.ldr, (size_t)W * H * 4) == 0, "default != the glTF camera given explicitly");
        CHECK_MSG(memcmp(a.ldr, c.ldr, (size_t)W * H * 4) == 0, "default != --camera front");
        CHECK_MSG(memcmp(a.ldr, d.ldr, (size_t)W * H * 4) != 0, "the glTF camera renders like auto framing");
        /* the file's camera looks at the cube's centre from 3.1 units: the cube is centred */
        double cx = 0.5 * (a.x0 + a.x1), cy = 0.5 * (a.y0 + a.y1);
        CHECK_MSG(fabs(cx - W / 2.0) < 0.1 * W && fabs(cy - H / 2.0) < 0.1 * H, "glTF camera: cube centre at %.1f, %.1f",
                  cx, cy);
    }
    check_framed_lit("camera.gltf default (glTF camera)", &a, false);
    check_framed_lit("camera.gltf --camera auto", &d, true);
    free(a.ldr);
    free(b.ldr);
    free(c.ldr);
    free(d.ldr);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(sc);

    if (!open_scene("two_cameras.gltf", &sc, &sg)) return;
    pg_frame_info side = view_of(sc, NULL, why, sizeof why);
    CHECK_MSG(strstr(why, "'side'") != NULL, "two_cameras.gltf default: %s", why);
    shot s = take("two_cameras.gltf default ('side', infinite zfar)", sg, &side);
    check_framed_lit("two_cameras.gltf default ('side', infinite zfar)", &s, false);
    free(s.ldr);
    /* the orthographic camera 'top' (ymag 1, 5 units above the unit cube, looking down): the
     * cube's top face is a square of exactly H/2 pixels (1 unit of a 2-unit view height), the same
     * in x (parallel projection); and the clustered pipelines shade it with the same lights */
    pg_frame_info top = view_of(sc, "top", why, sizeof why);
    CHECK_MSG(strstr(why, "'top' (node 'top_node', orthographic)") != NULL, "two_cameras --camera top: %s", why);
    shot t = take("two_cameras.gltf --camera top (orthographic)", sg, &top);
    check_framed_lit("two_cameras.gltf --camera top (orthographic)", &t, false);
    if (t.ok)
        CHECK_MSG(t.x1 - t.x0 + 1 == H / 2 && t.y1 - t.y0 + 1 == H / 2, "orthographic top view: %dx%d px, want %dx%d",
                  t.x1 - t.x0 + 1, t.y1 - t.y0 + 1, H / 2, H / 2);
    free(t.ldr);
    check_ortho_pipelines(sg, &top);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(sc);

    /* an orthographic first camera is the default view */
    if (!open_scene("ortho_first.gltf", &sc, &sg)) return;
    pg_frame_info of = view_of(sc, NULL, why, sizeof why);
    CHECK_MSG(strstr(why, "glTF camera 0 'plan' (node 'plan_node', orthographic), the scene's first camera"),
              "ortho_first: %s", why);
    shot o = take("ortho_first.gltf default (orthographic 'plan')", sg, &of);
    check_framed_lit("ortho_first.gltf default (orthographic 'plan')", &o, false);
    free(o.ldr);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(sc);
}

/* Display difference of a against b: the largest 8-bit step over RGB and the share of pixels more
 * than one step off. */
static void display_diff(const pg_th_frame *a, const pg_th_frame *b, int *max_step, double *share)
{
    size_t n = (size_t)a->w * a->h, over = 0;
    *max_step = 0;
    for (size_t i = 0; i < n; i++) {
        int m = 0;
        for (int c = 0; c < 3; c++) m = abs((int)a->ldr[4 * i + c] - (int)b->ldr[4 * i + c]) > m ? abs((int)a->ldr[4 * i + c] - (int)b->ldr[4 * i + c]) : m;
        if (m > *max_step) *max_step = m;
        over += m > 1;
    }
    *share = (double)over / (double)n;
}

/* The Sponza (cis565, 320x180, 1000 lights) with the camera's near plane at 0.01 and 0.001 (far
 * 1000: far/near 1e5 and 1e6; glTF cameras often have such planes). oct16 rebuilds positions from
 * the D32 depth, whose precision falls with far/near (docs/accuracy.md, "Position from depth"):
 * its display bound OCT16_DISPLAY_MAX_STEP holds to far/near 1e5 (asserted, and no note); at 1e6 it
 * does not (measured 128 steps) and the frame must carry the note that says so; the image stays
 * finite. packed (a stored view depth) keeps its own bound at both. */
static void check_near_plane(void)
{
    char sponza[PG_PATH_MAX];
    snprintf(sponza, sizeof sponza, "%s/assets/dabrovic-sponza/sponza.gltf", PG_SHARED_DIR);
    pg_th_scene ts;
    if (access(sponza, R_OK) != 0) {
        printf("near plane: Sponza skipped: %s not found\n", sponza);
        return;
    }
    if (!pg_th_scene_open(g_gpu, "sponza", sponza, "assets/scenarios/cis565.json", 320, 180, 1000, &ts)) {
        CHECK_MSG(0, "near plane: Sponza did not open");
        return;
    }
    const float nears[2] = {0.01f, 0.001f};
    for (int k = 0; k < 2; k++) {
        pg_frame_info fi = ts.fi;
        fi.camera.near_z = nears[k];
        fi.camera.far_z = 1000.0f;
        pg_th_frame ref, oct, pk;
        bool ok = pg_th_render(g_gpu, &g_reg, ts.sg, "pipelines/naive.json", NULL, 0, &fi, 1, false, &ref);
        ok = pg_th_render(g_gpu, &g_reg, ts.sg, "pipelines/deferred_oct16.json", NULL, 0, &fi, 1, false, &oct) && ok;
        ok = pg_th_render(g_gpu, &g_reg, ts.sg, "pipelines/deferred_packed.json", NULL, 0, &fi, 1, false, &pk) && ok;
        CHECK_MSG(ok, "near plane %g: render", nears[k]);
        if (!ok) continue;
        int so, sp;
        double ho, hp;
        display_diff(&oct, &ref, &so, &ho);
        display_diff(&pk, &ref, &sp, &hp);
        bool noted = false;
        for (uint32_t i = 0; i < oct.stats.n_notes; i++) noted |= strstr(oct.stats.notes[i], "oct16 rebuilds") != NULL;
        printf("near plane %g (far/near %.0e): oct16 display %d steps, %.3f%% > 1%s; packed %d steps, %.3f%% > 1\n",
               nears[k], 1000.0 / nears[k], so, 100 * ho, noted ? " (noted)" : "", sp, 100 * hp);
        if (k == 0)
            CHECK_MSG(so <= OCT16_DISPLAY_MAX_STEP && ho <= OCT16_DISPLAY_SHARE, "near plane %g: oct16 %d display "
                      "steps, %.3f%% > 1", nears[k], so, 100 * ho);
        CHECK_MSG(pg_count_nonfinite(oct.hdr, oct.w, oct.h) == 0, "near plane %g: oct16 non-finite", nears[k]);
        CHECK_MSG(sp <= PACKED_DISPLAY_MAX_STEP && hp <= PACKED_DISPLAY_SHARE, "near plane %g: packed %d steps",
                  nears[k], sp);
        CHECK_MSG(noted == (k == 1), "near plane %g: the oct16 precision note is %s", nears[k],
                  noted ? "there" : "missing");
        pg_th_release(&ref);
        pg_th_release(&oct);
        pg_th_release(&pk);
    }
    pg_th_scene_close(g_gpu, &ts);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_gpu_framing", "PG_TEST_NO_GPU set");
    pg_register_builtin_passes(&g_reg);
    pg_gpu_desc gd = {.validation = true, .device_index = -1};
    pg_error err = {0};
    if (pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_gpu_framing: %s\n", err.msg);
        return 1;
    }
    check_objects();
    check_ambient();
    check_cameras();
    check_near_plane();
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    return pg_test_finish("test_gpu_framing");
}
