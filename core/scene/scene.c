/* scene.c - scene lifetime, textures with mip chains, mesh helpers, derived data (bounds,
 * features) and camera / matrix math.
 *
 * Matrix convention (used everywhere in passgraph): column-major float[16], element (row r,
 * column c) at m[c*4 + r]; vectors are columns, p' = M * p.
 *
 * Camera convention:
 *   world: right-handed, +Y up.
 *   view (pg_camera_view): right-handed look-at; camera space has +X right, +Y up and the camera
 *     looking down -Z (the OpenGL/glTF camera convention).
 *   projection (pg_camera_proj): perspective into Vulkan clip space: x_ndc -1 = left,
 *     y_ndc -1 = TOP of the image (the view's +Y is negated, so the image is upright with the
 *     Vulkan viewport's y-down), depth z_ndc = 0 at near and 1 at far (standard, NOT reversed Z),
 *     w_clip = -z_view. A viewport with positive height (no VK_KHR_maintenance1 flip) is expected.
 */
#include "scene.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PG_PI_F 3.14159265358979323846f

/* ------------------------------------------------------------------------------------------ */
/* scene lifetime                                                                              */

pg_result pg_scene_load(const char *path_or_default, pg_scene **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: out is NULL");
    *out = NULL;
    if (!path_or_default || !path_or_default[0])
        return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_load: empty scene path");
    if (strcmp(path_or_default, "default") == 0) return pg_scene_create_default(out, err);
    return pg_scene_load_gltf(path_or_default, out, err);
}

void pg_material_init(pg_material *m, const char *name)
{
    memset(m, 0, sizeof *m);
    pg_strlcpy(m->name, name ? name : "", sizeof m->name);
    for (int k = 0; k < 4; k++) m->base_color[k] = 1.0f;
    m->base_color_tex = m->normal_tex = m->emissive_tex = -1;
    m->normal_scale = 1.0f;
    m->alpha_mode = PG_ALPHA_OPAQUE;
    m->alpha_cutoff = 0.5f;
    m->specular = 0.04f;
    m->shininess = 1.0f;
    for (int t = 0; t < PG_TEXSLOT_COUNT; t++) {
        m->uv_transform[t][0] = 1.0f;
        m->uv_transform[t][4] = 1.0f;
    }
}

void pg_scene_free(pg_scene *scene)
{
    if (!scene) return;
    if (scene->textures) {
        for (uint32_t i = 0; i < scene->n_textures; i++) pg_texture_release(&scene->textures[i]);
        free(scene->textures);
    }
    free(scene->vertices);
    free(scene->colors);
    free(scene->uv1);
    free(scene->indices);
    free(scene->primitives);
    free(scene->materials);
    free(scene->cameras);
    for (uint32_t i = 0; i < scene->n_warnings; i++) free(scene->warnings[i]);
    free(scene->warnings);
    free(scene);
}

pg_result pg_scene_add_warning(pg_scene *scene, const char *line, pg_error *err)
{
    size_t n = strlen(line);
    char *copy = malloc(n + 1);
    char **grown = copy ? realloc(scene->warnings, sizeof(char *) * (scene->n_warnings + 1)) : NULL;
    if (!grown) {
        free(copy);
        return pg_fail(err, PG_ERR_OOM, "%s: out of memory adding a warning", scene->path);
    }
    memcpy(copy, line, n + 1);
    scene->warnings = grown;
    scene->warnings[scene->n_warnings++] = copy;
    return PG_OK;
}

void pg_scene_print_warnings(const pg_scene *scene, const char *prefix, FILE *f)
{
    if (!scene) return;
    for (uint32_t i = 0; i < scene->n_warnings; i++)
        fprintf(f, "%swarning: %s\n", prefix ? prefix : "", scene->warnings[i]);
}

/* ------------------------------------------------------------------------------------------ */
/* textures                                                                                    */

