/* scene_gpu.c - uploads a pg_scene once; everything here is read-only afterwards. */
#include "scene_gpu.h"
#include "scene_gpu_anim.h"

#include "environment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Where each part lies in the one staging buffer: vertices | colours | uv1 | indices | materials |
 * file lights | environment (every level) | white texel | every mip of every texture (16-byte aligned from the white texel on). */
typedef struct staging_layout {
    VkDeviceSize vb, cb, ub, ib, mb, lb; /* bytes of vertices, colours, uv1, indices, materials, lights */
    VkDeviceSize eb, e_off;          /* bytes and offset of the environment's texels */
    VkDeviceSize qb, q_off;          /* bytes and offset of its sampling tables (cdf) */
    uint32_t n_mat;                  /* materials (1, the default, when the scene has none) */
    VkDeviceSize v_off, c_off, u_off, i_off, m_off, l_off, white_off;
    VkDeviceSize *tex_off; /* per texture */
} staging_layout;

/* the byte counts of L and the staging buffer's size */
static VkDeviceSize staging_size(const pg_scene_gpu *sg, const pg_scene *scene, staging_layout *L)
{
    L->vb = (VkDeviceSize)scene->n_vertices * sizeof(pg_vertex);
    L->cb = sg->colors.buffer ? (VkDeviceSize)scene->n_vertices * sizeof(float[4]) : 0;
    L->ub = sg->uv1.buffer ? (VkDeviceSize)scene->n_vertices * sizeof(float[2]) : 0;
    L->ib = (VkDeviceSize)scene->n_indices * sizeof(uint32_t);
    L->n_mat = scene->n_materials ? scene->n_materials : 1;
    L->mb = (VkDeviceSize)L->n_mat * sizeof(pg_gpu_material);
    L->lb = (VkDeviceSize)scene->n_lights * sizeof(pg_gpu_file_light);
    L->eb = scene->environment ? scene->environment->n_texels * 16 : 0;
    L->qb = scene->environment ? scene->environment->n_cdf * sizeof(float) : 0;
    VkDeviceSize total = L->vb + L->cb + L->ub + L->ib + L->mb + L->lb + L->eb + L->qb + 48;
    for (uint32_t t = 0; t < scene->n_textures; t++) total += (scene->textures[t].data_size + 15) & ~(VkDeviceSize)15;
    total += 16; /* white texel */
    return total;
}

/* the file's lights as light_animate reads them */
static void gpu_file_lights(const pg_scene *scene, pg_gpu_file_light *fl)
{
    for (uint32_t i = 0; i < scene->n_lights; i++) pg_gpu_file_light_from(&scene->lights[i], &fl[i]);
}


/* the scene's arrays, materials and textures written to the staging memory; offsets into L */
static void fill_staging(uint8_t *dst, const pg_scene *scene, staging_layout *L)
{
    VkDeviceSize off = 0;
    memcpy(dst + off, scene->vertices, L->vb);
    L->v_off = off;
    off += L->vb;
    L->c_off = off;
    if (L->cb) memcpy(dst + off, scene->colors, L->cb);
    off += L->cb;
    L->u_off = off;
    if (L->ub) memcpy(dst + off, scene->uv1, L->ub);
    off += L->ub;
    L->i_off = off;
    memcpy(dst + off, scene->indices, L->ib);
    off += L->ib;
    L->m_off = off;
    pg_gpu_material *gm = (pg_gpu_material *)(dst + off);
    for (uint32_t m = 0; m < L->n_mat; m++) {
        pg_material dm;
        pg_material_init(&dm, "default");
        pg_gpu_material_from(scene->n_materials ? &scene->materials[m] : &dm, &gm[m]);
    }
    off += L->mb;
    L->l_off = off;
    gpu_file_lights(scene, (pg_gpu_file_light *)(dst + off));
    off += L->lb;
    off = (off + 15) & ~(VkDeviceSize)15;
    L->e_off = off;
    if (L->eb) memcpy(dst + off, scene->environment->rgba, L->eb);
    off += L->eb;
    L->q_off = off;
    if (L->qb) memcpy(dst + off, scene->environment->cdf, L->qb);
    off = (off + L->qb + 15) & ~(VkDeviceSize)15;
    L->white_off = off;
    static const uint8_t white[4] = {255, 255, 255, 255};
    memcpy(dst + off, white, 4);
    off += 16;
    for (uint32_t t = 0; t < scene->n_textures; t++) {
        L->tex_off[t] = off;
        memcpy(dst + off, scene->textures[t].data, scene->textures[t].data_size);
        off += (scene->textures[t].data_size + 15) & ~(VkDeviceSize)15;
    }
}

