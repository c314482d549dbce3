/* embed.c - a program that uses passgraph as a library (docs/embedding.md): it opens a session on a
 * pipeline and the built-in atrium, sets the camera, the lights and a parameter (the default
 * pipeline's grid_z), renders a frame into memory and writes it as a binary PPM, renders one into a
 * VkImage of its own and reads that back, prints every pass's GPU time and the error against the
 * reference pipeline (every light for every pixel).
 *
 *   embed [PIPELINE] [OUT.ppm]      (defaults: the installed forward_plus.json, embed.ppm)
 *
 * Built against the installed package by CMake (find_package(passgraph), examples/embed/
 * CMakeLists.txt) or by pkg-config (`cc embed.c $(pkg-config --cflags --libs passgraph)`);
 * scripts/check-install.sh does both and runs them. Exit status 0 only when every step worked and the
 * two images (memory, VkImage) agree. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <passgraph.h>

#define W 320
#define H 180

static int fail(const char *what, const pg_error *err)
{
    fprintf(stderr, "embed: %s: %s\n", what, err->msg);
    return 1;
}

/* A host-visible linear image of the session's device, for passgraph_render_to_image. */
typedef struct host_image {
    VkImage image;
    VkDeviceMemory memory;
} host_image;

static int make_image(const passgraph_vulkan *vk, host_image *out)
{
    VkImageCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = VK_FORMAT_R8G8B8A8_UNORM, .extent = {W, H, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .tiling = VK_IMAGE_TILING_LINEAR,
                            .usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT, .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    if (vkCreateImage(vk->device, &ci, NULL, &out->image) != VK_SUCCESS) return 1;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk->device, out->image, &req);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(vk->physical_device, &mp);
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < mp.memoryTypeCount && type == UINT32_MAX; i++)
        if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) type = i;
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = type};
    if (type == UINT32_MAX || vkAllocateMemory(vk->device, &ai, NULL, &out->memory) != VK_SUCCESS) return 1;
    return vkBindImageMemory(vk->device, out->image, out->memory, 0) != VK_SUCCESS;
}

/* Pixels of the linear image that differ from the RGBA8 frame read into memory. */
static int compare_image(const passgraph_vulkan *vk, const host_image *img, const uint8_t *rgba, uint32_t *differ)
{
    VkImageSubresource sub = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0};
    VkSubresourceLayout lay;
    vkGetImageSubresourceLayout(vk->device, img->image, &sub, &lay);
    void *map;
    if (vkMapMemory(vk->device, img->memory, 0, VK_WHOLE_SIZE, 0, &map) != VK_SUCCESS) return 1;
    *differ = 0;
    for (uint32_t y = 0; y < H; y++)
        *differ += memcmp((const uint8_t *)map + lay.offset + y * lay.rowPitch, rgba + (size_t)y * W * 4, W * 4) != 0;
    vkUnmapMemory(vk->device, img->memory);
    return 0;
}

int main(int argc, char **argv)
{
    const char *out_path = argc > 2 ? argv[2] : "embed.ppm";
    const char *pipeline = argc > 1 && argv[1][0] ? argv[1] : NULL; /* "" or none: the installed forward_plus.json */
    const char *sets[] = {"exposure=1"};
    passgraph_desc d = {.pipeline = pipeline, .width = W, .height = H, .params = sets, .n_params = 1,
                        .device = -1, .validation = getenv("EMBED_VALIDATION") != NULL};
    pg_error err = {0};
    passgraph *pg;
    if (passgraph_open(&d, &pg, &err)) return fail("open", &err);
    const float eye[3] = {0, 3, 12}, target[3] = {0, 3, 0}, up[3] = {0, 1, 0};
    int rc = 1;
    uint8_t *rgba = malloc((size_t)W * H * 4);
    if (passgraph_set_camera(pg, eye, target, up, 60, 0, 0, &err)) rc = fail("camera", &err);
    else if (passgraph_set_lights(pg, 1000, 3, 1.5f, &err)) rc = fail("lights", &err);
    else if (!passgraph_set_param(pg, "no_such_param", "1", &err)) rc = fail("an unknown parameter was taken", &err);
    /* errors are values: the refused key is taken back, the session goes on as it was */
    else if (passgraph_set_param(pg, "grid_z", "24", &err)) rc = fail("parameter", &err); /* a new variant */
    else if (passgraph_render(pg, &err)) rc = fail("render", &err);
    else if (!rgba || passgraph_read_rgba8(pg, rgba, (size_t)W * H * 4, &err)) rc = fail("read", &err);
    else rc = 0;
    if (rc == 0) {
        printf("embed: data folder %s\n", passgraph_data_dir());
        printf("embed: %ux%u, GPU %.3f ms:", W, H, passgraph_gpu_ms(pg));
        for (uint32_t i = 0; i < passgraph_pass_count(pg); i++)
            printf(" %s %.3f", passgraph_pass_name(pg, i), passgraph_pass_ms(pg, i));
        printf("\n");
        FILE *f = fopen(out_path, "wb");
        if (f) {
            fprintf(f, "P6\n%d %d\n255\n", W, H);
            for (size_t i = 0; i < (size_t)W * H; i++) fwrite(rgba + i * 4, 1, 3, f);
            fclose(f);
        } else {
            fprintf(stderr, "embed: cannot write %s\n", out_path);
            rc = 1;
        }
    }
    passgraph_error_stats e;
    if (rc == 0 && passgraph_error_against(pg, NULL, &e, &err)) rc = fail("error against the reference", &err);
    if (rc == 0)
        printf("embed: against the reference: RMSE %.3g, PSNR %.2f dB, max abs %.3g, %.4f of pixels off by > 1/255\n",
               e.rmse, e.psnr_db, e.max_abs, e.share_over_1);
    passgraph_vulkan vk;
    passgraph_get_vulkan(pg, &vk);
    host_image img = {0};
    uint32_t differ = 0;
    if (rc == 0 && make_image(&vk, &img)) rc = fail("VkImage", &(pg_error){.msg = "cannot make a linear host-visible image"});
    if (rc == 0 && passgraph_render_to_image(pg, img.image, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_LAYOUT_UNDEFINED,
                                             VK_IMAGE_LAYOUT_GENERAL, &err))
        rc = fail("render to image", &err);
    if (rc == 0 && compare_image(&vk, &img, rgba, &differ)) rc = fail("map", &(pg_error){.msg = "vkMapMemory failed"});
    if (rc == 0) {
        printf("embed: VkImage vs memory: %u of %d rows differ\n", differ, H);
        rc = differ != 0;
    }
    if (d.validation) {
        printf("embed: validation messages: %u\n", passgraph_validation_messages(pg));
        if (passgraph_validation_messages(pg)) rc = 1;
    }
    if (img.image) vkDestroyImage(vk.device, img.image, NULL);
    if (img.memory) vkFreeMemory(vk.device, img.memory, NULL);
    free(rgba);
    passgraph_close(pg);
    if (rc == 0) printf("embed: wrote %s\n", out_path);
    return rc;
}
