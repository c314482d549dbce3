/* view_window.c - surface, swapchain and UI render passes for the viewer. */
#include "view_window.h"

#include <string.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

static pg_result make_render_pass(pg_gpu *gpu, VkFormat format, bool capture, VkRenderPass *out, pg_error *err)
{
    VkAttachmentDescription att = {
        .format = format,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD, /* the graph's frame was blitted in first */
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
        .finalLayout = capture ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
    };
    VkAttachmentReference ref = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub = {
        .pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
        .colorAttachmentCount = 1,
        .pColorAttachments = &ref,
    };
    VkSubpassDependency deps[2] = {
        {
            /* after the blit wrote the image */
            .srcSubpass = VK_SUBPASS_EXTERNAL,
            .dstSubpass = 0,
            .srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
            .dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
        },
        {
            /* before the screenshot copy (capture) or present (whose semaphore waits on all
             * commands). Both passes declare the same dependencies so they stay compatible (the UI
             * pipeline is built against one and used in both); only the final layout differs. */
            .srcSubpass = 0,
            .dstSubpass = VK_SUBPASS_EXTERNAL,
            .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
            .dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
            .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT,
        },
    };
    VkRenderPassCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
        .attachmentCount = 1,
        .pAttachments = &att,
        .subpassCount = 1,
        .pSubpasses = &sub,
        .dependencyCount = 2,
        .pDependencies = deps,
    };
    PG_VK_TRY(err, vkCreateRenderPass(gpu->device, &ci, NULL, out));
    pg_gpu_name(gpu, VK_OBJECT_TYPE_RENDER_PASS, (uint64_t)*out, "%s", capture ? "ui.capture" : "ui.present");
    return PG_OK;
}

static void destroy_swapchain(pg_view_window *w)
{
    VkDevice dev = w->gpu->device;
    for (uint32_t i = 0; i < w->n_images; i++) {
        if (w->framebuffers[i]) vkDestroyFramebuffer(dev, w->framebuffers[i], NULL);
        if (w->views[i]) vkDestroyImageView(dev, w->views[i], NULL);
        if (w->render_done[i]) vkDestroySemaphore(dev, w->render_done[i], NULL);
        w->framebuffers[i] = VK_NULL_HANDLE;
        w->views[i] = VK_NULL_HANDLE;
        w->render_done[i] = VK_NULL_HANDLE;
    }
    w->n_images = 0;
}

pg_result pg_view_window_create(pg_view_window *w, pg_gpu *gpu, GLFWwindow *window, pg_error *err)
{
    memset(w, 0, sizeof *w);
    w->gpu = gpu;
    w->window = window;
    VkResult r = glfwCreateWindowSurface(gpu->instance, window, NULL, &w->surface);
    if (r != VK_SUCCESS) return pg_fail(err, PG_ERR_VULKAN, "glfwCreateWindowSurface failed: %s", pg_vk_result_name(r));
    VkBool32 ok = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(gpu->phys, gpu->queue_family, w->surface, &ok);
    if (!ok) return pg_fail(err, PG_ERR_NO_DEVICE, "%s cannot present to this window", gpu->props.deviceName);
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu->phys, w->surface, &n, NULL);
    VkSurfaceFormatKHR fmts[64];
    if (n > 64) n = 64;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu->phys, w->surface, &n, fmts);
    if (!n) return pg_fail(err, PG_ERR_NO_DEVICE, "the window surface offers no format");
    w->format = fmts[0].format;
    w->color_space = fmts[0].colorSpace;
    for (uint32_t i = 0; i < n; i++) /* the graph writes sRGB-encoded 8-bit: blit into an sRGB image */
        if ((fmts[i].format == VK_FORMAT_B8G8R8A8_SRGB || fmts[i].format == VK_FORMAT_R8G8B8A8_SRGB) &&
            fmts[i].colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
            w->format = fmts[i].format;
            w->color_space = fmts[i].colorSpace;
            break;
        }
    pg_result res;
    if ((res = make_render_pass(gpu, w->format, false, &w->pass_present, err))) return res;
    if ((res = make_render_pass(gpu, w->format, true, &w->pass_capture, err))) return res;
    VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = gpu->cmd_pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = 1};
    for (int f = 0; f < PG_VIEW_FRAMES; f++) {
        PG_VK_TRY(err, vkCreateSemaphore(gpu->device, &sci, NULL, &w->image_ready[f]));
        PG_VK_TRY(err, vkCreateFence(gpu->device, &fci, NULL, &w->fence[f]));
        PG_VK_TRY(err, vkAllocateCommandBuffers(gpu->device, &ai, &w->cmd[f]));
    }
    return PG_OK;
}

