/* scene.c - scene lifetime, textures with mip chains, mesh helpers and derived data (bounds,
 * features): what the loaders (scene_default.c, scene_gltf*.cpp) build a scene with; it calls
 * none of them (pg_scene_load is scene_load.c). Camera and matrix math (and their conventions)
 * are in scene_camera.c.
 */
#include "scene.h"
#include "scene_internal.h"
#include "environment.h"
#include "animation.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------------------------ */
/* scene lifetime                                                                              */

void pg_material_init(pg_material *m, const char *name)
{
    memset(m, 0, sizeof *m);
    pg_strlcpy(m->name, name ? name : "", sizeof m->name);
    for (int k = 0; k < 4; k++) m->base_color[k] = 1.0f;
    m->base_color_tex = m->normal_tex = m->emissive_tex = m->metallic_roughness_tex = m->occlusion_tex = -1;
    m->metallic = m->roughness = 1.0f; /* glTF's defaults */
    m->occlusion_strength = 1.0f;
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

int pg_material_slot_texture(const pg_material *m, int slot)
{
    switch (slot) {
    case PG_TEXSLOT_BASE: return m->base_color_tex;
    case PG_TEXSLOT_NORMAL: return m->normal_tex;
    case PG_TEXSLOT_EMISSIVE: return m->emissive_tex;
    case PG_TEXSLOT_METALLIC_ROUGHNESS: return m->metallic_roughness_tex;
    case PG_TEXSLOT_OCCLUSION: return m->occlusion_tex;
    default: return -1;
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
    free(scene->lights);
    pg_environment_free(scene->environment);
    pg_scene_anim_free(scene->anim);
    for (uint32_t i = 0; i < scene->n_warnings; i++) free(scene->warnings[i]);
    free(scene->warnings);
    free(scene);
}

void pg_scene_set_environment(pg_scene *scene, struct pg_environment *env)
{
    if (scene->environment != env) pg_environment_free(scene->environment);
    scene->environment = env;
    scene->features.has_environment = env != NULL;
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
            if (m->unlit) s->features.has_unlit = s->features.has_emissive = true; /* drawn as emission */
            if (m->metallic_roughness_tex >= 0) s->features.has_metallic_roughness_tex = true;
            if (m->occlusion_tex >= 0) s->features.has_occlusion_tex = true;
            /* KHR_animation_pointer: what a material may become at another time counts too */
            const uint32_t ab = s->anim && pr->material < s->anim->n_materials ? s->anim->material_animated[pr->material] : 0;
            if (ab & (1u << (PG_ANIM_MAT_EMISSIVE - PG_ANIM_MAT_BASE_COLOR) |
                      1u << (PG_ANIM_MAT_EMISSIVE_STRENGTH - PG_ANIM_MAT_BASE_COLOR)))
                s->features.has_emissive = true;
            for (int t = 0; t < PG_TEXSLOT_COUNT; t++) {
                int tex = pg_material_slot_texture(m, t);
                if (tex < 0) continue;
                if (m->has_uv_transform[t] || ((ab >> (PG_ANIM_MAT_UV + 3 * t - PG_ANIM_MAT_BASE_COLOR)) & 7u))
                    s->features.has_uv_transform = true;
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
    s->features.has_file_lights = s->n_lights > 0;
    s->features.has_animation = s->anim != NULL && s->anim->n_prims > 0;
    s->features.vertices = s->n_vertices;
    s->features.auto_shading = s->gltf_materials ? PG_SHADING_PBR : PG_SHADING_LAMBERT;
    s->features.has_spot_lights = false;
    for (uint32_t i = 0; i < s->n_lights; i++)
        if (s->lights[i].type == PG_LIGHT_SPOT) s->features.has_spot_lights = true;
}