static float srgb_to_linear_f(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

typedef struct srgb_tables {
    float to_linear[256];
    float threshold[255]; /* linear value half-way between byte i and byte i+1 (in sRGB space) */
} srgb_tables;

static void srgb_tables_init(srgb_tables *t)
{
    for (int i = 0; i < 256; i++) t->to_linear[i] = srgb_to_linear_f((float)i / 255.0f);
    /* Round in the encoded space: the threshold between byte i and i+1 is the linear value of
     * the encoded midpoint (i + 0.5) / 255. */
    for (int i = 0; i < 255; i++) t->threshold[i] = srgb_to_linear_f(((float)i + 0.5f) / 255.0f);
}

static uint8_t linear_to_srgb_byte(const srgb_tables *t, float v)
{
    /* the number of thresholds <= v (binary search over 255 sorted values) */
    int lo = 0, hi = 255;
    while (lo < hi) {
        int mid = (lo + hi) >> 1;
        if (t->threshold[mid] <= v) lo = mid + 1;
        else hi = mid;
    }
    return (uint8_t)lo;
}

static uint8_t unorm_byte(float v)
{
    if (!(v > 0.0f)) return 0;
    if (v >= 255.0f) return 255;
    return (uint8_t)(v + 0.5f);
}

/* Area-weighted box filter weights along one axis: destination texel i covers the source interval
 * [i*s, (i+1)*s) with s = src/dst; at most 4 source texels overlap (s <= 3). */
typedef struct tap4 {
    uint32_t first;
    uint32_t n;
    float w[4];
} tap4;

static void box_taps(uint32_t src, uint32_t dst, tap4 *taps)
{
    double s = (double)src / (double)dst;
    for (uint32_t i = 0; i < dst; i++) {
        double a = i * s, b = (i + 1) * s;
        if (b > src) b = src;
        uint32_t first = (uint32_t)floor(a);
        tap4 *t = &taps[i];
        t->first = first;
        t->n = 0;
        for (uint32_t k = first; k < src && (double)k < b && t->n < 4; k++) {
            double lo = a > k ? a : (double)k;
            double hi = b < k + 1.0 ? b : k + 1.0;
            double w = hi - lo;
            t->w[t->n++] = (float)(w > 0 ? w / (b - a) : 0.0);
        }
    }
}

static void downsample(const srgb_tables *tab, bool srgb, const uint8_t *src, uint32_t sw,
                       uint32_t sh, uint8_t *dst, uint32_t dw, uint32_t dh, tap4 *tx, tap4 *ty)
{
    box_taps(sw, dw, tx);
    box_taps(sh, dh, ty);
    for (uint32_t y = 0; y < dh; y++) {
        const tap4 *vy = &ty[y];
        for (uint32_t x = 0; x < dw; x++) {
            const tap4 *vx = &tx[x];
            float acc[4] = {0, 0, 0, 0};
            for (uint32_t j = 0; j < vy->n; j++) {
                const uint8_t *row = src + ((size_t)(vy->first + j) * sw) * 4;
                for (uint32_t i = 0; i < vx->n; i++) {
                    const uint8_t *p = row + (size_t)(vx->first + i) * 4;
                    float w = vy->w[j] * vx->w[i];
                    if (srgb) {
                        acc[0] += w * tab->to_linear[p[0]];
                        acc[1] += w * tab->to_linear[p[1]];
                        acc[2] += w * tab->to_linear[p[2]];
                    } else {
                        acc[0] += w * p[0];
                        acc[1] += w * p[1];
                        acc[2] += w * p[2];
                    }
                    acc[3] += w * p[3];
                }
            }
            uint8_t *o = dst + ((size_t)y * dw + x) * 4;
            if (srgb) {
                o[0] = linear_to_srgb_byte(tab, acc[0]);
                o[1] = linear_to_srgb_byte(tab, acc[1]);
                o[2] = linear_to_srgb_byte(tab, acc[2]);
            } else {
                o[0] = unorm_byte(acc[0]);
                o[1] = unorm_byte(acc[1]);
                o[2] = unorm_byte(acc[2]);
            }
            o[3] = unorm_byte(acc[3]); /* alpha is always linear */
        }
    }
}

pg_result pg_texture_init(pg_texture *tex, const char *name, const uint8_t *rgba, uint32_t w,
                          uint32_t h, bool srgb, pg_error *err)
{
    if (!tex) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_texture_init: tex is NULL");
    memset(tex, 0, sizeof *tex);
    const char *nm = name ? name : "";
    if (!rgba) return pg_fail(err, PG_ERR_INVALID_ARG, "texture '%s': no pixel data", nm);
    const uint32_t max_side = 1u << (PG_MAX_MIPS - 1);
    if (w == 0 || h == 0 || w > max_side || h > max_side)
        return pg_fail(err, PG_ERR_INVALID_ARG, "texture '%s': size %ux%u outside 1..%u", nm, w,
                       h, max_side);
    pg_strlcpy(tex->name, nm, sizeof tex->name);
    tex->srgb = srgb;

    uint32_t n = 1, mw = w, mh = h;
    size_t total = (size_t)w * h * 4;
    while (mw > 1 || mh > 1) {
        mw = mw > 1 ? mw / 2 : 1;
        mh = mh > 1 ? mh / 2 : 1;
        total += (size_t)mw * mh * 4;
        n++;
    }
    /* levels after the base are at most w/2 x h/2 (or 1): one tap array for x, one for y */
    size_t ntx = (size_t)w / 2 + 1, nty = (size_t)h / 2 + 1;
    tap4 *taps = malloc(sizeof(tap4) * (ntx + nty));
    tex->data = malloc(total);
    if (!tex->data || !taps) {
        free(taps);
        free(tex->data);
        memset(tex, 0, sizeof *tex);
        return pg_fail(err, PG_ERR_OOM, "texture '%s': out of memory (%zu bytes)", nm, total);
    }
    tex->data_size = total;
    tex->n_mips = n;

    srgb_tables tab;
    if (srgb) srgb_tables_init(&tab);

    size_t off = 0;
    mw = w;
    mh = h;
    for (uint32_t m = 0; m < n; m++) {
        tex->mips[m].width = mw;
        tex->mips[m].height = mh;
        tex->mips[m].rgba = tex->data + off;
        if (m == 0) {
            memcpy(tex->data, rgba, (size_t)w * h * 4);
        } else {
            const pg_mip *p = &tex->mips[m - 1];
            downsample(&tab, srgb, p->rgba, p->width, p->height, tex->mips[m].rgba, mw, mh,
                       taps, taps + ntx);
        }
        off += (size_t)mw * mh * 4;
        mw = mw > 1 ? mw / 2 : 1;
        mh = mh > 1 ? mh / 2 : 1;
    }
    free(taps);
    return PG_OK;
}

void pg_texture_release(pg_texture *tex)
{
    if (!tex) return;
    free(tex->data);
    memset(tex, 0, sizeof *tex);
}

/* ------------------------------------------------------------------------------------------ */
/* mesh helpers                                                                                */

static void v3_sub(const float a[3], const float b[3], float o[3])
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static void v3_cross(const float a[3], const float b[3], float o[3])
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}
static float v3_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static float v3_len(const float a[3]) { return sqrtf(v3_dot(a, a)); }
static bool v3_normalize(float a[3])
{
    float l = v3_len(a);
    if (!(l > 1e-30f) || !isfinite(l)) return false;
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
    return true;
}

