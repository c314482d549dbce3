/* display_common.h - the graphics record shared by the two display pass types (display_tonemap.c,
 * display_ocio.c's fragment path): one full-screen triangle into the LDR output. */
#ifndef PG_DISPLAY_COMMON_H
#define PG_DISPLAY_COMMON_H

#include "graph_execute.h"
#include "vk_pipeline.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Begins rendering to ldr_slot cleared to opaque black, binds pipeline with the frame set (set 0)
 * and set (set 1), pushes exposure, draws three vertices and ends rendering. */
void pg_display_record_fullscreen(const pg_pass_record_ctx *ctx, uint32_t ldr_slot, VkPipeline pipeline,
                                  VkPipelineLayout layout, VkDescriptorSet set, float exposure);

#ifdef __cplusplus
}
#endif

#endif
