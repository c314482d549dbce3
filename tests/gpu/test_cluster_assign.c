#define _DEFAULT_SOURCE /* mkstemps */
/* test_cluster_assign.c - the binned light assignment (passes/cluster_assign.c, the default)
 * against the brute-force oracle (method brute_force: every light tested against every cluster
 * with the same exact sphere-vs-box test), on lavapipe with validation + synchronization
 * validation on.
 *
 * Lights come from a test pass that uploads a host array, so the sets can be hostile: lights on
 * tile edges and slice boundaries, straddling the near plane, behind the camera, past far,
 * radius 0 / negative / NaN / 1e6, NaN and huge positions, hundreds in one cluster; plus random
 * sets, extreme near/far, very wide and very narrow fields of view, odd grids, and both the
 * one-subgroup and the 64-wide workgroup paths. For every cluster the binned record (offset,
 * stored, raw) and list must equal the oracle's exactly, lists ascending. Then the approximation
 * and memory knobs: max_lights keeps the first max_lights lights of every exact list; a list
 * budget smaller than the lists keeps the first k of every exact list for one k, counts what it
 * dropped, says so in a note, and gives the same lists every frame; the list buffer grows from
 * its initial size and the frame is rendered again. Spot lights: a spot light is binned and tested by
 * the bound of its ball within its cone (pg_cone_bound_sphere), and the lists also leave it out
 * where its cone misses a cluster (cluster_light.glsl pg_cone_reaches_sphere); on a hostile set of
 * cones the binned lists equal the oracle's, no cluster box holds a sampled point inside a light's
 * range and cone whose list lacks the light, lights without a usable cone (point records, NaN,
 * wider than a half-space) keep every cluster their sphere reaches, and the test removes a share
 * of the sphere's references. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cluster_math.h"
#include "graph_execute.h"
#include "pass_list.h"
#include "render_session.h"
#include "shader.h"
#include "test_util.h"
#include "pass_set.h"
#include "vk_pipeline.h"

#define W 64
#define H 36

static pg_gpu *g_gpu;
static pg_pass_registry g_reg;
static float *g_lights;  /* 8 floats per light: position, radius, colour, 0 */
static uint32_t g_count;
static float *g_spots;   /* with g_spot_mode: 8 floats per light, its spot record (axis x scale, offset), 0s */
static bool g_spot_mode; /* the scene declares spot lights: the lights slot holds both arrays */

/* ---- a pass that copies g_lights into its "lights" slot every frame ---- */
static uint32_t g_lights_gen; /* bumped (with the device idle) when g_lights changes between frames */

typedef struct upload_pass {
    pg_buffer staging;
    uint64_t bytes;
    uint32_t gen;
} upload_pass;

static pg_result up_declare(const pg_declare_in *in, pg_pass_decl *out, pg_error *err)
{
    (void)in;
    (void)err;
    pg_decl_write(out, "lights", PG_RES_BUFFER, PG_ACCESS_TRANSFER_DST, 0, 0);
    return PG_OK;
}

static void up_copy(upload_pass *p)
{
    uint64_t n = (uint64_t)g_count * 32 < p->bytes ? (uint64_t)g_count * 32 : p->bytes;
    memcpy(p->staging.mapped, g_lights, n);
    if (g_spot_mode && 2 * n <= p->bytes) memcpy((char *)p->staging.mapped + n, g_spots, n);
    p->gen = g_lights_gen;
}

static pg_result up_create(void *self, const pg_pass_create_ctx *ctx, pg_error *err)
{
    upload_pass *p = self;
    p->bytes = ctx->slots[0]->size;
    pg_result r = pg_buffer_create(ctx->gpu, p->bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "test.lights", &p->staging,
                                   err);
    if (r) return r;
    memset(p->staging.mapped, 0, p->bytes);
    up_copy(p);
    return PG_OK;
}

static void up_record(void *self, const pg_pass_record_ctx *ctx)
{
    upload_pass *p = self;
    if (p->gen != g_lights_gen) up_copy(p); /* the lights changed while the device was idle */
    VkBufferCopy c = {0, 0, p->bytes};
    vkCmdCopyBuffer(ctx->cmd, p->staging.buffer, ctx->slots[0]->buffer, 1, &c);
}

static void up_destroy(void *self, pg_gpu *gpu)
{
    pg_buffer_destroy(gpu, &((upload_pass *)self)->staging);
}

static const pg_pass_type k_upload = {
    .name = "test_upload_lights",
    .summary = "test: host light array -> lights",
    .instance_size = sizeof(upload_pass),
    .declare = up_declare,
    .create = up_create,
    .record = up_record,
    .destroy = up_destroy,
};