/* staging -> the buffers */
static void copy_buffers(VkCommandBuffer cmd, VkBuffer staging, const pg_scene_gpu *sg, const staging_layout *L)
{
    VkBufferCopy c0 = {L->v_off, 0, L->vb};
    if (L->vb) vkCmdCopyBuffer(cmd, staging, sg->vertices.buffer, 1, &c0);
    VkBufferCopy c1 = {L->i_off, 0, L->ib};
    if (L->ib) vkCmdCopyBuffer(cmd, staging, sg->indices.buffer, 1, &c1);
    VkBufferCopy c2 = {L->m_off, 0, L->mb};
    vkCmdCopyBuffer(cmd, staging, sg->materials.buffer, 1, &c2);
    VkBufferCopy c3 = {L->c_off, 0, L->cb}, c4 = {L->u_off, 0, L->ub}, c5 = {L->l_off, 0, L->lb};
    if (L->lb) vkCmdCopyBuffer(cmd, staging, sg->file_lights.buffer, 1, &c5);
    VkBufferCopy c6 = {L->e_off, 0, L->eb};
    if (L->eb) vkCmdCopyBuffer(cmd, staging, sg->environment.buffer, 1, &c6);
    VkBufferCopy c7 = {L->q_off, 0, L->qb};
    if (L->qb) vkCmdCopyBuffer(cmd, staging, sg->env_cdf.buffer, 1, &c7);
    if (L->cb) vkCmdCopyBuffer(cmd, staging, sg->colors.buffer, 1, &c3);
    if (L->ub) vkCmdCopyBuffer(cmd, staging, sg->uv1.buffer, 1, &c4);
}

/* staging -> the images (the white texel, then every mip of every texture), each image made a
 * transfer destination first (bars: one barrier per image) */