/* A unit vector perpendicular to the unit vector n. */
static void any_perpendicular(const float n[3], float out[3])
{
    float ax[3] = {1, 0, 0};
    if (fabsf(n[0]) > 0.9f) {
        ax[0] = 0;
        ax[1] = 1;
    }
    float d = v3_dot(ax, n);
    out[0] = ax[0] - n[0] * d;
    out[1] = ax[1] - n[1] * d;
    out[2] = ax[2] - n[2] * d;
    if (!v3_normalize(out)) {
        out[0] = 1;
        out[1] = 0;
        out[2] = 0;
    }
}

void pg_mesh_compute_normals(pg_vertex *verts, uint32_t n_verts, const uint32_t *indices,
                             uint32_t n_indices)
{
    for (uint32_t i = 0; i < n_verts; i++) memset(verts[i].normal, 0, sizeof verts[i].normal);
    for (uint32_t t = 0; t + 2 < n_indices; t += 3) {
        uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        if (a >= n_verts || b >= n_verts || c >= n_verts) continue;
        float e1[3], e2[3], n[3];
        v3_sub(verts[b].position, verts[a].position, e1);
        v3_sub(verts[c].position, verts[a].position, e2);
        v3_cross(e1, e2, n); /* length = 2 * area: area weighting */
        for (int k = 0; k < 3; k++) {
            verts[a].normal[k] += n[k];
            verts[b].normal[k] += n[k];
            verts[c].normal[k] += n[k];
        }
    }
    for (uint32_t i = 0; i < n_verts; i++) {
        if (!v3_normalize(verts[i].normal)) {
            verts[i].normal[0] = 0;
            verts[i].normal[1] = 1;
            verts[i].normal[2] = 0;
        }
    }
}

