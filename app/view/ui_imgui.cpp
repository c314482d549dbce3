// ui_imgui.cpp - the thin shim behind tools/ui.h: plain forwarding to Dear ImGui 1.86 and its
// GLFW and Vulkan backends as Debian ships them (libimgui-dev, libimgui.a includes the backends).
#include "ui.h"

#include <cstdarg>
#include <cstdio>
#include <cstring>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

static VkDescriptorPool g_pool = VK_NULL_HANDLE;
static VkDevice g_device = VK_NULL_HANDLE;
static ImVec2 g_canvas_origin;
static bool g_ready = false;

static ImU32 col(uint32_t rgba)
{
    return IM_COL32((rgba >> 24) & 255, (rgba >> 16) & 255, (rgba >> 8) & 255, rgba & 255);
}

extern "C" bool pg_ui_init(const pg_ui_init_info *info, char *err, size_t err_size)
{
    g_device = info->device;
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
    VkDescriptorPoolCreateInfo pci = {};
    pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pci.maxSets = 16;
    pci.poolSizeCount = 1;
    pci.pPoolSizes = sizes;
    if (vkCreateDescriptorPool(info->device, &pci, nullptr, &g_pool) != VK_SUCCESS) {
        snprintf(err, err_size, "ImGui: vkCreateDescriptorPool failed");
        return false;
    }
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini next to wherever the viewer runs
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    if (!ImGui_ImplGlfw_InitForVulkan(info->window, true)) {
        snprintf(err, err_size, "ImGui: GLFW backend init failed");
        return false;
    }
    ImGui_ImplVulkan_InitInfo ii = {};
    ii.Instance = info->instance;
    ii.PhysicalDevice = info->phys;
    ii.Device = info->device;
    ii.QueueFamily = info->queue_family;
    ii.Queue = info->queue;
    ii.DescriptorPool = g_pool;
    ii.PipelineCache = info->pipeline_cache;
    ii.MinImageCount = info->image_count < 2 ? 2 : info->image_count;
    ii.ImageCount = info->image_count < 2 ? 2 : info->image_count;
    ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    if (!ImGui_ImplVulkan_Init(&ii, info->render_pass)) {
        snprintf(err, err_size, "ImGui: Vulkan backend init failed");
        return false;
    }
    g_ready = true;
    return true;
}

extern "C" bool pg_ui_upload_fonts(VkCommandBuffer cmd) { return ImGui_ImplVulkan_CreateFontsTexture(cmd); }
extern "C" void pg_ui_upload_fonts_done(void) { ImGui_ImplVulkan_DestroyFontUploadObjects(); }
extern "C" void pg_ui_set_min_image_count(uint32_t n) { ImGui_ImplVulkan_SetMinImageCount(n < 2 ? 2 : n); }

extern "C" void pg_ui_shutdown(void)
{
    if (g_ready) {
        ImGui_ImplVulkan_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        g_ready = false;
    }
    if (g_pool) vkDestroyDescriptorPool(g_device, g_pool, nullptr);
    g_pool = VK_NULL_HANDLE;
}

extern "C" void pg_ui_new_frame(void)
{
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

extern "C" void pg_ui_render(VkCommandBuffer cmd)
{
    ImGui::Render();
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

extern "C" bool pg_ui_want_mouse(void) { return ImGui::GetIO().WantCaptureMouse; }
extern "C" bool pg_ui_want_keyboard(void) { return ImGui::GetIO().WantCaptureKeyboard; }

extern "C" bool pg_ui_begin(const char *title, float x, float y, float w, float h)
{
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(w, h), ImGuiCond_FirstUseEver);
    return ImGui::Begin(title);
}
extern "C" void pg_ui_end(void) { ImGui::End(); }
extern "C" bool pg_ui_header(const char *label, bool default_open)
{
    return ImGui::CollapsingHeader(label, default_open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}
extern "C" void pg_ui_separator(void) { ImGui::Separator(); }
extern "C" void pg_ui_same_line(void) { ImGui::SameLine(); }
extern "C" void pg_ui_push_id(int id) { ImGui::PushID(id); }
extern "C" void pg_ui_pop_id(void) { ImGui::PopID(); }
extern "C" float pg_ui_avail_width(void) { return ImGui::GetContentRegionAvail().x; }

extern "C" void pg_ui_text(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}
extern "C" void pg_ui_text_colored(uint32_t rgba, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextColoredV(ImGui::ColorConvertU32ToFloat4(col(rgba)), fmt, ap);
    va_end(ap);
}
extern "C" void pg_ui_text_wrapped(const char *text) { ImGui::TextWrapped("%s", text); }
extern "C" bool pg_ui_button(const char *label) { return ImGui::Button(label); }
extern "C" bool pg_ui_checkbox(const char *label, bool *v) { return ImGui::Checkbox(label, v); }
extern "C" bool pg_ui_slider_int(const char *label, int *v, int min, int max, bool log)
{
    return ImGui::SliderInt(label, v, min, max, "%d", log ? ImGuiSliderFlags_Logarithmic : 0);
}
extern "C" bool pg_ui_slider_float(const char *label, float *v, float min, float max, const char *fmt, bool log)
{
    return ImGui::SliderFloat(label, v, min, max, fmt ? fmt : "%.3f", log ? ImGuiSliderFlags_Logarithmic : 0);
}
extern "C" bool pg_ui_input_int(const char *label, int *v) { return ImGui::InputInt(label, v); }
extern "C" bool pg_ui_combo(const char *label, int *current, const char *const *items, int n)
{
    return ImGui::Combo(label, current, items, n);
}
extern "C" bool pg_ui_input_text(const char *label, char *buf, size_t size)
{
    return ImGui::InputText(label, buf, size, ImGuiInputTextFlags_EnterReturnsTrue);
}
extern "C" void pg_ui_plot_lines(const char *label, const float *values, int n, int offset, const char *overlay,
                                 float min, float max, float w, float h)
{
    ImGui::PlotLines(label, values, n, offset, overlay, min, max, ImVec2(w, h));
}
extern "C" void pg_ui_tooltip(const char *text)
{
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

extern "C" bool pg_ui_table_begin(const char *id, int columns)
{
    return ImGui::BeginTable(id, columns, ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp);
}
extern "C" void pg_ui_table_header(const char *const *names, int n)
{
    for (int i = 0; i < n; i++) ImGui::TableSetupColumn(names[i]);
    ImGui::TableHeadersRow();
}
extern "C" void pg_ui_table_next_row(void) { ImGui::TableNextRow(); }
extern "C" void pg_ui_table_cell(const char *fmt, ...)
{
    ImGui::TableNextColumn();
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}
extern "C" void pg_ui_table_end(void) { ImGui::EndTable(); }

extern "C" void pg_ui_canvas_begin(float w, float h)
{
    g_canvas_origin = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(w, h));
}
extern "C" void pg_ui_canvas_rect(float x0, float y0, float x1, float y1, uint32_t rgba, bool filled)
{
    ImDrawList *dl = ImGui::GetWindowDrawList();
    ImVec2 a(g_canvas_origin.x + x0, g_canvas_origin.y + y0), b(g_canvas_origin.x + x1, g_canvas_origin.y + y1);
    if (filled) dl->AddRectFilled(a, b, col(rgba));
    else dl->AddRect(a, b, col(rgba));
}
extern "C" void pg_ui_canvas_text(float x, float y, uint32_t rgba, const char *text)
{
    ImGui::GetWindowDrawList()->AddText(ImVec2(g_canvas_origin.x + x, g_canvas_origin.y + y), col(rgba), text);
}
extern "C" void pg_ui_canvas_end(void) {}