pg_result pg_view_window_resize(pg_view_window *w, bool *minimised, pg_error *err)
{
    pg_gpu *gpu = w->gpu;
    *minimised = false;
    vkDeviceWaitIdle(gpu->device);
    VkSurfaceCapabilitiesKHR caps;
    PG_VK_TRY(err, vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu->phys, w->surface, &caps));
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w->window, &fw, &fh);
    VkExtent2D ext = caps.currentExtent;
    if (ext.width == UINT32_MAX) {
        ext.width = (uint32_t)(fw > 0 ? fw : 0);
        ext.height = (uint32_t)(fh > 0 ? fh : 0);
    }
    if (ext.width < caps.minImageExtent.width) ext.width = caps.minImageExtent.width;
    if (ext.height < caps.minImageExtent.height) ext.height = caps.minImageExtent.height;
    if (ext.width > caps.maxImageExtent.width) ext.width = caps.maxImageExtent.width;
    if (ext.height > caps.maxImageExtent.height) ext.height = caps.maxImageExtent.height;
    if (ext.width == 0 || ext.height == 0 || fw == 0 || fh == 0) {
        *minimised = true; /* keep the old swapchain until there is something to draw */
        return PG_OK;
    }
    uint32_t count = caps.minImageCount + 1;
    if (caps.maxImageCount && count > caps.maxImageCount) count = caps.maxImageCount;
    if (count > PG_VIEW_MAX_IMAGES) count = PG_VIEW_MAX_IMAGES;
    w->usage_transfer_src = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        return pg_fail(err, PG_ERR_NO_DEVICE, "swapchain images cannot be blit destinations on %s", gpu->props.deviceName);
    VkSwapchainKHR old = w->swapchain;
    VkSwapchainCreateInfoKHR ci = {
        .sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
        .surface = w->surface,
        .minImageCount = count,
        .imageFormat = w->format,
        .imageColorSpace = w->color_space,
        .imageExtent = ext,
        .imageArrayLayers = 1,
        .imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                      (w->usage_transfer_src ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .preTransform = caps.currentTransform,
        .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
        .presentMode = VK_PRESENT_MODE_FIFO_KHR, /* always supported */
        .clipped = VK_TRUE,
        .oldSwapchain = old,
    };
    if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR))
        ci.compositeAlpha = (VkCompositeAlphaFlagBitsKHR)(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    VkSwapchainKHR sc;
    PG_VK_TRY(err, vkCreateSwapchainKHR(gpu->device, &ci, NULL, &sc));
    destroy_swapchain(w);
    if (old) vkDestroySwapchainKHR(gpu->device, old, NULL);
    w->swapchain = sc;
    w->extent = ext;
    w->min_images = count;
    uint32_t n = 0;
    vkGetSwapchainImagesKHR(gpu->device, sc, &n, NULL);
    if (n > PG_VIEW_MAX_IMAGES) return pg_fail(err, PG_ERR_LIMIT, "swapchain has %u images (max %d)", n, PG_VIEW_MAX_IMAGES);
    PG_VK_TRY(err, vkGetSwapchainImagesKHR(gpu->device, sc, &n, w->images));
    w->n_images = n;
    for (uint32_t i = 0; i < n; i++) {
        pg_gpu_name(gpu, VK_OBJECT_TYPE_IMAGE, (uint64_t)w->images[i], "swapchain[%u]", i);
        VkImageViewCreateInfo vci = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = w->images[i],
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = w->format,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
        PG_VK_TRY(err, vkCreateImageView(gpu->device, &vci, NULL, &w->views[i]));
        VkFramebufferCreateInfo fci = {
            .sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
            .renderPass = w->pass_present,
            .attachmentCount = 1,
            .pAttachments = &w->views[i],
            .width = ext.width,
            .height = ext.height,
            .layers = 1,
        };
        PG_VK_TRY(err, vkCreateFramebuffer(gpu->device, &fci, NULL, &w->framebuffers[i]));
        VkSemaphoreCreateInfo sci = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        PG_VK_TRY(err, vkCreateSemaphore(gpu->device, &sci, NULL, &w->render_done[i]));
    }
    w->recreations++;
    return PG_OK;
}

void pg_view_window_destroy(pg_view_window *w)
{
    if (!w->gpu) return;
    VkDevice dev = w->gpu->device;
    vkDeviceWaitIdle(dev);
    destroy_swapchain(w);
    if (w->swapchain) vkDestroySwapchainKHR(dev, w->swapchain, NULL);
    if (w->pass_present) vkDestroyRenderPass(dev, w->pass_present, NULL);
    if (w->pass_capture) vkDestroyRenderPass(dev, w->pass_capture, NULL);
    for (int f = 0; f < PG_VIEW_FRAMES; f++) {
        if (w->image_ready[f]) vkDestroySemaphore(dev, w->image_ready[f], NULL);
        if (w->fence[f]) vkDestroyFence(dev, w->fence[f], NULL);
        if (w->cmd[f]) vkFreeCommandBuffers(dev, w->gpu->cmd_pool, 1, &w->cmd[f]);
    }
    if (w->surface) vkDestroySurfaceKHR(w->gpu->instance, w->surface, NULL);
    memset(w, 0, sizeof *w);
}