void pg_mesh_compute_tangents(pg_vertex *verts, uint32_t n_verts, const uint32_t *indices,
                              uint32_t n_indices)
{
    /* accumulate tangent (xyz) and bitangent per vertex; use the tangent slot for T and a
     * temporary array for B */
    float *bacc = calloc((size_t)n_verts * 3, sizeof(float));
    for (uint32_t i = 0; i < n_verts; i++) memset(verts[i].tangent, 0, sizeof verts[i].tangent);
    for (uint32_t t = 0; t + 2 < n_indices; t += 3) {
        uint32_t id[3] = {indices[t], indices[t + 1], indices[t + 2]};
        if (id[0] >= n_verts || id[1] >= n_verts || id[2] >= n_verts) continue;
        const pg_vertex *v0 = &verts[id[0]], *v1 = &verts[id[1]], *v2 = &verts[id[2]];
        float e1[3], e2[3], fn[3];
        v3_sub(v1->position, v0->position, e1);
        v3_sub(v2->position, v0->position, e2);
        v3_cross(e1, e2, fn);
        float area = v3_len(fn);
        if (!(area > 0.0f)) continue;
        /* v is negated: glTF's v grows downward in the image, tangent space +Y is up */
        float du1 = v1->uv[0] - v0->uv[0], dv1 = -(v1->uv[1] - v0->uv[1]);
        float du2 = v2->uv[0] - v0->uv[0], dv2 = -(v2->uv[1] - v0->uv[1]);
        float det = du1 * dv2 - du2 * dv1;
        if (!(fabsf(det) > 1e-20f) || !isfinite(det)) continue;
        float r = 1.0f / det;
        float T[3], B[3];
        for (int k = 0; k < 3; k++) {
            T[k] = (e1[k] * dv2 - e2[k] * dv1) * r;
            B[k] = (e2[k] * du1 - e1[k] * du2) * r;
        }
        if (!v3_normalize(T) || !v3_normalize(B)) continue;
        for (int c = 0; c < 3; c++) {
            float *tt = verts[id[c]].tangent;
            for (int k = 0; k < 3; k++) {
                tt[k] += T[k] * area;
                if (bacc) bacc[(size_t)id[c] * 3 + k] += B[k] * area;
            }
        }
    }
    for (uint32_t i = 0; i < n_verts; i++) {
        float *n = verts[i].normal;
        float *tt = verts[i].tangent;
        float t[3] = {tt[0], tt[1], tt[2]};
        float d = v3_dot(n, t);
        t[0] -= n[0] * d;
        t[1] -= n[1] * d;
        t[2] -= n[2] * d;
        if (!v3_normalize(t)) any_perpendicular(n, t);
        float w = 1.0f;
        if (bacc) {
            float c[3];
            v3_cross(n, t, c);
            if (v3_dot(c, &bacc[(size_t)i * 3]) < 0.0f) w = -1.0f;
        }
        tt[0] = t[0];
        tt[1] = t[1];
        tt[2] = t[2];
        tt[3] = w;
    }
    free(bacc);
}

