/* gbuffer_layout.h - the G-buffer packing variants, shared by the gbuffer and deferred_lighting
 * pass types (one pipeline parameter, `packing`, selects the same layout in both):
 *   float  : position (rgba32f, or rgba16f to show its failure far from the origin),
 *            normal+shininess (rgba32f), albedo+specular (rgba32f)          - 3 targets
 *   oct16  : normal as 2x16-bit octahedral + shininess/512 (rgba16 unorm), albedo sRGB8 +
 *            specular (rgba8_srgb); position rebuilt from the depth buffer  - 2 targets
 *   packed : one rgba32ui: oct16 normal | sRGB8 albedo + spec8 | shininess f32 | view depth f32;
 *            position rebuilt from the stored view depth                    - 1 target
 *   visibility (deferred_lighting only): no G-buffer; the visibility pass's triangle id (r32ui)
 *            is the one "target", and the surface is rebuilt from the triangle and its material
 *            evaluated in the lighting pass (visibility_common.h)            - 1 target
 * Any variant may add one optional target after depth: emissive (rgba16f or rgba32f, the scene-linear
 * emissive colour; gb_emissive in the shipped pipelines), unused and not allocated when no material
 * emits (pg_emissive_slot_declare, passes/shading_common.h). */
#ifndef PG_GBUFFER_LAYOUT_H
#define PG_GBUFFER_LAYOUT_H

#include <stdint.h>

enum { PG_GBUFFER_FLOAT = 0, PG_GBUFFER_OCT16 = 1, PG_GBUFFER_PACKED = 2, PG_GBUFFER_VISIBILITY = 3 };
static const char *const pg_gbuffer_packings[] = {"float", "oct16", "packed", "visibility", NULL};
static const uint32_t pg_gbuffer_targets[] = {3, 2, 1, 1};
static const char *const pg_gbuffer_defines[] = {"PG_GBUFFER_FLOAT", "PG_GBUFFER_OCT16", "PG_GBUFFER_PACKED",
                                                 "PG_GBUFFER_VISIBILITY"};
static const char *const pg_gbuffer_slot_names[4][3] = {
    {"position", "normal", "albedo"},
    {"normal_oct", "albedo"},
    {"packed"},
    {"vis_id"},
};

#endif