static void copy_images(VkCommandBuffer cmd, VkBuffer staging, const pg_scene_gpu *sg, const pg_scene *scene,
                        const staging_layout *L, VkImageMemoryBarrier2 *bars)
{
    for (uint32_t i = 0; i < sg->n_images; i++)
        bars[i] = pg_image_barrier(sg->images[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                   VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    pg_cmd_barriers(cmd, sg->n_images, bars, 0, NULL);
    VkBufferImageCopy wc = {.bufferOffset = L->white_off,
                            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .imageExtent = {1, 1, 1}};
    vkCmdCopyBufferToImage(cmd, staging, sg->images[0].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &wc);
    for (uint32_t t = 0; t < scene->n_textures; t++) {
        const pg_texture *tex = &scene->textures[t];
        VkBufferImageCopy regions[PG_MAX_MIPS];
        for (uint32_t m = 0; m < tex->n_mips; m++) {
            regions[m] = (VkBufferImageCopy){
                .bufferOffset = L->tex_off[t] + (VkDeviceSize)(tex->mips[m].rgba - tex->data),
                .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1},
                .imageExtent = {tex->mips[m].width, tex->mips[m].height, 1},
            };
        }
        vkCmdCopyBufferToImage(cmd, staging, sg->images[t + 1].image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, tex->n_mips, regions);
    }
}

/* after the copies: the images to shader reads, the buffers to their readers (the vertex streams
 * and indices are also storage buffers of the compute passes that rebuild surfaces from triangle
 * ids: visibility_shade, visibility_gbuffer; the file lights are read by light_animate) */
static void release_to_shaders(VkCommandBuffer cmd, const pg_scene_gpu *sg, VkImageMemoryBarrier2 *bars)
{
    for (uint32_t i = 0; i < sg->n_images; i++)
        bars[i] = pg_image_barrier(sg->images[i].image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                                   VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    VkBufferMemoryBarrier2 bb[8];
    VkBuffer bufs[8] = {sg->vertices.buffer, sg->indices.buffer, sg->materials.buffer, sg->colors.buffer,
                        sg->uv1.buffer, sg->file_lights.buffer, sg->environment.buffer, sg->env_cdf.buffer};
    const VkAccessFlags2 sr = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    const VkPipelineStageFlags2 cs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    VkAccessFlags2 acc[8] = {VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | sr, VK_ACCESS_2_INDEX_READ_BIT | sr,
                             VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | sr,
                             VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | sr, sr, sr, sr};
    VkPipelineStageFlags2 st[8] = {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | cs,
                                   VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT | cs,
                                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | cs,
                                   VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | cs,
                                   VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | cs, cs, cs, cs};
    uint32_t n_bb = 0;
    for (int i = 0; i < 8; i++) {
        if (!bufs[i]) continue;
        bb[n_bb++] = pg_buffer_barrier(bufs[i], VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, st[i],
                                       acc[i]);
    }
    pg_cmd_barriers(cmd, sg->n_images, bars, n_bb, bb);
}

/* the scene's data to the buffers and images, through one staging buffer and one submit */
static pg_result upload(pg_gpu *gpu, pg_scene_gpu *sg, const pg_scene *scene, pg_error *err)
{
    staging_layout L = {0};
    VkDeviceSize total = staging_size(sg, scene, &L);
    pg_result r;
    pg_buffer staging;
    if ((r = pg_buffer_create(gpu, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, "scene.staging", &staging, err)))
        return r;
    L.tex_off = calloc(scene->n_textures + 1, sizeof *L.tex_off);
    if (!L.tex_off) {
        pg_buffer_destroy(gpu, &staging);
        return pg_fail(err, PG_ERR_OOM, "out of memory");
    }
    fill_staging(staging.mapped, scene, &L);

    VkCommandBuffer cmd;
    if ((r = pg_gpu_begin_once(gpu, &cmd, err))) goto out;
    copy_buffers(cmd, staging.buffer, sg, &L);
    VkImageMemoryBarrier2 *bars = calloc(sg->n_images, sizeof *bars);
    if (!bars) {
        vkEndCommandBuffer(cmd);
        vkFreeCommandBuffers(gpu->device, gpu->cmd_pool, 1, &cmd);
        r = pg_fail(err, PG_ERR_OOM, "out of memory");
        goto out;
    }
    copy_images(cmd, staging.buffer, sg, scene, &L, bars);
    release_to_shaders(cmd, sg, bars);
    free(bars);
    r = pg_gpu_end_once(gpu, cmd, err);
out:
    free(L.tex_off);
    pg_buffer_destroy(gpu, &staging);
    return r;
}

/* field by field: the struct has padding */
static bool same_state(const pg_sampler_state *a, const pg_sampler_state *b)
{
    return a->wrap_s == b->wrap_s && a->wrap_t == b->wrap_t && a->mag_nearest == b->mag_nearest &&
           a->min_nearest == b->min_nearest && a->mip == b->mip;
}

pg_result pg_scene_sampler_create(pg_gpu *gpu, const pg_sampler_state *st, VkSampler *out, pg_error *err)
{
    static const VkSamplerAddressMode wrap[3] = {VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                                 VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT};
    VkSamplerCreateInfo sci = {
        .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
        .magFilter = st->mag_nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
        .minFilter = st->min_nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
        .mipmapMode = st->mip == PG_MIP_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST,
        .addressModeU = wrap[st->wrap_s <= PG_WRAP_MIRROR ? st->wrap_s : 0],
        .addressModeV = wrap[st->wrap_t <= PG_WRAP_MIRROR ? st->wrap_t : 0],
        .addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT,
        .maxLod = st->mip == PG_MIP_NONE ? 0.0f : VK_LOD_CLAMP_NONE, /* NONE: level 0 only */
    };
    VkResult vr = vkCreateSampler(gpu->device, &sci, NULL, out);
    if (vr != VK_SUCCESS) return pg_fail(err, PG_ERR_VULKAN, "vkCreateSampler failed: %s", pg_vk_result_name(vr));
    return PG_OK;
}

static int draw_cmp(const void *a, const void *b)
{
    const pg_draw *x = a, *y = b;
    if (x->blend != y->blend) return x->blend ? 1 : -1;
    if (x->alpha_mask != y->alpha_mask) return x->alpha_mask ? 1 : -1;
    if (x->material != y->material) return x->material < y->material ? -1 : 1;
    return x->first_index < y->first_index ? -1 : (x->first_index > y->first_index);
}

/* a device-local buffer of the scene, filled by upload (its usage plus TRANSFER_DST) */
static pg_result scene_buffer(pg_gpu *gpu, VkDeviceSize size, VkBufferUsageFlags usage, const char *name,
                              pg_buffer *out, pg_error *err)
{
    /* concurrent over both queue families: compute passes on the second queue read them too */
    return pg_buffer_create_ex(gpu, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, true, name, out, err);
}

/* vertices, indices, materials, and the optional streams only for a scene that uses them (the
 * draw passes compile their paths from the same features) */
static pg_result create_buffers(pg_gpu *gpu, pg_scene_gpu *sg, const pg_scene *scene, pg_error *err)
{
    const VkBufferUsageFlags vs = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    uint32_t n_mat = scene->n_materials ? scene->n_materials : 1;
    pg_result r;
    if ((r = scene_buffer(gpu, (VkDeviceSize)scene->n_vertices * sizeof(pg_vertex), vs, "scene.vertices",
                          &sg->vertices, err)) ||
        (r = scene_buffer(gpu, (VkDeviceSize)scene->n_indices * sizeof(uint32_t),
                          VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.indices",
                          &sg->indices, err)) ||
        (r = scene_buffer(gpu, (VkDeviceSize)n_mat * sizeof(pg_gpu_material), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          "scene.materials", &sg->materials, err)))
        return r;
    if (scene->features.has_vertex_colors) {
        if (!scene->colors)
            return pg_fail(err, PG_ERR_INVALID_ARG, "scene '%s': has_vertex_colors without colors", scene->name);
        if ((r = scene_buffer(gpu, (VkDeviceSize)scene->n_vertices * sizeof(float[4]), vs, "scene.colors",
                              &sg->colors, err)))
            return r;
    }
    if (scene->features.has_uv1) {
        if (!scene->uv1) return pg_fail(err, PG_ERR_INVALID_ARG, "scene '%s': has_uv1 without uv1", scene->name);
        if ((r = scene_buffer(gpu, (VkDeviceSize)scene->n_vertices * sizeof(float[2]), vs, "scene.uv1", &sg->uv1,
                              err)))
            return r;
    }
    if (scene->n_lights > 0) { /* device-local, filled by the upload; read once a frame by light_animate */
        if ((r = scene_buffer(gpu, (VkDeviceSize)scene->n_lights * sizeof(pg_gpu_file_light),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene.file_lights", &sg->file_lights, err)))
            return r;
        sg->n_file_lights = scene->n_lights;
    }
    if (scene->environment) { /* every level; read by environment_filter and reference_lighting */
        const pg_environment *e = scene->environment;
        if ((r = scene_buffer(gpu, (VkDeviceSize)e->n_texels * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              "scene.environment", &sg->environment, err)))
            return r;
        if (e->cdf && (r = scene_buffer(gpu, (VkDeviceSize)e->n_cdf * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        "scene.env_cdf", &sg->env_cdf, err)))
            return r;
        sg->env_levels = e->n_levels;
        sg->env_width = e->width[0];
        sg->env_height = e->height[0];
        sg->env_id = e->id;
    }
    sg->bytes = sg->vertices.size + sg->indices.size + sg->materials.size + sg->colors.size + sg->uv1.size +
                sg->file_lights.size + sg->environment.size + sg->env_cdf.size;
    return PG_OK;
}

/* image 0 the white texel, image t + 1 texture t (sRGB or linear, every mip) */
static pg_result create_images(pg_gpu *gpu, pg_scene_gpu *sg, const pg_scene *scene, pg_error *err)
{
    sg->n_images = scene->n_textures + 1;
    sg->images = calloc(sg->n_images, sizeof *sg->images);
    if (!sg->images) return pg_fail(err, PG_ERR_OOM, "out of memory");
    VkImageUsageFlags iu = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    pg_result r;
    if ((r = pg_image_create(gpu, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1, iu, "scene.white", &sg->images[0], err)))
        return r;
    for (uint32_t t = 0; t < scene->n_textures; t++) {
        const pg_texture *tex = &scene->textures[t];
        char name[PG_NAME_MAX + 16];
        snprintf(name, sizeof name, "tex.%s", tex->name);
        if ((r = pg_image_create(gpu, tex->srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM,
                                 tex->mips[0].width, tex->mips[0].height, tex->n_mips, iu, name,
                                 &sg->images[t + 1], err)))
            return r;
        sg->bytes += tex->data_size;
    }
    return PG_OK;
}

/* one sampler per distinct state; [0] is the default (the white texture's); *tex_sampler (made
 * here, n_textures + 1 entries, freed by the caller): image i's sampler */
static pg_result create_samplers(pg_gpu *gpu, pg_scene_gpu *sg, const pg_scene *scene, uint32_t **tex_sampler,
                                 pg_error *err)
{
    *tex_sampler = calloc(scene->n_textures + 1, sizeof **tex_sampler);
    sg->samplers = calloc(scene->n_textures + 1, sizeof *sg->samplers);
    sg->sampler_states = calloc(scene->n_textures + 1, sizeof *sg->sampler_states);
    if (!*tex_sampler || !sg->samplers || !sg->sampler_states) return pg_fail(err, PG_ERR_OOM, "out of memory");
    memset(&sg->sampler_states[0], 0, sizeof sg->sampler_states[0]);
    sg->n_samplers = 1;
    for (uint32_t t = 0; t < scene->n_textures; t++) {
        const pg_sampler_state *ss = &scene->textures[t].sampler;
        uint32_t k = 0;
        while (k < sg->n_samplers && !same_state(&sg->sampler_states[k], ss)) k++;
        if (k == sg->n_samplers) sg->sampler_states[sg->n_samplers++] = *ss;
        (*tex_sampler)[t + 1] = k;
    }
    pg_result r;
    for (uint32_t k = 0; k < sg->n_samplers; k++) {
        if ((r = pg_scene_sampler_create(gpu, &sg->sampler_states[k], &sg->samplers[k], err))) return r;
    }
    return PG_OK;
}

/* the scene's descriptor set: binding 0 the materials, binding 1 every image with its sampler */
static pg_result create_descriptor_set(pg_gpu *gpu, pg_scene_gpu *sg, const uint32_t *tex_sampler, pg_error *err)
{
    VkDescriptorSetLayoutBinding b[2] = {
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
         VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_COMPUTE_BIT, NULL},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, sg->n_images,
         VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, NULL},
    };
    VkDescriptorSetLayoutCreateInfo lci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 2, .pBindings = b};
    VkResult vr = vkCreateDescriptorSetLayout(gpu->device, &lci, NULL, &sg->set_layout);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "vkCreateDescriptorSetLayout failed: %s", pg_vk_result_name(vr));
    VkDescriptorPoolSize ps[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, sg->n_images}};
    VkDescriptorPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = 1, .poolSizeCount = 2, .pPoolSizes = ps};
    vr = vkCreateDescriptorPool(gpu->device, &pci, NULL, &sg->pool);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "vkCreateDescriptorPool failed: %s", pg_vk_result_name(vr));
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = sg->pool, .descriptorSetCount = 1,
                                      .pSetLayouts = &sg->set_layout};
    vr = vkAllocateDescriptorSets(gpu->device, &ai, &sg->set);
    if (vr != VK_SUCCESS)
        return pg_fail(err, PG_ERR_VULKAN, "vkAllocateDescriptorSets failed: %s", pg_vk_result_name(vr));
    VkDescriptorImageInfo *ii = calloc(sg->n_images, sizeof *ii);
    if (!ii) return pg_fail(err, PG_ERR_OOM, "out of memory");
    for (uint32_t i = 0; i < sg->n_images; i++)
        ii[i] = (VkDescriptorImageInfo){sg->samplers[tex_sampler[i]], sg->images[i].view,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorBufferInfo bi = {sg->materials.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[2] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = sg->set, .dstBinding = 0,
         .descriptorCount = 1, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &bi},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = sg->set, .dstBinding = 1,
         .descriptorCount = sg->n_images, .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
         .pImageInfo = ii},
    };
    vkUpdateDescriptorSets(gpu->device, 2, w, 0, NULL);
    free(ii);
    return PG_OK;
}

