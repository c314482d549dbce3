#include "vk_pipeline.h"

#include "pipeline_stats.h"

#include <stddef.h>
#include <string.h>


pg_result pg_pipeline_layout_create(pg_gpu *gpu, uint32_t n_sets, const VkDescriptorSetLayout *sets,
                                    uint32_t push_bytes, VkPipelineLayout *out, pg_error *err)
{
    VkPushConstantRange pr = {PG_PUSH_STAGES,
                              0, push_bytes};
    VkPipelineLayoutCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = n_sets,
        .pSetLayouts = sets,
        .pushConstantRangeCount = push_bytes ? 1 : 0,
        .pPushConstantRanges = &pr,
    };
    PG_VK_TRY(err, vkCreatePipelineLayout(gpu->device, &ci, NULL, out));
    return PG_OK;
}

pg_result pg_gfx_pipeline_create(pg_gpu *gpu, const pg_gfx_pipeline_desc *d, const char *name, VkPipeline *out,
                                 pg_error *err)
{
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = d->vs, .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = d->fs, .pName = "main"},
    };
    VkPipelineVertexInputStateCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (d->vertex_input) {
        vi.vertexBindingDescriptionCount = d->vertex_input->n_bindings;
        vi.pVertexBindingDescriptions = d->vertex_input->bindings;
        vi.vertexAttributeDescriptionCount = d->vertex_input->n_attributes;
        vi.pVertexAttributeDescriptions = d->vertex_input->attributes;
    }
    VkPipelineInputAssemblyStateCreateInfo ia = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
                                                 .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkPipelineViewportStateCreateInfo vp = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                            .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo rs = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = d->cull,
        .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .depthBiasEnable = d->depth_bias_constant != 0.0f || d->depth_bias_slope != 0.0f,
        .depthBiasConstantFactor = d->depth_bias_constant,
        .depthBiasSlopeFactor = d->depth_bias_slope,
        .lineWidth = 1.0f,
    };
    VkPipelineMultisampleStateCreateInfo ms = {.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
                                               .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineDepthStencilStateCreateInfo ds = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = d->depth_test,
        .depthWriteEnable = d->depth_write,
        .depthCompareOp = d->depth_compare ? d->depth_compare : VK_COMPARE_OP_LESS,
    };
    VkPipelineColorBlendAttachmentState att[8];
    memset(att, 0, sizeof att);
    for (uint32_t i = 0; i < d->n_color && i < 8; i++) {
        att[i].colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                                VK_COLOR_COMPONENT_A_BIT;
        if (d->blend_over) {
            att[i].blendEnable = VK_TRUE;
            att[i].srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
            att[i].dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            att[i].colorBlendOp = VK_BLEND_OP_ADD;
            att[i].srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            att[i].dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
            att[i].alphaBlendOp = VK_BLEND_OP_ADD;
        } else if (d->blend_add) {
            att[i].blendEnable = VK_TRUE;
            att[i].srcColorBlendFactor = att[i].dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
            att[i].srcAlphaBlendFactor = att[i].dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            att[i].colorBlendOp = att[i].alphaBlendOp = VK_BLEND_OP_ADD;
        }
    }
    VkPipelineColorBlendStateCreateInfo cb = {.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                              .attachmentCount = d->n_color, .pAttachments = att};
    VkDynamicState dyn[4] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE,
                             VK_DYNAMIC_STATE_FRONT_FACE};
    VkPipelineDynamicStateCreateInfo dy = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                           .dynamicStateCount = d->dynamic_cull ? 4 : 2, .pDynamicStates = dyn};
    VkPipelineRenderingCreateInfo ri = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .colorAttachmentCount = d->n_color,
        .pColorAttachmentFormats = d->color_formats,
        .depthAttachmentFormat = d->depth_format,
    };
    VkGraphicsPipelineCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = &ri,
        .flags = pg_pipeline_stats_flags(gpu),
        .stageCount = 2,
        .pStages = stages,
        .pVertexInputState = &vi,
        .pInputAssemblyState = &ia,
        .pViewportState = &vp,
        .pRasterizationState = &rs,
        .pMultisampleState = &ms,
        .pDepthStencilState = &ds,
        .pColorBlendState = &cb,
        .pDynamicState = &dy,
        .layout = d->layout,
    };
    PG_VK_TRY(err, vkCreateGraphicsPipelines(gpu->device, gpu->pipeline_cache, 1, &ci, NULL, out));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_PIPELINE, (uint64_t)*out, "%s", name);
    pg_pipeline_stats_report(gpu, *out, name);
    return PG_OK;
}

