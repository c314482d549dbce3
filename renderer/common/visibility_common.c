/* visibility_common.c - triangle ids and the vertex streams of the visibility-buffer passes
 * (visibility_common.h). */
#include "visibility_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "scene_gpu_anim.h"

pg_result pg_vis_tri_bits(const pg_scene_gpu *sc, uint32_t *tri_bits, pg_error *err)
{
    uint32_t n = sc->n_draws - sc->n_blend_draws; /* the draws the visibility pass rasterizes */
    uint64_t max_tris = 1;
    for (uint32_t i = 0; i < n; i++)
        if (sc->draws[i].index_count / 3 > max_tris) max_tris = sc->draws[i].index_count / 3;
    uint32_t bits = 1;
    while (bits < 32 && (1ull << bits) < max_tris) bits++;
    uint64_t last = n ? ((uint64_t)(n - 1) << bits) | (max_tris - 1) : 0;
    if (bits > 31 || last >= 0xFFFFFFFFull)
        return pg_fail(err, PG_ERR_LIMIT,
                       "visibility ids: %u draws with up to %llu triangles each do not fit a 32-bit id "
                       "(draw << %u | triangle); split the largest meshes or use a G-buffer pipeline",
                       n, (unsigned long long)max_tris, bits);
    *tri_bits = bits;
    return PG_OK;
}

pg_result pg_vis_geometry_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_features *f, uint32_t scene_set,
                                 pg_vis_geometry *g, pg_error *err)
{
    g->geometry = f->has_geometry ? pg_ctx_res(ctx, f->geometry) : NULL;
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    pg_result r;
    if (!sc) return pg_fail(err, PG_ERR_INVALID_ARG, "%s: needs a scene", ctx->pass->name);
    if ((r = pg_vis_tri_bits(sc, &g->tri_bits, err))) return r;
    g->n_defines = 0;
    g->colors = f->vertex_colors;
    g->uv1 = f->uv1;
    const char *defs[PG_MAX_DEFINES];
    /* without PG_ALPHA_MASK: the visibility pass discarded already */
    const uint32_t nd = pg_scene_draw_define_list(&ctx->pass->decl, f, defs, PG_MAX_DEFINES);
    for (uint32_t i = 0; i < nd; i++) snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "%s", defs[i]);
    if ((g->colors && !sc->colors.buffer) || (g->uv1 && !sc->uv1.buffer))
        return pg_fail(err, PG_ERR_INVALID_ARG, "%s: compiled with %s but the uploaded scene has no such stream",
                       ctx->pass->name, g->colors && !sc->colors.buffer ? "PG_VERTEX_COLORS" : "PG_UV1");
    snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "TEXTURE_COUNT=%u", sc->n_images);
    snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "PG_VIS_TRI_BITS=%u", g->tri_bits);
    snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "PG_SCENE_SET=%u", scene_set);
    snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "PG_SURFACE_GRADS");
    snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "PG_SURFACE_NO_PUSH");
    /* PASSGRAPH_VIS_TEXTURE_LOOP=1: the path of devices without non-uniform indexing (to test it on a GPU) */
    const char *wg = getenv("PASSGRAPH_VIS_TEXTURE_LOOP");
    if (ctx->gpu->nonuniform_sampled_arrays && !(wg && !strcmp(wg, "1")))
        snprintf(g->defines[g->n_defines++], PG_NAME_MAX, "PG_NONUNIFORM_TEXTURES");
    uint32_t n = sc->n_draws ? sc->n_draws : 1;
    char name[PG_NAME_MAX + 16];
    snprintf(name, sizeof name, "%s.draws", ctx->pass->name);
    if ((r = pg_buffer_create(ctx->gpu, (VkDeviceSize)n * 4 * sizeof(uint32_t),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, name,
                              &g->draws, err)))
        return r;
    uint32_t *t = g->draws.mapped;
    memset(t, 0, (size_t)n * 4 * sizeof(uint32_t));
    g->n_moving = 0;
    for (uint32_t i = 0; i < sc->n_draws; i++) {
        t[4 * i + 0] = sc->draws[i].first_index;
        memcpy(&t[4 * i + 1], &sc->draws[i].vertex_offset, sizeof(uint32_t)); /* added modulo 2^32 */
        t[4 * i + 2] = sc->draws[i].material;
        /* flags: bit 0 double-sided (no culling), bit 1 alpha mask, bit 2 mirrored (pg_vis_geometry_record) */
        t[4 * i + 3] = (sc->draws[i].double_sided ? 1u : 0u) | (sc->draws[i].alpha_mask ? 2u : 0u);
        g->n_moving += g->geometry && sc->draws[i].anim_prim >= 0;
    }
    return PG_OK;
}

void pg_vis_geometry_record(const pg_vis_geometry *g, const pg_pass_record_ctx *ctx)
{
    if (!g->n_moving) return;
    const pg_scene_gpu *sc = PG_SCENE_OF(ctx);
    const pg_frame_uniforms *fu = PG_FRAME_OF(ctx);
    const VkPipelineStageFlags2 ALL = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, TR = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    VkBufferMemoryBarrier2 b = pg_buffer_barrier(g->draws.buffer, ALL, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, TR,
                                                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    pg_cmd_barriers(ctx->cmd, 0, NULL, 1, &b);
    for (uint32_t i = 0; i < sc->n_draws; i++) {
        const pg_draw *d = &sc->draws[i];
        if (d->anim_prim < 0) continue;
        uint32_t flags = (d->double_sided ? 1u : 0u) | (d->alpha_mask ? 2u : 0u);
        if (pg_scene_gpu_anim_flipped(sc->anim, d->anim_prim, pg_frame_animation(fu), fu->camera_pos[3])) flags |= 4u;
        vkCmdUpdateBuffer(ctx->cmd, g->draws.buffer, (VkDeviceSize)i * 16 + 12, sizeof flags, &flags);
    }
    b = pg_buffer_barrier(g->draws.buffer, TR, VK_ACCESS_2_TRANSFER_WRITE_BIT, ALL, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    pg_cmd_barriers(ctx->cmd, 0, NULL, 1, &b);
}

uint32_t pg_vis_geometry_bindings(pg_vis_geometry *g, const pg_scene_gpu *sc, pg_set_binding *b, uint32_t n)
{
    const pg_buffer *src[5] = {&sc->vertices, &sc->indices, &g->draws, g->colors ? &sc->colors : NULL,
                               g->uv1 ? &sc->uv1 : NULL};
    for (uint32_t i = 0; i < 5; i++) {
        if (!src[i]) continue;
        g->streams[i] = (pg_phys_resource){.kind = PG_RES_BUFFER, .buffer = src[i]->buffer, .size = src[i]->size};
        if (i == 0 && g->geometry) g->streams[0] = *g->geometry; /* the vertices at the frame's pose */
        b[n++] = (pg_set_binding){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &g->streams[i], VK_NULL_HANDLE, 0};
    }
    return n;
}

uint32_t pg_vis_geometry_define_list(const pg_vis_geometry *g, const char **out)
{
    for (uint32_t i = 0; i < g->n_defines; i++) out[i] = g->defines[i];
    return g->n_defines;
}

void pg_vis_geometry_destroy(pg_gpu *gpu, pg_vis_geometry *g)
{
    pg_buffer_destroy(gpu, &g->draws);
}
