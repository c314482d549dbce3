/* display_common.c - the display passes' full-screen record (display_common.h). */
#include "display_common.h"

void pg_display_record_fullscreen(const pg_pass_record_ctx *ctx, uint32_t ldr_slot, VkPipeline pipeline,
                                  VkPipelineLayout layout, VkDescriptorSet set, float exposure)
{
    VkClearColorValue clear = {{0, 0, 0, 1}};
    pg_pass_begin_rendering(ctx, 1, &ldr_slot, &clear, -1, false, 0);
    VkDescriptorSet sets[2] = {ctx->frame_set, set};
    vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 2, sets, 0, NULL);
    vkCmdPushConstants(ctx->cmd, layout, PG_PUSH_STAGES, 0, sizeof(float), &exposure);
    vkCmdDraw(ctx->cmd, 3, 1, 0, 0);
    vkCmdEndRendering(ctx->cmd);
}