/* one draw per primitive with triangles, sorted: opaque, then alpha-masked, then blended, each by
 * material */
static pg_result build_draws(pg_scene_gpu *sg, const pg_scene *scene, pg_error *err)
{
    uint32_t n_mat = scene->n_materials ? scene->n_materials : 1;
    sg->draws = calloc(scene->n_primitives ? scene->n_primitives : 1, sizeof *sg->draws);
    if (!sg->draws) return pg_fail(err, PG_ERR_OOM, "out of memory");
    for (uint32_t p = 0; p < scene->n_primitives; p++) {
        const pg_primitive *pr = &scene->primitives[p];
        if (!pr->index_count) continue;
        uint32_t m = pr->material < n_mat ? pr->material : 0;
        bool mask = scene->n_materials && scene->materials[m].alpha_mode == PG_ALPHA_MASK;
        bool blend = scene->n_materials && scene->materials[m].alpha_mode == PG_ALPHA_BLEND;
        bool two = scene->n_materials && scene->materials[m].double_sided;
        pg_draw d = {pr->first_index, pr->index_count, pr->vertex_offset, m, mask, blend, two, {0, 0, 0}, -1};
        for (int k = 0; k < 3; k++) d.center[k] = 0.5f * (pr->bounds_min[k] + pr->bounds_max[k]);
        sg->draws[sg->n_draws++] = d;
        if (blend) sg->n_blend_draws++;
        else if (!mask) sg->n_opaque_draws++;
    }
    qsort(sg->draws, sg->n_draws, sizeof *sg->draws, draw_cmp);
    return PG_OK;
}