/* ---- light sets ---- */
static uint32_t g_rng = 12345;
static float frand(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (float)(g_rng >> 8) / 16777216.0f;
}

static void light_clear(void)
{
    g_count = 0;
}

static void light_add(float x, float y, float z, float r)
{
    float *l = g_lights + (size_t)g_count * 8;
    l[0] = x, l[1] = y, l[2] = z, l[3] = r;
    l[4] = 0.5f + frand(), l[5] = 0.5f + frand(), l[6] = 0.5f + frand(), l[7] = 0;
    g_count++;
}

/* camera at the origin looking down -Z: view space == world space */
static pg_camera camera(float fov, float near_z, float far_z)
{
    pg_camera c = {.position = {0, 0, 0}, .target = {0, 0, -1}, .up = {0, 1, 0}, .fov_y_deg = fov,
                   .near_z = near_z, .far_z = far_z, .aspect = (float)W / H};
    return c;
}

static float slice_depth(uint32_t k, uint32_t gz, float n, float f)
{
    return (float)(n * pow((double)f / n, (double)k / gz));
}

/* Lights on tile edges and slice boundaries (centres and spheres just touching them) and every
 * other hostile case, for a camera (fov, near, far) and grid. */
static void hostile_set(float fov, float n, float f, uint32_t gx, uint32_t gy, uint32_t gz)
{
    double ty = tan(fov * M_PI / 360.0), tx = ty * W / H;
    for (uint32_t k = 0; k <= gz; k += (gz > 8 ? 3 : 1)) {
        float d = slice_depth(k, gz, n, f);
        for (uint32_t ex = 0; ex <= gx; ex += (gx > 8 ? 2 : 1))
            for (uint32_t ey = 0; ey <= gy; ey += 2) {
                float x = (float)((2.0 * ex / gx - 1.0) * tx * d);
                float y = (float)((1.0 - 2.0 * ey / gy) * ty * d);
                light_add(x, y, -d, d * 1e-4f);          /* tiny sphere on the edge */
                light_add(x, y, -d, 0.05f * d);          /* small */
                light_add(x + 0.05f * d, y, -d, 0.05f * d); /* touching the edge from one side */
            }
    }
    /* straddling the near plane, behind the camera (reaching / not reaching), past far */
    for (int i = 0; i < 20; i++) {
        float r = n * (0.5f + i);
        light_add((frand() - 0.5f) * n * 4, (frand() - 0.5f) * n * 4, -n + (frand() - 0.5f) * r, r);
    }
    light_add(0, 0, 5 * n, 4 * n);     /* behind, reaches nothing */
    light_add(0, 0, 5 * n, 6 * n);     /* behind, reaches past near */
    light_add(0, 0, 3, 2);             /* behind, not reaching z = 0 when near > 1 */
    light_add(0, 0, -f * 1.5f, f * 0.6f); /* past far, reaching back in */
    light_add(0, 0, -f * 3.0f, f * 0.5f); /* past far, not reaching */
    /* degenerate radii and positions */
    light_add(0, 0, -(n + f) * 0.01f, 0.0f);
    light_add(1, 0, -(n + f) * 0.01f, -1.0f);
    light_add(0, 1, -(n + f) * 0.01f, NAN);
    light_add(NAN, 0, -10, 1);
    light_add(INFINITY, 0, -10, 1);
    light_add(1e30f, 1e30f, -1e30f, 1e29f);
    light_add(0, 0, -(n + f) * 0.01f, 1e6f); /* reaches everything */
    /* many lights in one cluster */
    float d = slice_depth(gz / 2, gz, n, f) * 1.01f;
    for (int i = 0; i < 300; i++) light_add((float)(tx * d * 0.01), (float)(ty * d * 0.01), -d, d * 1e-3f);
}

static void random_set(uint32_t count, float n, float f, float rmin, float rmax)
{
    for (uint32_t i = 0; i < count; i++) {
        float d = (float)(n * pow((double)f / n, frand() * 1.05 - 0.02));
        float x = (frand() * 2.4f - 1.2f) * d, y = (frand() * 1.6f - 0.8f) * d;
        light_add(x, y, -d, rmin + (rmax - rmin) * frand() * frand());
    }
}

/* ---- render one frame of the oracle pipeline and read the lists back ---- */
typedef struct lists {
    uint32_t clusters;
    uint32_t *rec;     /* 4 per cluster */
    uint32_t *list;
    uint64_t list_words;
} lists;

