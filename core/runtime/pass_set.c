/* pass_set.c - pass-private descriptor sets (pass_set.h). */
#include "pass_set.h"

#include <string.h>

pg_result pg_pass_set_create(pg_gpu *gpu, uint32_t n, const pg_set_binding *b, const char *name, pg_pass_set *out,
                             pg_error *err)
{
    return pg_pass_set_create_numbered(gpu, n, b, NULL, name, out, err);
}

pg_result pg_pass_set_create_numbered(pg_gpu *gpu, uint32_t n, const pg_set_binding *b, const uint32_t *numbers,
                                      const char *name, pg_pass_set *out, pg_error *err)
{
    return pg_pass_set_create_windowed(gpu, n, b, numbers, NULL, 0, name, out, err);
}

pg_result pg_pass_set_create_windowed(pg_gpu *gpu, uint32_t n, const pg_set_binding *b, const uint32_t *numbers,
                                      const uint32_t *windows, VkDeviceSize window, const char *name,
                                      pg_pass_set *out, pg_error *err)
{
    memset(out, 0, sizeof *out);
    if (n > 16) return pg_fail(err, PG_ERR_LIMIT, "%s: too many bindings", name);
    VkDescriptorSetLayoutBinding lb[16];
    VkDescriptorPoolSize ps[16];
    for (uint32_t i = 0; i < n; i++) {
        uint32_t count = windows && windows[i] > 1 ? windows[i] : 1;
        if (count > PG_SET_MAX_WINDOWS)
            return pg_fail(err, PG_ERR_LIMIT, "%s: binding %u: %u windows, at most %u", name, i, count,
                           PG_SET_MAX_WINDOWS);
        bool storage = b[i].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        if (storage && count == 1 && b[i].res->size > gpu->max_storage_buffer_range)
            return pg_fail(err, PG_ERR_LIMIT,
                           "%s: binding %u: a storage buffer of %llu bytes, more than one binding spans on %s (%llu)",
                           name, i, (unsigned long long)b[i].res->size, gpu->props.deviceName,
                           (unsigned long long)gpu->max_storage_buffer_range);
        if (count > 1 && (!storage || window == 0 || window > gpu->max_storage_buffer_range ||
                          (count - 1) * window >= b[i].res->size || count * window < b[i].res->size))
            return pg_fail(err, PG_ERR_INVALID_ARG, "%s: binding %u: %u windows of %llu bytes do not cover %llu bytes",
                           name, i, count, (unsigned long long)window, (unsigned long long)b[i].res->size);
        lb[i] = (VkDescriptorSetLayoutBinding){numbers ? numbers[i] : i, b[i].type, count,
                                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
                                                   VK_SHADER_STAGE_COMPUTE_BIT,
                                               NULL};
        ps[i] = (VkDescriptorPoolSize){b[i].type, count};
    }
    VkDescriptorSetLayoutCreateInfo lci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = n, .pBindings = lb};
    PG_VK_TRY(err, vkCreateDescriptorSetLayout(gpu->device, &lci, NULL, &out->layout));
    if (n == 0) ps[0] = (VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}; /* a pool needs a size */
    VkDescriptorPoolCreateInfo pci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = 1, .poolSizeCount = lci.bindingCount ? lci.bindingCount : 1, .pPoolSizes = ps};
    PG_VK_TRY(err, vkCreateDescriptorPool(gpu->device, &pci, NULL, &out->pool));
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = out->pool, .descriptorSetCount = 1,
                                      .pSetLayouts = &out->layout};
    PG_VK_TRY(err, vkAllocateDescriptorSets(gpu->device, &ai, &out->set));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_DESCRIPTOR_SET, (uint64_t)out->set, "%s", name);
    VkWriteDescriptorSet w[16];
    VkDescriptorBufferInfo bi[16 * PG_SET_MAX_WINDOWS];
    VkDescriptorImageInfo ii[16];
    uint32_t nbi = 0;
    for (uint32_t i = 0; i < n; i++) {
        w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = out->set,
                                      .dstBinding = lb[i].binding, .descriptorCount = lb[i].descriptorCount,
                                      .descriptorType = b[i].type};
        if (b[i].type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || b[i].type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
            w[i].pBufferInfo = &bi[nbi];
            if (lb[i].descriptorCount == 1) bi[nbi++] = (VkDescriptorBufferInfo){b[i].res->buffer, 0, VK_WHOLE_SIZE};
            for (uint32_t k = 0; lb[i].descriptorCount > 1 && k < lb[i].descriptorCount; k++) {
                VkDeviceSize off = k * window, left = b[i].res->size - off;
                bi[nbi++] = (VkDescriptorBufferInfo){b[i].res->buffer, off, left < window ? left : window};
            }
        } else {
            VkImageLayout l = b[i].layout;
            if (!l)
                l = b[i].type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VK_IMAGE_LAYOUT_GENERAL
                                                                  : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
            ii[i] = (VkDescriptorImageInfo){b[i].sampler, b[i].res->view, l};
            w[i].pImageInfo = &ii[i];
        }
    }
    vkUpdateDescriptorSets(gpu->device, n, w, 0, NULL);
    return PG_OK;
}

void pg_pass_set_destroy(pg_gpu *gpu, pg_pass_set *s)
{
    if (s->pool) vkDestroyDescriptorPool(gpu->device, s->pool, NULL);
    if (s->layout) vkDestroyDescriptorSetLayout(gpu->device, s->layout, NULL);
    memset(s, 0, sizeof *s);
}

