/* test_shader_layout.c - workgroup shapes the Vulkan rules ask for on every GPU, checked from the
 * SPIR-V glslang makes (no GPU). A compute pipeline created with
 * VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT and a required subgroup size must
 * have a workgroup X size that is a multiple of that size (VUID-VkPipelineShaderStageCreateInfo-
 * pNext-02757). The deferred lighting pass requires full subgroups for its tiled path
 * (PG_TILE_SUBGROUPS, passes/deferred_lighting.c) with the device's subgroup size: 8 on lavapipe,
 * 32 on NVIDIA, 64 on AMD. Its workgroup was once 8 x 8 (X = 8), valid on lavapipe and refused by
 * the validation layer on an H200; this test reads the LocalSize execution mode of every
 * tile-size variant and requires X to be a multiple of 64 (every subgroup size up to 64) and
 * Y = Z = 1, the tile as one dimension. */
#include <stdlib.h>
#include <string.h>

#include "shader.h"
#include "test_util.h"

/* The workgroup size: execution mode LocalSize (17) of OpExecutionMode (opcode 16), or LocalSizeId
 * (38) of OpExecutionModeId (331, what glslang emits for SPIR-V 1.6) whose operands are ids of
 * OpConstant (43) values. false if neither is found. */
static bool local_size(const uint32_t *w, size_t n, uint32_t out[3])
{
    uint32_t ids[3] = {0, 0, 0};
    bool by_id = false;
    for (size_t i = 5; i < n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        if (len == 0 || i + len > n) return false;
        if (op == 16 && len >= 6 && w[i + 2] == 17) {
            for (int k = 0; k < 3; k++) out[k] = w[i + 3 + k];
            return true;
        }
        if (op == 331 && len >= 6 && w[i + 2] == 38) {
            for (int k = 0; k < 3; k++) ids[k] = w[i + 3 + k];
            by_id = true;
        }
        i += len;
    }
    if (!by_id) return false;
    int found = 0;
    for (size_t i = 5; i < n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        if (len == 0 || i + len > n) return false;
        if (op == 43 && len == 4)
            for (int k = 0; k < 3; k++)
                if (w[i + 2] == ids[k]) {
                    out[k] = w[i + 3];
                    found |= 1 << k;
                }
        i += len;
    }
    return found == 7;
}

int main(void)
{
    static const char *const tiles[] = {"PG_TILE=8", "PG_TILE=16"};
    for (int t = 0; t < 2; t++) {
        const char *defs[] = {"PG_GBUFFER_OCT16", tiles[t], "PG_HDR_FORMAT=rgba16f", "PG_TILE_LIGHTS",
                              "PG_TILE_SUBGROUPS", "PG_CLUSTERED", "PG_HAS_LIGHTS", "GRID_X=16", "GRID_Y=9",
                              "GRID_Z=24", "PG_DEBUG_VIEW=0"};
        uint32_t *spv = NULL;
        size_t n = 0;
        pg_error err = {0};
        pg_result r = pg_shader_compile("deferred_lighting.comp", VK_SHADER_STAGE_COMPUTE_BIT, defs,
                                        sizeof defs / sizeof defs[0], &spv, &n, &err);
        CHECK_MSG(r == PG_OK, "%s: %s", tiles[t], err.msg);
        uint32_t ls[3] = {0, 0, 0};
        CHECK_MSG(r == PG_OK && local_size(spv, n, ls), "%s: no LocalSize execution mode", tiles[t]);
        printf("deferred_lighting.comp %s: local size %u x %u x %u\n", tiles[t], ls[0], ls[1], ls[2]);
        uint32_t tile = t == 0 ? 8 : 16;
        CHECK_MSG(ls[0] == tile * tile && ls[1] == 1 && ls[2] == 1, "%s: %u x %u x %u, want %u x 1 x 1", tiles[t], ls[0],
                  ls[1], ls[2], tile * tile);
        CHECK_MSG(ls[0] % 64 == 0, "%s: X = %u is not a multiple of 64 (full 64-wide subgroups impossible)", tiles[t],
                  ls[0]);
        free(spv);
    }
    return pg_test_finish("test_shader_layout");
}