typedef struct run_result {
    lists binned, oracle;
    pg_frame_stats st;
    uint32_t growths;        /* frames whose lists grew (run_desc.grow) */
    double worst_headroom;   /* max over frames of list_bytes / (4 x needed_refs) after growing */
    bool ok;
} run_result;

static void lists_free(lists *l)
{
    free(l->rec);
    free(l->list);
    memset(l, 0, sizeof *l);
}

static bool read_lists(pg_session *s, const char *counts, const char *names, uint32_t clusters, lists *out)
{
    pg_error err = {0};
    out->clusters = clusters;
    out->rec = calloc((size_t)clusters * 4, 4);
    out->list_words = pg_runtime_buffer_size(s->runtime, names) / 4;
    out->list = calloc(out->list_words ? out->list_words : 1, 4);
    if (!out->rec || !out->list) return false;
    if (pg_runtime_read_buffer(s->runtime, counts, 0, (uint64_t)clusters * 16, out->rec, &err) ||
        pg_runtime_read_buffer(s->runtime, names, 0, out->list_words * 4, out->list, &err)) {
        fprintf(stderr, "read back: %s\n", err.msg);
        return false;
    }
    return true;
}

static const char *k_pipeline_fmt =
    "{\"name\": \"assign_oracle\",\n"
    " \"resources\": [\n"
    "  {\"name\": \"lights\", \"type\": \"buffer\", \"stride\": 32, \"count\": [\"lights\"]},\n"
    "  {\"name\": \"cluster_counts\", \"type\": \"buffer\", \"stride\": 16, \"count\": [%u, %u, %u]},\n"
    "  {\"name\": \"cluster_lights\", \"type\": \"buffer\", \"stride\": 4, \"count\": [%u, %u, %u, 4], \"grow\": true},\n"
    "  {\"name\": \"oracle_counts\", \"type\": \"buffer\", \"stride\": 16, \"count\": [%u, %u, %u]},\n"
    "  {\"name\": \"oracle_lights\", \"type\": \"buffer\", \"stride\": 4, \"count\": [%u, %u, %u, 4], \"grow\": true},\n"
    "  {\"name\": \"hdr\", \"type\": \"image\", \"format\": \"rgba16f\"},\n"
    "  {\"name\": \"depth\", \"type\": \"image\", \"format\": \"d32f\"}],\n"
    " \"passes\": [\n"
    "  {\"name\": \"upload\", \"type\": \"test_upload_lights\", \"writes\": [\"lights\"]},\n"
    "  {\"name\": \"assign\", \"type\": \"cluster_assign\", \"reads\": [\"lights\"], \"writes\": [\"cluster_counts\", "
    "\"cluster_lights\"],\n"
    "   \"options\": {\"max_lights\": %u, \"budget_mb\": %g, "
    "\"subgroups\": %s}},\n"
    "  {\"name\": \"oracle\", \"type\": \"cluster_assign\", \"reads\": [\"lights\"], \"writes\": [\"oracle_counts\", "
    "\"oracle_lights\"], \"side_effects\": true,\n"
    "   \"options\": {\"method\": \"brute_force\"}},\n"
    "  {\"name\": \"shade\", \"type\": \"forward_plus\", \"reads\": [\"lights\", \"cluster_counts\", \"cluster_lights\"], "
    "\"writes\": [\"hdr\", \"depth\"]}],\n"
    " \"output\": \"hdr\"}\n";

typedef struct run_desc {
    uint32_t grid[3];
    uint32_t max_lights;
    double budget_mb;
    bool subgroups;
    pg_camera cam;
    uint32_t frames;
    float grow;          /* > 0: every light's radius times this before each frame after the first */
} run_desc;

static uint64_t counter(const pg_frame_stats *st, const char *pass, const char *name);

