/* visibility_common.h - what the visibility-buffer passes share: the 32-bit triangle id the
 * visibility pass writes and the compute passes that rebuild surfaces from it read
 * (deferred_lighting with packing "visibility", visibility_resolve).
 *
 * The id of a pixel is (draw << tri_bits) | triangle, where draw indexes pg_scene_gpu.draws and
 * triangle is gl_PrimitiveID within that draw; tri_bits is the fewest bits that hold the largest
 * drawn primitive's triangle count, so both halves fit in 32 bits for any scene with fewer than
 * 2^32 drawn triangles split sensibly (a scene whose draws x largest draw do not fit is refused
 * with both numbers). 0xFFFFFFFF (the clear value) means nothing was drawn.
 *
 * The rebuilding passes bind, after their own images, the scene's vertices and indices (storage
 * buffers of pg_scene_gpu), the pass's draw table (uvec4 per draw: first index, vertex offset,
 * material, flags with bit 0 double-sided, bit 1 alpha mask and bit 2 mirrored by the frame's pose;
 * host-visible, written at create, bit 2 rewritten each frame by pg_vis_geometry_record) and the optional
 * COLOR_0 / TEXCOORD_1 streams (shaders/visibility_surface.glsl), and the scene's set (materials,
 * textures). */
#ifndef PG_VISIBILITY_COMMON_H
#define PG_VISIBILITY_COMMON_H

#include "graph_execute.h"
#include "pass_set.h"
#include "scene_gpu.h"
#include "scene_draw.h"

/* The triangle bits of the scene's ids (1..31); fails when (draws, largest draw) do not fit. */
pg_result pg_vis_tri_bits(const pg_scene_gpu *sc, uint32_t *tri_bits, pg_error *err);

typedef struct pg_vis_geometry {
    uint32_t tri_bits;
    bool colors, uv1;          /* the pass was compiled with PG_VERTEX_COLORS / PG_UV1 */
    pg_buffer draws;           /* the draw table */
    uint32_t n_moving;         /* draws whose pose may mirror them (pg_draw.anim_prim >= 0), with
                                * geometry: their flags are rewritten each frame */
    const pg_phys_resource *geometry; /* the graph's deformed vertices (an animated scene), else NULL:
                                       * stream 0 is then the static vertex buffer */
    pg_phys_resource streams[5]; /* descriptors of vertices, indices, draws, colours, uv1 (buffer
                                  * kind, static: the graph does not track them) for pg_pass_set */
    char defines[PG_MAX_DEFINES + 8][PG_NAME_MAX];
    uint32_t n_defines;        /* the pass's declared defines without PG_ALPHA_MASK, plus
                                * TEXTURE_COUNT, PG_VIS_TRI_BITS, PG_SURFACE_GRADS, PG_SURFACE_NO_PUSH
                                * and PG_SCENE_SET=scene_set */
} pg_vis_geometry;

/* Checks the device and the scene, writes the draw table and the defines (f: the surface variant the
 * pass's declare chose, kept in its params). */
pg_result pg_vis_geometry_create(const pg_pass_create_ctx *ctx, const pg_scene_draw_features *f, uint32_t scene_set,
                                 pg_vis_geometry *g, pg_error *err);
/* Records, before the pass reads the draw table, each moving draw's flags at the frame's pose:
 * bit 2 where the pose mirrors it against the winding of its indices (pg_scene_gpu_anim_flipped:
 * the surface's front face and the compute rasterizer's culling swap), with the barriers around
 * the writes. Nothing when no drawn primitive moves rigidly. Outside dynamic rendering. */
void pg_vis_geometry_record(const pg_vis_geometry *g, const pg_pass_record_ctx *ctx);
/* Appends the vertex-stream bindings (3 to 5) at b[n...]; returns the new count. */
uint32_t pg_vis_geometry_bindings(pg_vis_geometry *g, const pg_scene_gpu *sc, pg_set_binding *b, uint32_t n);
/* The defines as the const char * array pg_shader_module takes; returns their count. */
uint32_t pg_vis_geometry_define_list(const pg_vis_geometry *g, const char **out);
void pg_vis_geometry_destroy(pg_gpu *gpu, pg_vis_geometry *g);

#endif