pg_result pg_compute_pipeline_create(pg_gpu *gpu, VkPipelineLayout layout, VkShaderModule cs, const char *name,
                                     VkPipeline *out, pg_error *err)
{
    VkComputePipelineCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = pg_pipeline_stats_flags(gpu),
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = cs, .pName = "main"},
        .layout = layout,
    };
    PG_VK_TRY(err, vkCreateComputePipelines(gpu->device, gpu->pipeline_cache, 1, &ci, NULL, out));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_PIPELINE, (uint64_t)*out, "%s", name);
    pg_pipeline_stats_report(gpu, *out, name);
    return PG_OK;
}

pg_result pg_compute_pipeline_create_ex(pg_gpu *gpu, const pg_compute_pipeline_desc *d, const char *name,
                                        VkPipeline *out, pg_error *err)
{
    VkSpecializationMapEntry map[8];
    if (d->n_spec > 8) return pg_fail(err, PG_ERR_LIMIT, "%s: more than 8 specialization constants", name);
    for (uint32_t i = 0; i < d->n_spec; i++) map[i] = (VkSpecializationMapEntry){i, i * 4, 4};
    VkSpecializationInfo si = {.mapEntryCount = d->n_spec, .pMapEntries = map, .dataSize = d->n_spec * 4u,
                               .pData = d->spec_data};
    VkPipelineShaderStageRequiredSubgroupSizeCreateInfo rs = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_REQUIRED_SUBGROUP_SIZE_CREATE_INFO,
        .requiredSubgroupSize = d->subgroup_size,
    };
    if (d->subgroup_size && !gpu->exact_subgroups)
        return pg_fail(err, PG_ERR_NO_DEVICE, "%s: %s cannot require a subgroup size", name, gpu->props.deviceName);
    VkComputePipelineCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = pg_pipeline_stats_flags(gpu),
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .pNext = d->subgroup_size ? &rs : NULL,
                  .flags = d->subgroup_size ? VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT : 0,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = d->cs,
                  .pName = "main",
                  .pSpecializationInfo = d->n_spec ? &si : NULL},
        .layout = d->layout,
    };
    PG_VK_TRY(err, vkCreateComputePipelines(gpu->device, gpu->pipeline_cache, 1, &ci, NULL, out));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_PIPELINE, (uint64_t)*out, "%s", name);
    pg_pipeline_stats_report(gpu, *out, name);
    return PG_OK;
}

void pg_cmd_viewport(VkCommandBuffer cmd, uint32_t w, uint32_t h)
{
    VkViewport vp = {0, 0, (float)w, (float)h, 0, 1};
    VkRect2D sc = {{0, 0}, {w, h}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
}

void pg_cmd_begin_rendering(VkCommandBuffer cmd, uint32_t w, uint32_t h, uint32_t n_color,
                            const VkImageView *color_views, const VkClearColorValue *clear_colors,
                            VkImageView depth_view, bool clear_depth, float depth_clear)
{
    VkRenderingAttachmentInfo ca[8];
    for (uint32_t i = 0; i < n_color && i < 8; i++) {
        ca[i] = (VkRenderingAttachmentInfo){
            .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = color_views[i],
            .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .loadOp = clear_colors ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD,
            .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        };
        if (clear_colors) ca[i].clearValue.color = clear_colors[i];
    }
    VkRenderingAttachmentInfo da = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = depth_view,
        .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .loadOp = clear_depth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD,
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        .clearValue.depthStencil = {depth_clear, 0},
    };
    VkRenderingInfo ri = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {w, h}},
        .layerCount = 1,
        .colorAttachmentCount = n_color,
        .pColorAttachments = ca,
        .pDepthAttachment = depth_view ? &da : NULL,
    };
    vkCmdBeginRendering(cmd, &ri);
    pg_cmd_viewport(cmd, w, h);
}

pg_result pg_sampler_create(pg_gpu *gpu, VkFilter filter, VkSamplerAddressMode address, VkSampler *out,
                            pg_error *err)
{
    VkSamplerCreateInfo sci = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = filter,
        .minFilter = filter,
        .addressModeU = address,
        .addressModeV = address,
        .addressModeW = address,
    };
    PG_VK_TRY(err, vkCreateSampler(gpu->device, &sci, NULL, out));
    return PG_OK;
}