static run_result run(const pg_scene_gpu *sg, const run_desc *d)
{
    run_result res = {0};
    const uint32_t *g = d->grid;
    char path[] = "/tmp/pg_assign_oracle_XXXXXX.json";
    int fd = mkstemps(path, 5);
    if (fd < 0) return res;
    FILE *f = fdopen(fd, "w");
    fprintf(f, k_pipeline_fmt, g[0], g[1], g[2], g[0], g[1], g[2], g[0], g[1], g[2], g[0], g[1], g[2], d->max_lights,
            d->budget_mb, d->subgroups ? "true" : "false");
    fclose(f);
    pg_session_desc sd = {.pipeline_path = path, .registry = &g_reg, .disable_aliasing = true};
    pg_session *s = NULL;
    pg_error err = {0};
    if (pg_session_create(g_gpu, sg, &sd, &s, &err)) {
        fprintf(stderr, "session: %s\n", err.msg);
        unlink(path);
        return res;
    }
    pg_frame_info fi = {.camera = d->cam, .width = W, .height = H};
    fi.lights.count = g_count;
    bool ok = true;
    for (uint32_t k = 0; k < (d->frames ? d->frames : 1) && ok; k++) {
        if (k && d->grow > 0) {
            vkDeviceWaitIdle(g_gpu->device);
            for (uint32_t i = 0; i < g_count; i++) g_lights[(size_t)i * 8 + 3] *= d->grow;
            g_lights_gen++;
        }
        if (pg_session_render(s, &fi, false, &res.st, &err)) {
            fprintf(stderr, "render: %s\n", err.msg);
            ok = false;
        } else if (res.st.n_grown) {
            res.growths++;
            double need = 4.0 * (double)counter(&res.st, "assign", "needed_refs");
            double have = (double)counter(&res.st, "assign", "list_bytes");
            if (need > 0 && have / need > res.worst_headroom) res.worst_headroom = have / need;
        }
    }
    uint32_t clusters = g[0] * g[1] * g[2];
    ok = ok && read_lists(s, "cluster_counts", "cluster_lights", clusters, &res.binned) &&
         read_lists(s, "oracle_counts", "oracle_lights", clusters, &res.oracle);
    res.ok = ok;
    pg_session_destroy(s);
    unlink(path);
    return res;
}

static void run_free(run_result *r)
{
    lists_free(&r->binned);
    lists_free(&r->oracle);
}

static uint64_t counter(const pg_frame_stats *st, const char *pass, const char *name)
{
    for (uint32_t k = 0; k < st->n_counters; k++)
        if (!strcmp(st->counters[k].pass, pass) && !strcmp(st->counters[k].name, name)) return st->counters[k].value;
    return UINT64_MAX;
}

/* Every cluster: binned == oracle (records and lists), lists ascending. Returns the raw refs. */
static uint64_t check_equal(const char *label, const run_result *r)
{
    uint64_t raw = 0, mismatched = 0, unsorted = 0, nonempty = 0;
    for (uint32_t c = 0; c < r->binned.clusters; c++) {
        const uint32_t *b = r->binned.rec + 4 * c, *o = r->oracle.rec + 4 * c;
        raw += o[2];
        nonempty += o[2] > 0;
        bool same = b[1] == o[1] && b[2] == o[2] && b[1] == b[2];
        for (uint32_t k = 0; same && k < b[1]; k++) {
            if ((uint64_t)b[0] + k >= r->binned.list_words || (uint64_t)o[0] + k >= r->oracle.list_words) {
                same = false;
                break;
            }
            uint32_t lb = r->binned.list[b[0] + k], lo = r->oracle.list[o[0] + k];
            if (lb != lo) same = false;
            if (k && lb <= r->binned.list[b[0] + k - 1]) unsorted++;
        }
        if (!same) {
            if (mismatched < 5)
                fprintf(stderr, "  %s: cluster %u: binned (%u stored, %u raw) vs oracle (%u stored, %u raw)\n", label, c,
                        b[1], b[2], o[1], o[2]);
            mismatched++;
        }
    }
    printf("  %-28s lights %6u  refs %8llu  clusters with lights %5llu/%u  mismatched %llu  grew %u\n", label, g_count,
           (unsigned long long)raw, (unsigned long long)nonempty, r->binned.clusters, (unsigned long long)mismatched,
           r->st.n_grown);
    CHECK_MSG(mismatched == 0, "%s: %llu clusters differ from the oracle", label, (unsigned long long)mismatched);
    CHECK_MSG(unsorted == 0, "%s: %llu list entries out of order", label, (unsigned long long)unsorted);
    CHECK_MSG(nonempty > 0, "%s: no cluster has a light (the comparison would be vacuous)", label);
    CHECK_MSG(counter(&r->st, "assign", "overflow_dropped") == 0, "%s: dropped references", label);
    return raw;
}

