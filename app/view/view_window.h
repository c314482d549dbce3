/* view_window.h - the viewer's window side: GLFW window, Vulkan surface and swapchain (re-created
 * on resize / out-of-date, skipped while minimised), the UI render passes and per-frame
 * synchronisation (two frames in flight, like the graph's runtime in the viewer). */
#ifndef PG_VIEW_WINDOW_H
#define PG_VIEW_WINDOW_H

#include <stdbool.h>
#include <vulkan/vulkan.h>

#include "pg_common.h"
#include "vk_context.h"

struct GLFWwindow;

#define PG_VIEW_MAX_IMAGES 8

#define PG_VIEW_FRAMES 2

typedef struct pg_view_window {
    struct GLFWwindow *window;
    pg_gpu *gpu; /* borrowed */
    VkSurfaceKHR surface;
    VkSwapchainKHR swapchain;
    VkFormat format;
    VkColorSpaceKHR color_space;
    VkExtent2D extent;
    uint32_t n_images, min_images;
    VkImage images[PG_VIEW_MAX_IMAGES];
    VkImageView views[PG_VIEW_MAX_IMAGES];
    VkFramebuffer framebuffers[PG_VIEW_MAX_IMAGES];
    VkSemaphore render_done[PG_VIEW_MAX_IMAGES];
    VkSemaphore image_ready[PG_VIEW_FRAMES];
    VkRenderPass pass_present;    /* UI over the blitted frame, ends in PRESENT_SRC */
    VkRenderPass pass_capture;    /* same, ends in TRANSFER_SRC for a screenshot */
    /* two frames in flight: frame k records cmd[k % 2] and waits only for fence[k % 2] */
    VkCommandBuffer cmd[PG_VIEW_FRAMES];
    VkFence fence[PG_VIEW_FRAMES];        /* created signalled */
    uint32_t slot;
    bool usage_transfer_src;      /* swapchain images can be copied (screenshots) */
    uint32_t recreations;
} pg_view_window;

/* GLFW must be initialised (glfwInit) and the window created with GLFW_NO_API; the device must
 * have been created with the extensions glfwGetRequiredInstanceExtensions lists + swapchain. */
pg_result pg_view_window_create(pg_view_window *w, pg_gpu *gpu, struct GLFWwindow *window, pg_error *err);
/* (Re)creates the swapchain for the current framebuffer size. *minimised true: size 0, nothing
 * created; try again later. */
pg_result pg_view_window_resize(pg_view_window *w, bool *minimised, pg_error *err);
void pg_view_window_destroy(pg_view_window *w);

#endif