pg_result pg_scene_gpu_create(pg_gpu *gpu, const pg_scene *scene, pg_scene_gpu **out, pg_error *err)
{
    *out = NULL;
    pg_scene_gpu *sg = calloc(1, sizeof *sg);
    if (!sg) return pg_fail(err, PG_ERR_OOM, "out of memory");
    uint32_t *tex_sampler = NULL; /* texture -> index into sg->samplers */
    sg->features = scene->features;
    memcpy(sg->bounds_min, scene->bounds_min, sizeof sg->bounds_min);
    memcpy(sg->bounds_max, scene->bounds_max, sizeof sg->bounds_max);
    pg_result r;
    if ((r = create_buffers(gpu, sg, scene, err)) || (r = create_images(gpu, sg, scene, err)) ||
        (r = create_samplers(gpu, sg, scene, &tex_sampler, err)) || (r = upload(gpu, sg, scene, err)) ||
        (r = create_descriptor_set(gpu, sg, tex_sampler, err)))
        goto fail;
    free(tex_sampler);
    tex_sampler = NULL;
    if ((r = build_draws(sg, scene, err))) goto fail;
    if ((r = pg_scene_gpu_anim_create(gpu, scene, &sg->anim, err))) goto fail;
    for (uint32_t i = 0; sg->anim && i < sg->n_draws; i++) { /* the rigid moving draws: a pose may mirror them */
        const int32_t k = pg_scene_gpu_anim_prim_at(sg->anim, sg->draws[i].vertex_offset);
        if (k >= 0 && scene->anim->prims[k].skin < 0) sg->draws[i].anim_prim = k;
    }
    if (sg->anim) sg->bytes += sg->anim->local.size + sg->anim->info.size + sg->anim->prims.size +
                               sg->anim->deltas.size + sg->anim->pose.size;
    *out = sg;
    return PG_OK;
fail:
    free(tex_sampler);
    pg_scene_gpu_destroy(gpu, sg);
    return r;
}

