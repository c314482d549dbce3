/* ui.h - a thin C interface to Dear ImGui (Debian libimgui-dev) and its GLFW + Vulkan backends,
 * for the viewer. Only what the viewer uses; every call maps to one ImGui call or a tiny
 * composition of them (tools/ui_imgui.cpp). */
#ifndef PG_UI_H
#define PG_UI_H

#include <stdbool.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

struct GLFWwindow;

typedef struct pg_ui_init_info {
    struct GLFWwindow *window;
    VkInstance instance;
    VkPhysicalDevice phys;
    VkDevice device;
    uint32_t queue_family;
    VkQueue queue;
    VkRenderPass render_pass;
    uint32_t image_count;
    VkPipelineCache pipeline_cache; /* the device's (pg_gpu.pipeline_cache), may be VK_NULL_HANDLE */
} pg_ui_init_info;

/* Returns false with a message in err (size err_size) on failure. */
bool pg_ui_init(const pg_ui_init_info *info, char *err, size_t err_size);
/* Uploads the font atlas with a one-shot command buffer the caller submits and waits for. */
bool pg_ui_upload_fonts(VkCommandBuffer cmd);
void pg_ui_upload_fonts_done(void);
void pg_ui_set_min_image_count(uint32_t n);
void pg_ui_shutdown(void);

void pg_ui_new_frame(void);
/* Ends the frame and records its draw commands (inside the caller's render pass). */
void pg_ui_render(VkCommandBuffer cmd);
bool pg_ui_want_mouse(void);
bool pg_ui_want_keyboard(void);

/* windows and layout */
bool pg_ui_begin(const char *title, float x, float y, float w, float h);
void pg_ui_end(void);
bool pg_ui_header(const char *label, bool default_open);
void pg_ui_separator(void);
void pg_ui_same_line(void);
void pg_ui_push_id(int id);
void pg_ui_pop_id(void);
float pg_ui_avail_width(void);

/* widgets: each returns true when the user changed the value (buttons: when clicked) */
void pg_ui_text(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
void pg_ui_text_colored(uint32_t rgba, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void pg_ui_text_wrapped(const char *text);
bool pg_ui_button(const char *label);
bool pg_ui_checkbox(const char *label, bool *v);
bool pg_ui_slider_int(const char *label, int *v, int min, int max, bool log);
bool pg_ui_slider_float(const char *label, float *v, float min, float max, const char *fmt, bool log);
bool pg_ui_input_int(const char *label, int *v);
bool pg_ui_combo(const char *label, int *current, const char *const *items, int n);
/* returns true when Enter was pressed */
bool pg_ui_input_text(const char *label, char *buf, size_t size);
void pg_ui_plot_lines(const char *label, const float *values, int n, int offset, const char *overlay,
                      float min, float max, float w, float h);
void pg_ui_tooltip(const char *text); /* for the last item, when hovered */

/* tables */
bool pg_ui_table_begin(const char *id, int columns);
void pg_ui_table_header(const char *const *names, int n);
void pg_ui_table_next_row(void);
void pg_ui_table_cell(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
void pg_ui_table_end(void);

/* a canvas: reserves w x h at the cursor; draw with coordinates relative to its top-left */
void pg_ui_canvas_begin(float w, float h);
void pg_ui_canvas_rect(float x0, float y0, float x1, float y1, uint32_t rgba, bool filled);
void pg_ui_canvas_text(float x, float y, uint32_t rgba, const char *text);
void pg_ui_canvas_end(void);

#ifdef __cplusplus
}
#endif
#endif