static void oracle_cases(const pg_scene_gpu *sg)
{
    struct {
        const char *label;
        float fov, n, f;
        uint32_t grid[3];
        bool subgroups;
        int set; /* 0 hostile, 1 random, 2 many small random */
    } cases[] = {
        {"hostile 16x9x24", 60, 0.1f, 1000, {16, 9, 24}, true, 0},
        {"hostile 16x9x24 wg64", 60, 0.1f, 1000, {16, 9, 24}, false, 0},
        {"hostile near 1e-4 far 1e7", 60, 1e-4f, 1e7f, {16, 9, 24}, true, 0},
        {"hostile fov 150", 150, 0.5f, 500, {16, 9, 24}, true, 0},
        {"hostile fov 1", 1, 1.0f, 5000, {16, 9, 24}, true, 0},
        {"hostile grid 7x5x11", 60, 0.1f, 300, {7, 5, 11}, true, 0},
        {"hostile grid 1x1x1", 60, 0.1f, 300, {1, 1, 1}, true, 0},
        {"random 4000 r 0.1..20", 60, 0.5f, 1000, {16, 9, 24}, true, 1},
        {"random 4000 grid 32x18x48", 60, 0.5f, 1000, {32, 18, 48}, false, 1},
        {"random 40000 (3 segments)", 60, 0.5f, 1000, {16, 9, 24}, true, 2},
        {"random 40000 (3 segs) wg64", 60, 0.5f, 1000, {16, 9, 24}, false, 2},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        light_clear();
        if (cases[i].set == 0) hostile_set(cases[i].fov, cases[i].n, cases[i].f, cases[i].grid[0], cases[i].grid[1],
                                           cases[i].grid[2]);
        else if (cases[i].set == 1) random_set(4000, cases[i].n, cases[i].f, 0.1f, 20.0f);
        else random_set(40000, cases[i].n, cases[i].f, 0.05f, 3.0f); /* > 16,384: several segments */
        run_desc d = {.grid = {cases[i].grid[0], cases[i].grid[1], cases[i].grid[2]}, .budget_mb = 1024,
                      .subgroups = cases[i].subgroups, .cam = camera(cases[i].fov, cases[i].n, cases[i].f)};
        run_result r = run(sg, &d);
        CHECK_MSG(r.ok, "%s: render failed", cases[i].label);
        if (r.ok) check_equal(cases[i].label, &r);
        /* the lists started at 4 per cluster: a dense set must have grown them */
        if (r.ok && i == 0) CHECK_MSG(r.st.n_grown >= 1 && r.st.rerenders >= 1, "hostile: the lists did not grow");
        run_free(&r);
    }
}

/* ---- spot lights: the cone test of the lists ---- */
static void spot_set(uint32_t i, float ax, float ay, float az, float outer, float inner)
{
    float *sp = g_spots + (size_t)i * 8;
    memset(sp, 0, 8 * sizeof(float));
    double len = sqrt((double)ax * ax + (double)ay * ay + (double)az * az);
    double scale = 1.0 / fmax(cos(inner) - cos(outer), 1e-3); /* the extension's (renderer: light upload) */
    sp[0] = (float)(ax / len * scale), sp[1] = (float)(ay / len * scale), sp[2] = (float)(az / len * scale);
    sp[3] = (float)(-cos(outer) * scale);
}

static void spot_none(uint32_t i, float w) /* a record without a usable cone: (0, 0, 0, w) */
{
    float *sp = g_spots + (size_t)i * 8;
    memset(sp, 0, 8 * sizeof(float));
    sp[3] = w;
}

/* A spot set (camera at the origin looking down -Z: view = world): seeded random cones of every
 * orientation and width in the frustum, cones whose apex sits on tile edges and slice boundaries
 * with axes along the tile planes, and twins of ten lights (the same sphere) without a usable cone:
 * a point record, a NaN record, a cone wider than a half-space. Returns the first twin. */
static uint32_t spot_hostile_set(float fov, float n, float f, uint32_t gx, uint32_t gy, uint32_t gz)
{
    static const float outers[] = {0.005f, 0.05f, 0.2f, 0.5f, 0.9f, 1.3f, 1.5707964f};
    double ty = tan(fov * M_PI / 360.0), tx = ty * W / H;
    for (uint32_t i = 0; i < 700; i++) {
        float d = (float)(n * pow((double)f / n, frand() * 0.8));
        light_add((frand() * 2.4f - 1.2f) * (float)tx * d, (frand() * 2.0f - 1.0f) * (float)ty * d, -d,
                  d * (0.05f + 0.6f * frand()));
        float o = outers[i % 7];
        spot_set(g_count - 1, frand() - 0.5f, frand() - 0.5f, frand() - 0.5f, o, o * frand());
    }
    for (uint32_t k = 1; k < gz; k += 5) { /* on edges, axes along the tile planes and the view axis */
        float d = slice_depth(k, gz, n, f);
        for (uint32_t ex = 1; ex < gx; ex += 3) {
            float x = (float)((2.0 * ex / gx - 1.0) * tx * d);
            light_add(x, 0.0f, -d, 0.4f * d);
            spot_set(g_count - 1, 0.0f, 1.0f, 0.0f, 0.3f, 0.1f);
            light_add(x, 0.0f, -d, 0.4f * d);
            spot_set(g_count - 1, 0.0f, 0.0f, -1.0f, 0.05f, 0.0f);
            light_add(x, 0.0f, -d, 0.4f * d);
            spot_set(g_count - 1, 1.0f, 0.0f, 0.0f, 1.5707964f, 1.0f);
        }
        for (uint32_t ey = 1; ey < gy; ey += 2) {
            float y = (float)((1.0 - 2.0 * ey / gy) * ty * d);
            light_add(0.0f, y, -d, 0.4f * d);
            spot_set(g_count - 1, 1.0f, 0.0f, 0.0f, 0.4f, 0.2f);
            light_add(0.0f, y, -d, 0.4f * d);
            spot_set(g_count - 1, 0.0f, -1.0f, 0.0f, 1.0f, 0.5f);
        }
    }
    uint32_t twins = g_count;
    for (uint32_t i = 0; i < 10; i++) {
        const float *src = g_lights + (size_t)i * 8;
        for (int t = 0; t < 3; t++) {
            light_add(src[0], src[1], src[2], src[3]);
            spot_none(g_count - 1, t == 0 ? 1.0f : t == 1 ? NAN : 0.5f); /* point, NaN, cos(outer) = -0.5 */
            if (t == 2) g_spots[(size_t)(g_count - 1) * 8] = 1.0f; /* axis (1, 0, 0), offset 0.5: 120 degrees */
        }
    }
    return twins;
}