void pg_scene_gpu_destroy(pg_gpu *gpu, pg_scene_gpu *sg)
{
    if (!sg) return;
    if (sg->pool) vkDestroyDescriptorPool(gpu->device, sg->pool, NULL);
    if (sg->set_layout) vkDestroyDescriptorSetLayout(gpu->device, sg->set_layout, NULL);
    for (uint32_t k = 0; sg->samplers && k < sg->n_samplers; k++)
        if (sg->samplers[k]) vkDestroySampler(gpu->device, sg->samplers[k], NULL);
    free(sg->samplers);
    free(sg->sampler_states);
    for (uint32_t i = 0; sg->images && i < sg->n_images; i++) pg_image_destroy(gpu, &sg->images[i]);
    free(sg->images);
    pg_buffer_destroy(gpu, &sg->vertices);
    pg_buffer_destroy(gpu, &sg->indices);
    pg_buffer_destroy(gpu, &sg->materials);
    pg_buffer_destroy(gpu, &sg->colors);
    pg_buffer_destroy(gpu, &sg->uv1);
    pg_buffer_destroy(gpu, &sg->file_lights);
    pg_buffer_destroy(gpu, &sg->environment);
    pg_buffer_destroy(gpu, &sg->env_cdf);
    pg_scene_gpu_anim_destroy(gpu, sg->anim);
    free(sg->draws);
    free(sg);
}