void pg_scene_finalize(pg_scene *s)
{
    if (!s) return;
    float smin[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, smax[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    bool any = false;
    memset(&s->features, 0, sizeof s->features);
    s->features.has_vertex_colors = s->colors != NULL;
    for (uint32_t p = 0; p < s->n_primitives; p++) {
        pg_primitive *pr = &s->primitives[p];
        float mn[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, mx[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        bool pany = false;
        for (uint32_t i = 0; i < pr->index_count; i++) {
            uint64_t gi = (uint64_t)pr->first_index + i;
            if (gi >= s->n_indices) break;
            int64_t v = (int64_t)s->indices[gi] + pr->vertex_offset;
            if (v < 0 || v >= (int64_t)s->n_vertices) continue;
            const float *pos = s->vertices[v].position;
            for (int k = 0; k < 3; k++) {
                if (pos[k] < mn[k]) mn[k] = pos[k];
                if (pos[k] > mx[k]) mx[k] = pos[k];
            }
            pany = true;
        }
        if (!pany) {
            memset(mn, 0, sizeof mn);
            memset(mx, 0, sizeof mx);
        } else {
            for (int k = 0; k < 3; k++) {
                if (mn[k] < smin[k]) smin[k] = mn[k];
                if (mx[k] > smax[k]) smax[k] = mx[k];
            }
            any = true;
        }
        memcpy(pr->bounds_min, mn, sizeof mn);
        memcpy(pr->bounds_max, mx, sizeof mx);
        if (pr->index_count && pr->material < s->n_materials) {
            const pg_material *m = &s->materials[pr->material];
            if (m->base_color_tex >= 0) s->features.has_textures = true;
            if (m->normal_tex >= 0) s->features.has_normal_maps = true;
            if (m->alpha_mode == PG_ALPHA_MASK) s->features.has_alpha_mask = true;
            if (m->alpha_mode == PG_ALPHA_BLEND) s->features.has_blend = true;
            if (m->emissive[0] > 0 || m->emissive[1] > 0 || m->emissive[2] > 0) s->features.has_emissive = true;
            for (int t = 0; t < PG_TEXSLOT_COUNT; t++) {
                int tex = t == PG_TEXSLOT_BASE ? m->base_color_tex
                          : t == PG_TEXSLOT_NORMAL ? m->normal_tex : m->emissive_tex;
                if (tex < 0) continue;
                if (m->has_uv_transform[t]) s->features.has_uv_transform = true;
                if (m->tex_coord[t] == 1 && s->uv1) s->features.has_uv1 = true;
            }
        }
    }
    if (!any) {
        memset(smin, 0, sizeof smin);
        memset(smax, 0, sizeof smax);
    }
    memcpy(s->bounds_min, smin, sizeof smin);
    memcpy(s->bounds_max, smax, sizeof smax);
}

/* ------------------------------------------------------------------------------------------ */
/* camera and matrices                                                                         */

pg_camera pg_camera_default_for_scene(const pg_scene *scene, float aspect)
{
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    if (scene && scene->bounds_min[0] <= scene->bounds_max[0] &&
        scene->bounds_min[1] <= scene->bounds_max[1] &&
        scene->bounds_min[2] <= scene->bounds_max[2]) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    float size[3], center[3];
    for (int k = 0; k < 3; k++) {
        size[k] = mx[k] - mn[k];
        center[k] = 0.5f * (mn[k] + mx[k]);
    }
    float diag = v3_len(size);
    if (!(diag > 1e-6f)) diag = 1.0f;
    if (!(size[0] > 1e-6f)) { /* flat along x: still look along +X from in front of it */
        mn[0] = center[0] - 0.5f * diag;
        mx[0] = center[0] + 0.5f * diag;
        size[0] = diag;
    }
    pg_camera c;
    memset(&c, 0, sizeof c);
    c.position[0] = mn[0] + 0.2f * size[0];
    c.position[1] = mn[1] + 0.18f * size[1];
    c.position[2] = center[2];
    c.target[0] = mx[0];
    c.target[1] = c.position[1];
    c.target[2] = center[2];
    c.up[0] = 0;
    c.up[1] = 1;
    c.up[2] = 0;
    c.fov_y_deg = 60.0f;
    c.near_z = fmaxf(0.01f, 0.001f * diag);
    c.far_z = 2.0f * diag;
    c.aspect = aspect > 0 && isfinite(aspect) ? aspect : 1.0f;
    return c;
}

static bool scene_has_bounds(const pg_scene *scene)
{
    return scene && scene->n_indices > 0 && scene->bounds_min[0] <= scene->bounds_max[0] &&
           scene->bounds_min[1] <= scene->bounds_max[1] && scene->bounds_min[2] <= scene->bounds_max[2];
}

pg_camera pg_camera_frame_object(const pg_scene *scene, float aspect, float *out_radius, float *out_distance)
{
    float mn[3] = {-1, -1, -1}, mx[3] = {1, 1, 1};
    if (scene_has_bounds(scene)) {
        memcpy(mn, scene->bounds_min, sizeof mn);
        memcpy(mx, scene->bounds_max, sizeof mx);
    }
    double c[3], h2 = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)mn[k] + (double)mx[k]);
        double h = 0.5 * ((double)mx[k] - (double)mn[k]);
        h2 += h * h;
    }
    double r = sqrt(h2);
    if (!(r > 1e-30)) r = 1.0;
    if (!(aspect > 0) || !isfinite(aspect)) aspect = 1.0f;
    const double pi = 3.14159265358979323846;
    double fy = 0.5 * 45.0 * pi / 180.0;
    double fx = atan(tan(fy) * aspect);
    double a = fy < fx ? fy : fx;
    double d = 1.1 * r / sin(a);
    double az = 35.0 * pi / 180.0, el = 25.0 * pi / 180.0;
    double dir[3] = {sin(az) * cos(el), sin(el), cos(az) * cos(el)};
    pg_camera cam;
    memset(&cam, 0, sizeof cam);
    for (int k = 0; k < 3; k++) {
        cam.position[k] = (float)(c[k] + d * dir[k]);
        cam.target[k] = (float)c[k];
    }
    cam.up[1] = 1.0f;
    cam.fov_y_deg = 45.0f;
    cam.near_z = (float)(d - 1.05 * r);
    cam.far_z = (float)(d + 1.05 * r);
    cam.aspect = aspect;
    if (out_radius) *out_radius = (float)r;
    if (out_distance) *out_distance = (float)d;
    return cam;
}

pg_result pg_camera_from_scene(const pg_scene *scene, uint32_t index, float aspect, pg_camera *out, pg_error *err)
{
    if (!scene || index >= scene->n_cameras)
        return pg_fail(err, PG_ERR_INVALID_ARG, "camera %u: out of range (%u cameras)", index,
                       scene ? scene->n_cameras : 0);
    const pg_scene_camera *sc = &scene->cameras[index];
    pg_camera cam;
    memset(&cam, 0, sizeof cam);
    double dist = 1.0; /* look-at distance: any positive value gives the same view */
    if (scene_has_bounds(scene)) {
        double cc = 0, r2 = 0;
        for (int k = 0; k < 3; k++) {
            double c = 0.5 * ((double)scene->bounds_min[k] + scene->bounds_max[k]);
            double h = 0.5 * ((double)scene->bounds_max[k] - scene->bounds_min[k]);
            cc += (c - sc->position[k]) * sc->forward[k];
            r2 += h * h;
        }
        dist = cc > 1e-6 * sqrt(r2) ? cc : (sqrt(r2) > 0 ? sqrt(r2) : 1.0);
    }
    for (int k = 0; k < 3; k++) {
        cam.position[k] = sc->position[k];
        cam.target[k] = (float)(sc->position[k] + dist * sc->forward[k]);
        cam.up[k] = sc->up[k];
    }
    cam.fov_y_deg = sc->yfov_rad * (float)(180.0 / 3.14159265358979323846);
    cam.near_z = sc->znear;
    float far = sc->zfar;
    if (!(far > 0)) { /* infinite: to the farthest corner of the bounds, twice */
        double m = 0;
        for (int i = 0; i < 8; i++) {
            double d2 = 0;
            for (int k = 0; k < 3; k++) {
                double v = ((i >> k) & 1) ? scene->bounds_max[k] : scene->bounds_min[k];
                d2 += (v - sc->position[k]) * (v - sc->position[k]);
            }
            if (d2 > m) m = d2;
        }
        far = (float)(2.0 * sqrt(m));
        if (far < 1000.0f * sc->znear) far = 1000.0f * sc->znear;
    }
    cam.far_z = far;
    cam.aspect = aspect > 0 && isfinite(aspect) ? aspect : 1.0f;
    if (sc->type == PG_CAMERA_ORTHOGRAPHIC) {
        cam.ortho_height = 2.0f * sc->ymag;
        cam.fov_y_deg = 45.0f; /* unused */
        if (!(cam.near_z > 1e-6f * cam.far_z)) cam.near_z = 1e-6f * cam.far_z;
    }
    *out = cam;
    return PG_OK;
}

pg_result pg_scene_find_camera(const pg_scene *scene, const char *spec, uint32_t *out_index, pg_error *err)
{
    uint32_t n = scene ? scene->n_cameras : 0;
    if (spec && spec[0]) {
        const char *p = spec;
        bool digits = true;
        for (; *p; p++)
            if (*p < '0' || *p > '9') digits = false;
        if (digits && strlen(spec) < 10) {
            unsigned long v = strtoul(spec, NULL, 10);
            if (v < n) {
                *out_index = (uint32_t)v;
                return PG_OK;
            }
        }
        for (uint32_t i = 0; i < n; i++)
            if (!strcmp(scene->cameras[i].name, spec)) {
                *out_index = i;
                return PG_OK;
            }
        for (uint32_t i = 0; i < n; i++)
            if (!strcmp(scene->cameras[i].node_name, spec)) {
                *out_index = i;
                return PG_OK;
            }
    }
    const char *file = scene ? scene->path : "(no scene)";
    if (n == 0)
        return pg_fail(err, PG_ERR_INVALID_ARG, "--camera %s: %s has no cameras; use --camera auto", spec ? spec : "",
                       file);
    char list[768];
    size_t len = 0;
    list[0] = 0;
    for (uint32_t i = 0; i < n && len + 1 < sizeof list; i++) {
        int w = snprintf(list + len, sizeof list - len, "%s%u '%s' (node '%s'%s)", i ? ", " : "", i,
                         scene->cameras[i].name, scene->cameras[i].node_name,
                         scene->cameras[i].type == PG_CAMERA_ORTHOGRAPHIC ? ", orthographic" : "");
        if (w < 0) break;
        len += (size_t)w;
        if (len >= sizeof list) len = sizeof list - 1;
    }
    return pg_fail(err, PG_ERR_INVALID_ARG, "--camera %s: no such camera in %s; available: %s, or auto",
                   spec ? spec : "", file, list);
}

void pg_camera_view(const pg_camera *cam, float out[16])
{
    float f[3], s[3], u[3];
    v3_sub(cam->target, cam->position, f);
    if (!v3_normalize(f)) {
        f[0] = 0;
        f[1] = 0;
        f[2] = -1;
    }
    float up[3] = {cam->up[0], cam->up[1], cam->up[2]};
    if (!v3_normalize(up)) {
        up[0] = 0;
        up[1] = 1;
        up[2] = 0;
    }
    v3_cross(f, up, s);
    if (!v3_normalize(s)) { /* up parallel to the view direction: pick another up */
        float alt[3] = {0, 0, 1};
        if (fabsf(f[2]) > 0.9f) {
            alt[1] = 1;
            alt[2] = 0;
        }
        v3_cross(f, alt, s);
        v3_normalize(s);
    }
    v3_cross(s, f, u);
    const float *e = cam->position;
    /* rows: s, u, -f */
    out[0] = s[0];
    out[4] = s[1];
    out[8] = s[2];
    out[12] = -v3_dot(s, e);
    out[1] = u[0];
    out[5] = u[1];
    out[9] = u[2];
    out[13] = -v3_dot(u, e);
    out[2] = -f[0];
    out[6] = -f[1];
    out[10] = -f[2];
    out[14] = v3_dot(f, e);
    out[3] = 0;
    out[7] = 0;
    out[11] = 0;
    out[15] = 1;
}

void pg_camera_proj(const pg_camera *cam, float out[16])
{
    float fov = cam->fov_y_deg;
    if (!(fov > 0.0f && fov < 180.0f)) fov = 60.0f;
    float aspect = cam->aspect > 0 && isfinite(cam->aspect) ? cam->aspect : 1.0f;
    float n = cam->near_z > 0 ? cam->near_z : 0.01f;
    float fz = cam->far_z > n ? cam->far_z : n * 1000.0f;
    memset(out, 0, 16 * sizeof(float));
    if (cam->ortho_height > 0 && isfinite(cam->ortho_height)) {
        float hh = 0.5f * cam->ortho_height;
        out[0] = 1.0f / (hh * aspect);
        out[5] = -1.0f / hh;             /* Vulkan: clip y down */
        out[10] = 1.0f / (n - fz);       /* z_ndc = (-z - n) / (f - n) */
        out[14] = n / (n - fz);
        out[15] = 1.0f;
        return;
    }
    float t = 1.0f / tanf(fov * PG_PI_F / 360.0f);
    out[0] = t / aspect;
    out[5] = -t;                     /* Vulkan: clip y down */
    out[10] = fz / (n - fz);         /* z_ndc: 0 at near, 1 at far */
    out[14] = n * fz / (n - fz);
    out[11] = -1.0f;                 /* w_clip = -z_view */
}

void pg_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float acc = 0;
            for (int k = 0; k < 4; k++) acc += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = acc;
        }
    memcpy(out, r, sizeof r);
}