static bool in_list(const lists *l, uint32_t c, uint32_t light)
{
    const uint32_t *rec = l->rec + 4 * c;
    for (uint32_t k = 0; k < rec[1]; k++)
        if (l->list[rec[0] + k] == light) return true;
    return false;
}

/* Is some sampled point of the box within the light's range and strictly inside its cone (the
 * shading's cone factor > 0 there)? 9 x 9 x 9 points, corners and faces included. */
static bool box_point_lit(const float *lt, const float *sp, pg_vec3 mn, pg_vec3 mx)
{
    double scale = sqrt((double)sp[0] * sp[0] + (double)sp[1] * sp[1] + (double)sp[2] * sp[2]);
    double cos_outer = -sp[3] / scale;
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++)
            for (int k = 0; k < 9; k++) {
                double p[3] = {mn.x + (mx.x - mn.x) * i / 8.0, mn.y + (mx.y - mn.y) * j / 8.0,
                               mn.z + (mx.z - mn.z) * k / 8.0};
                double v[3] = {p[0] - lt[0], p[1] - lt[1], p[2] - lt[2]};
                double d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                if (!(d2 < (double)lt[3] * lt[3]) || d2 == 0.0) continue;
                double c = (v[0] * sp[0] + v[1] * sp[1] + v[2] * sp[2]) / (scale * sqrt(d2));
                if (c > cos_outer + 1e-6) return true;
            }
    return false;
}

static void spot_cases(pg_scene_gpu *sg)
{
    const float fov = 60, n = 0.1f, f = 200;
    const uint32_t grid[3] = {16, 9, 24};
    light_clear();
    uint32_t twins = spot_hostile_set(fov, n, f, grid[0], grid[1], grid[2]);
    sg->features.has_spot_lights = g_spot_mode = true; /* what the passes compile for */
    run_desc d = {.grid = {grid[0], grid[1], grid[2]}, .budget_mb = 1024, .subgroups = true, .cam = camera(fov, n, f)};
    run_result r = run(sg, &d);
    sg->features.has_spot_lights = g_spot_mode = false;
    CHECK_MSG(r.ok, "spots: render failed");
    if (!r.ok) {
        run_free(&r);
        return;
    }
    check_equal("spots", &r);
    float proj[16], inv[16];
    pg_camera_proj(&d.cam, proj);
    CHECK(pg_mat4_invert(proj, inv));
    uint64_t sphere_refs = 0, listed = 0, missed = 0, twin_differ = 0;
    pg_uvec3 g3 = {grid[0], grid[1], grid[2]};
    for (uint32_t c = 0; c < grid[0] * grid[1] * grid[2]; c++) {
        pg_uvec3 cc = {c % grid[0], (c / grid[0]) % grid[1], c / (grid[0] * grid[1])};
        pg_vec3 mn, mx;
        pg_cluster_aabb(cc, g3, inv, n, f, &mn, &mx);
        for (uint32_t i = 0; i < g_count; i++) {
            const float *lt = g_lights + (size_t)i * 8;
            bool sphere = pg_sphere_intersects_aabb((pg_vec3){lt[0], lt[1], lt[2]}, lt[3], mn, mx);
            bool has = in_list(&r.binned, c, i);
            if (i >= twins) { /* no usable cone: listed exactly where the point-record twin is */
                uint32_t base = twins + (i - twins) / 3 * 3;
                twin_differ += has != in_list(&r.binned, c, base);
                continue;
            }
            sphere_refs += sphere;
            listed += has;
            if (sphere && !has && box_point_lit(lt, g_spots + (size_t)i * 8, mn, mx)) {
                if (missed++ < 5)
                    fprintf(stderr, "  spots: cluster %u lacks light %u, which lights a point of its box\n", c, i);
            }
        }
    }
    printf("  %-28s %llu of %llu sphere references kept by the cone tests (%.1f%%)\n", "spots", (unsigned long long)listed,
           (unsigned long long)sphere_refs, sphere_refs ? 100.0 * listed / sphere_refs : 0.0);
    CHECK_MSG(missed == 0, "spots: %llu (cluster, light) pairs lack a light that lights a sampled point of the box",
              (unsigned long long)missed);
    CHECK_MSG(twin_differ == 0, "spots: %llu clusters list a cone-less twin differently from its point twin",
              (unsigned long long)twin_differ);
    /* the test does something: the random cones miss much of what their spheres reach */
    CHECK_MSG(listed < sphere_refs * 3 / 4, "spots: the cone test kept %llu of %llu sphere references",
              (unsigned long long)listed, (unsigned long long)sphere_refs);
    run_free(&r);
}

/* max_lights and the list budget: deterministic subsets of the exact lists, counted */
static void knob_cases(const pg_scene_gpu *sg)
{
    light_clear();
    random_set(6000, 0.5f, 1000, 1.0f, 60.0f);
    run_desc base = {.grid = {16, 9, 24}, .budget_mb = 1024, .subgroups = true, .cam = camera(60, 0.5f, 1000)};
    run_result exact = run(sg, &base);
    CHECK(exact.ok);
    if (!exact.ok) return;
    uint64_t raw = check_equal("knobs: exact", &exact);

    /* max_lights = 7: every cluster keeps the first 7 of its exact list */
    run_desc capd = base;
    capd.max_lights = 7;
    run_result cap = run(sg, &capd);
    CHECK(cap.ok);
    uint64_t dropped = 0, bad = 0;
    for (uint32_t c = 0; cap.ok && c < cap.binned.clusters; c++) {
        const uint32_t *b = cap.binned.rec + 4 * c, *o = exact.oracle.rec + 4 * c;
        uint32_t want = o[2] < 7 ? o[2] : 7;
        dropped += o[2] - want;
        bool okc = b[1] == want && b[2] == o[2];
        for (uint32_t k = 0; okc && k < want; k++) okc = cap.binned.list[b[0] + k] == exact.oracle.list[o[0] + k];
        bad += !okc;
    }
    printf("  %-28s dropped %llu of %llu refs, counted %llu\n", "knobs: max_lights 7", (unsigned long long)dropped,
           (unsigned long long)raw, (unsigned long long)counter(&cap.st, "assign", "overflow_dropped"));
    CHECK_MSG(bad == 0, "max_lights: %llu clusters are not the prefix of their exact list", (unsigned long long)bad);
    CHECK(dropped > 0);
    CHECK(counter(&cap.st, "assign", "overflow_dropped") == dropped);
    CHECK(counter(&cap.st, "assign", "dropped_cap") == dropped);
    run_free(&cap);

    /* budget 1 MiB (262,144 refs) for more refs than that: one k for every cluster, counted, noted,
     * the same lists on every frame */
    CHECK_MSG(raw > 262144, "the knob set has %llu refs: too few to exceed a 1 MiB budget", (unsigned long long)raw);
    run_desc bud = base;
    bud.budget_mb = 1;
    bud.frames = 3;
    run_result b1 = run(sg, &bud), b2 = run(sg, &bud);
    CHECK(b1.ok && b2.ok);
    if (b1.ok && b2.ok) {
        uint32_t k = 0;
        uint64_t kept = 0;
        for (uint32_t c = 0; c < b1.binned.clusters; c++) {
            const uint32_t *r1 = b1.binned.rec + 4 * c;
            if (r1[1] < r1[2] && (k == 0 || r1[1] < k)) k = r1[1];
            kept += r1[1];
        }
        uint64_t bad_subset = 0, differ = 0;
        for (uint32_t c = 0; c < b1.binned.clusters; c++) {
            const uint32_t *r1 = b1.binned.rec + 4 * c, *r2 = b2.binned.rec + 4 * c, *o = exact.oracle.rec + 4 * c;
            uint32_t want = o[2] < k ? o[2] : k;
            bool okc = r1[1] == want && r1[2] == o[2];
            for (uint32_t j = 0; okc && j < want; j++) okc = b1.binned.list[r1[0] + j] == exact.oracle.list[o[0] + j];
            bad_subset += !okc;
            bool same = r1[0] == r2[0] && r1[1] == r2[1] && r1[2] == r2[2];
            for (uint32_t j = 0; same && j < r1[1]; j++) same = b1.binned.list[r1[0] + j] == b2.binned.list[r2[0] + j];
            differ += !same;
        }
        uint64_t counted = counter(&b1.st, "assign", "overflow_dropped");
        printf("  %-28s k %u  kept %llu of %llu refs (capacity %llu)  counted dropped %llu  note: %s\n",
               "knobs: budget 1 MiB", k, (unsigned long long)kept, (unsigned long long)raw,
               (unsigned long long)b1.binned.list_words, (unsigned long long)counted,
               b1.st.n_notes ? b1.st.notes[0] : "(none)");
        CHECK(k > 0);
        CHECK(kept <= 262144 && kept <= b1.binned.list_words);
        CHECK_MSG(bad_subset == 0, "budget: %llu clusters are not min(raw, k) prefixes", (unsigned long long)bad_subset);
        CHECK_MSG(differ == 0, "budget: %llu clusters differ between two runs", (unsigned long long)differ);
        CHECK(counted == raw - kept);
        CHECK(counter(&b1.st, "assign", "overflow_clusters") > 0);
        CHECK_MSG(b1.st.n_notes >= 1 && strstr(b1.st.notes[0], "budget"), "budget: no note says the budget was short");
        CHECK(counter(&b1.st, "assign", "list_bytes") <= 1048576);
    }
    run_free(&b1);
    run_free(&b2);

    /* growth: every radius x1.3 on each of 4 frames, so the lists grow several times in one
     * session; the buffer must stay within 1.25x the references the frame needs (it grows to
     * needed + 1/8; it grew to twice its size before: 2.00x after two growths) */
    run_desc gr = base;
    gr.frames = 5;
    gr.grow = 1.3f;
    light_clear();
    random_set(3000, 0.5f, 1000, 0.5f, 8.0f);
    run_result g = run(sg, &gr);
    CHECK(g.ok);
    printf("  %-28s %u frames grew the lists, list bytes at most %.3fx the needed references\n", "knobs: growth",
           g.growths, g.worst_headroom);
    CHECK_MSG(g.growths >= 3, "growth: only %u growths (the case needs several)", g.growths);
    CHECK_MSG(g.worst_headroom <= 1.25, "growth: the lists hold %.3fx the bytes they need", g.worst_headroom);
    if (g.ok) check_equal("knobs: after growth", &g);
    run_free(&g);
    run_free(&exact);
}