bool pg_mat4_invert(const float m[16], float out[16])
{
    double a[16], inv[16];
    double maxabs = 0;
    for (int i = 0; i < 16; i++) {
        a[i] = m[i];
        if (!isfinite(a[i])) return false;
        if (fabs(a[i]) > maxabs) maxabs = fabs(a[i]);
    }
    if (maxabs == 0) return false;
    inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] +
             a[9] * a[7] * a[14] + a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
    inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] -
             a[8] * a[7] * a[14] - a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
    inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] +
             a[8] * a[7] * a[13] + a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
    inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] -
              a[8] * a[6] * a[13] - a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
    inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] -
             a[9] * a[3] * a[14] - a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
    inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] +
             a[8] * a[3] * a[14] + a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
    inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] -
             a[8] * a[3] * a[13] - a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
    inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] +
              a[8] * a[2] * a[13] + a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
    inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] +
             a[5] * a[3] * a[14] + a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
    inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] -
             a[4] * a[3] * a[14] - a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
    inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] +
              a[4] * a[3] * a[13] + a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
    inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] -
              a[4] * a[2] * a[13] - a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
    inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] -
             a[5] * a[3] * a[10] - a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
    inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] +
             a[4] * a[3] * a[10] + a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
    inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] -
              a[4] * a[3] * a[9] - a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
    inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] +
              a[4] * a[2] * a[9] + a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
    double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
    /* Singular (or numerically so) relative to the matrix's scale. Hadamard's inequality bounds
     * |det| by the product of the row norms and by the product of the column norms; the smaller
     * one is the right scale: a view matrix with a large translation (camera ~1e5 from the
     * origin) has det 1 and huge rows but unit columns 0..2, and must stay invertible. */
    double prod_rows = 1, prod_cols = 1;
    for (int i = 0; i < 4; i++) {
        double rn = 0, cn = 0;
        for (int j = 0; j < 4; j++) {
            rn += a[j * 4 + i] * a[j * 4 + i];
            cn += a[i * 4 + j] * a[i * 4 + j];
        }
        prod_rows *= sqrt(rn);
        prod_cols *= sqrt(cn);
    }
    double scale = prod_rows < prod_cols ? prod_rows : prod_cols;
    if (!isfinite(det) || fabs(det) <= 1e-12 * scale) return false;
    double id = 1.0 / det;
    float r[16];
    for (int i = 0; i < 16; i++) {
        double v = inv[i] * id;
        if (!isfinite(v) || fabs(v) > FLT_MAX) return false;
        r[i] = (float)v;
    }
    memcpy(out, r, sizeof r);
    return true;
}