int main(void)
{
    if (getenv("PG_TEST_NO_GPU")) return pg_test_skip("test_cluster_assign", "PG_TEST_NO_GPU set");
    pg_error err = {0};
    pg_register_builtin_passes(&g_reg);
    if (pg_registry_add(&g_reg, &k_upload, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    g_lights = calloc((size_t)65536 * 8, sizeof(float));
    g_spots = calloc((size_t)65536 * 8, sizeof(float));
    pg_gpu_desc gd = {.validation = true, .device_index = -1, .quiet = true};
    if (!g_lights || !g_spots || pg_gpu_create(&gd, &g_gpu, &err)) {
        fprintf(stderr, "test_cluster_assign: %s\n", err.msg);
        return 1;
    }
    CHECK_MSG(g_gpu->debug_utils, "no VK_EXT_debug_utils: validation messages could not be seen");
    pg_scene *scene = NULL;
    pg_scene_gpu *sg = NULL;
    if (pg_scene_create_default(&scene, &err) || pg_scene_gpu_create(g_gpu, scene, &sg, &err)) {
        fprintf(stderr, "test_cluster_assign: %s\n", err.msg);
        return 1;
    }
    printf("subgroup size %u, one-subgroup workgroups %s\n", g_gpu->subgroup_size, g_gpu->exact_subgroups ? "yes" : "no");
    oracle_cases(sg);
    spot_cases(sg);
    knob_cases(sg);
    pg_scene_gpu_destroy(g_gpu, sg);
    pg_scene_free(scene);
    printf("validation messages: %u\n", g_gpu->validation_messages);
    CHECK_MSG(g_gpu->validation_messages == 0, "%u validation message(s)", g_gpu->validation_messages);
    pg_gpu_destroy(g_gpu);
    free(g_lights);
    free(g_spots);
    return pg_test_finish("test_cluster_assign");
}
