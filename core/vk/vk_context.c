/* vk_context.c - instance, device, queue, validation; vk_memory.c has the allocation helpers,
 * vk_names.c the result names and debug names. */
#include "vk_context.h"
#include "pipeline_stats.h"

#include "pg_cache.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static long g_fault_at = -2; /* -2: not read yet, -1: off */
static long g_fault_count;

bool pg_vk_fault_next(const char *call)
{
    const char *match = getenv("PASSGRAPH_FAULT_CALL");
    if (match && *match && call && strstr(call, match)) {
        fprintf(stderr, "passgraph: fault injection: failing %s (PASSGRAPH_FAULT_CALL)\n", call);
        return true;
    }
    if (g_fault_at == -2) {
        const char *e = getenv("PASSGRAPH_FAULT_AT");
        g_fault_at = e && *e ? strtol(e, NULL, 10) : -1;
    }
    if (g_fault_at < 0) return false;
    if (++g_fault_count != g_fault_at) return false;
    fprintf(stderr, "passgraph: fault injection: failing call #%ld: %s\n", g_fault_count, call);
    return true;
}

static VKAPI_ATTR VkBool32 VKAPI_CALL debug_cb(VkDebugUtilsMessageSeverityFlagBitsEXT sev,
                                               VkDebugUtilsMessageTypeFlagsEXT type,
                                               const VkDebugUtilsMessengerCallbackDataEXT *data,
                                               void *user)
{
    (void)type;
    pg_gpu *gpu = user;
    if (sev & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
               VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)) {
        gpu->validation_messages++;
        if (sev & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) gpu->validation_errors++;
        if (data && data->pMessageIdName && strncmp(data->pMessageIdName, "SYNC-HAZARD", 11) == 0)
            gpu->sync_hazards++;
        fprintf(stderr, "passgraph: validation %s: %s\n",
                (sev & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning",
                data && data->pMessage ? data->pMessage : "(no message)");
    }
    return VK_FALSE;
}

static bool has_layer(const char *name)
{
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, NULL);
    VkLayerProperties *p = calloc(n ? n : 1, sizeof *p);
    if (!p) return false;
    vkEnumerateInstanceLayerProperties(&n, p);
    bool found = false;
    for (uint32_t i = 0; i < n; i++)
        if (strcmp(p[i].layerName, name) == 0) found = true;
    free(p);
    return found;
}

static bool has_instance_ext(const char *name)
{
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(NULL, &n, NULL);
    VkExtensionProperties *p = calloc(n ? n : 1, sizeof *p);
    if (!p) return false;
    vkEnumerateInstanceExtensionProperties(NULL, &n, p);
    bool found = false;
    for (uint32_t i = 0; i < n; i++)
        if (strcmp(p[i].extensionName, name) == 0) found = true;
    free(p);
    return found;
}

static const char *device_type_name(VkPhysicalDeviceType t)
{
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

/* Vulkan 1.2 devices are used through the extensions passgraph's 1.3 features came from. */
static const char *const k_ext12_required[] = {
    VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME,
    VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME,
    VK_EXT_EXTENDED_DYNAMIC_STATE_EXTENSION_NAME,
};
#define N_EXT12_REQUIRED (sizeof k_ext12_required / sizeof k_ext12_required[0])

PFN_vkCmdPipelineBarrier2 pg_vk_CmdPipelineBarrier2;
PFN_vkQueueSubmit2 pg_vk_QueueSubmit2;
PFN_vkCmdWriteTimestamp2 pg_vk_CmdWriteTimestamp2;
PFN_vkCmdBeginRendering pg_vk_CmdBeginRendering;
PFN_vkCmdEndRendering pg_vk_CmdEndRendering;
PFN_vkCmdSetCullMode pg_vk_CmdSetCullMode;
PFN_vkCmdSetFrontFace pg_vk_CmdSetFrontFace;

/* PASSGRAPH_HIDE_EXTENSION=NAME[,NAME...]: device extensions treated as absent, so the refusal of
 * a 1.2 device that lacks one can be tested on any device. */
static bool hidden_ext(const char *name)
{
    const char *h = getenv("PASSGRAPH_HIDE_EXTENSION");
    size_t n = strlen(name);
    for (const char *p = h; p && *p;) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && !strncmp(p, name, n)) return true;
        p = e ? e + 1 : NULL;
    }
    return false;
}

static bool has_device_ext(VkPhysicalDevice phys, const char *name)
{
    if (hidden_ext(name)) return false;
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(phys, NULL, &n, NULL);
    VkExtensionProperties *p = calloc(n ? n : 1, sizeof *p);
    if (!p) return false;
    vkEnumerateDeviceExtensionProperties(phys, NULL, &n, p);
    bool found = false;
    for (uint32_t i = 0; i < n; i++)
        if (strcmp(p[i].extensionName, name) == 0) found = true;
    free(p);
    return found;
}

static bool force_vulkan12(void)
{
    const char *e = getenv("PASSGRAPH_VULKAN_1_2");
    return e && *e && strcmp(e, "0") != 0;
}

/* Whether phys is used as 1.2 + extensions; *missing (if given) gets the required extensions it
 * lacks ("" when none, or when it is too old for even that). Returns false for a 1.3 device. */
static bool uses_vulkan12(VkPhysicalDevice phys, const VkPhysicalDeviceProperties *p, char *missing, size_t size)
{
    if (missing && size) missing[0] = 0;
    if (p->apiVersion >= VK_API_VERSION_1_3 && !force_vulkan12()) return false;
    if (p->apiVersion < VK_API_VERSION_1_2) return true;
    for (size_t i = 0; i < N_EXT12_REQUIRED; i++)
        if (!has_device_ext(phys, k_ext12_required[i]) && missing) {
            size_t len = strlen(missing);
            snprintf(missing + len, size - len, "%s%s", len ? ", " : "", k_ext12_required[i]);
        }
    return true;
}

/* -1: unusable (older than 1.2, or 1.2 without the extensions; why goes to why[]). */
static int device_score(VkPhysicalDevice phys, const VkPhysicalDeviceProperties *p, char *why, size_t size)
{
    char missing[256];
    if (why && size) why[0] = 0;
    if (uses_vulkan12(phys, p, missing, sizeof missing)) {
        if (p->apiVersion < VK_API_VERSION_1_2) {
            if (why) snprintf(why, size, "too old: needs 1.3, or 1.2 with %s, %s and %s", k_ext12_required[0],
                              k_ext12_required[1], k_ext12_required[2]);
            return -1;
        }
        if (missing[0]) {
            if (why) snprintf(why, size, "Vulkan 1.2 without %s (needs 1.3, or 1.2 with these)", missing);
            return -1;
        }
    }
    switch (p->deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    default: return 1;
    }
}

static pg_result make_instance(pg_gpu *gpu, const pg_gpu_desc *desc, pg_error *err)
{
    bool validation = desc->validation;
    const char *exts[20];
    uint32_t n_ext = 0;
    for (uint32_t i = 0; i < desc->n_instance_extensions && n_ext < 16; i++) {
        if (!has_instance_ext(desc->instance_extensions[i]))
            return pg_fail(err, PG_ERR_NO_DEVICE, "instance extension %s is not available", desc->instance_extensions[i]);
        exts[n_ext++] = desc->instance_extensions[i];
    }
    if (has_instance_ext(VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
        exts[n_ext++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        gpu->debug_utils = true;
    }
    const char *layers[1];
    uint32_t n_layers = 0;
    if (validation) {
        if (!has_layer("VK_LAYER_KHRONOS_validation"))
            return pg_fail(err, PG_ERR_NO_DEVICE,
                           "validation requested but the loader offers no VK_LAYER_KHRONOS_validation "
                           "(Debian: apt-get install vulkan-validationlayers; or it is disabled, "
                           "e.g. by VK_LOADER_LAYERS_DISABLE)");
        layers[n_layers++] = "VK_LAYER_KHRONOS_validation";
        /* without the messenger nothing would count the layer's messages, and a test that
         * asserts "zero messages" would pass vacuously: refuse instead */
        if (!gpu->debug_utils)
            return pg_fail(err, PG_ERR_NO_DEVICE,
                           "validation requested but VK_EXT_debug_utils is not available: no "
                           "messenger could count the validation layer's messages");
    }
    VkApplicationInfo app = {
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = "passgraph",
        .applicationVersion = VK_MAKE_VERSION(0, 1, 0),
        .pEngineName = "passgraph",
        /* forced 1.2 path: the instance asks for 1.2 too, so the device is used as a 1.2 one and
         * the validation layer checks it as such (1.3 commands, structs, SPIR-V 1.6 flagged) */
        .apiVersion = force_vulkan12() ? VK_API_VERSION_1_2 : VK_API_VERSION_1_3,
    };
    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT,
    };
    VkValidationFeaturesEXT vfeat = {
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
    VkDebugUtilsMessengerCreateInfoEXT dbg = {
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = debug_cb,
        .pUserData = gpu,
    };
    if (validation) {
        vfeat.pNext = gpu->debug_utils ? &dbg : NULL;
    }
    VkInstanceCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? (const void *)&vfeat : NULL,
        .pApplicationInfo = &app,
        .enabledLayerCount = n_layers,
        .ppEnabledLayerNames = layers,
        .enabledExtensionCount = n_ext,
        .ppEnabledExtensionNames = exts,
    };
    VkResult r = vkCreateInstance(&ci, NULL, &gpu->instance);
    if (r != VK_SUCCESS)
        return pg_fail(err, PG_ERR_NO_DEVICE,
                       "vkCreateInstance failed: %s (is a Vulkan 1.3 driver installed? Debian: "
                       "mesa-vulkan-drivers for lavapipe)",
                       pg_vk_result_name(r));
    if (gpu->debug_utils) {
        gpu->set_object_name = (PFN_vkSetDebugUtilsObjectNameEXT)vkGetInstanceProcAddr(
            gpu->instance, "vkSetDebugUtilsObjectNameEXT");
        gpu->cmd_begin_label = (PFN_vkCmdBeginDebugUtilsLabelEXT)vkGetInstanceProcAddr(
            gpu->instance, "vkCmdBeginDebugUtilsLabelEXT");
        gpu->cmd_end_label = (PFN_vkCmdEndDebugUtilsLabelEXT)vkGetInstanceProcAddr(
            gpu->instance, "vkCmdEndDebugUtilsLabelEXT");
        if (validation) {
            PFN_vkCreateDebugUtilsMessengerEXT create =
                (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                    gpu->instance, "vkCreateDebugUtilsMessengerEXT");
            if (!create)
                return pg_fail(err, PG_ERR_NO_DEVICE,
                               "validation requested but vkCreateDebugUtilsMessengerEXT is missing");
            PG_VK_TRY(err, create(gpu->instance, &dbg, NULL, &gpu->messenger));
        }
    }
    return PG_OK;
}

pg_result pg_gpu_list_devices(FILE *f, pg_error *err)
{
    VkInstance inst;
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .apiVersion = VK_API_VERSION_1_3};
    VkInstanceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                               .pApplicationInfo = &app};
    VkResult r = vkCreateInstance(&ci, NULL, &inst);
    if (r != VK_SUCCESS)
        return pg_fail(err, PG_ERR_NO_DEVICE, "vkCreateInstance failed: %s", pg_vk_result_name(r));
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(inst, &n, NULL);
    VkPhysicalDevice devs[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(inst, &n, devs);
    for (uint32_t i = 0; i < n; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devs[i], &p);
        char why[320];
        bool v12 = device_score(devs[i], &p, why, sizeof why) >= 0 && uses_vulkan12(devs[i], &p, NULL, 0);
        fprintf(f, "%u: %s (%s, Vulkan %u.%u.%u)%s%s%s\n", i, p.deviceName,
                device_type_name(p.deviceType), VK_API_VERSION_MAJOR(p.apiVersion),
                VK_API_VERSION_MINOR(p.apiVersion), VK_API_VERSION_PATCH(p.apiVersion),
                why[0] ? " [" : "", why[0] ? why : (v12 ? " [used as 1.2 + extensions]" : ""),
                why[0] ? "]" : "");
    }
    vkDestroyInstance(inst, NULL);
    return PG_OK;
}

/* the physical device: the best-scoring one that desc's index and name allow */
static pg_result pick_device(pg_gpu *gpu, const pg_gpu_desc *desc, pg_error *err)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(gpu->instance, &n, NULL);
    if (n == 0) return pg_fail(err, PG_ERR_NO_DEVICE, "no Vulkan device found");
    VkPhysicalDevice devs[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(gpu->instance, &n, devs);
    int best = -1, best_score = -1;
    char why[320] = "", why_i[320];
    for (uint32_t i = 0; i < n; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devs[i], &p);
        if (desc->device_index >= 0 && (int)i != desc->device_index) continue;
        if (desc->device_match && desc->device_match[0] && !strstr(p.deviceName, desc->device_match))
            continue;
        int s = device_score(devs[i], &p, why_i, sizeof why_i);
        if (s < 0 && !why[0]) snprintf(why, sizeof why, "%s: %s", p.deviceName, why_i);
        if (s > best_score) {
            best = (int)i;
            best_score = s;
        }
    }
    if (best < 0 || best_score < 0) {
        char asked[PG_NAME_MAX + 48]; /* only what was asked: an index, a name, or neither */
        if (desc->device_index >= 0)
            snprintf(asked, sizeof asked, " device index %d of %u", desc->device_index, n);
        else if (desc->device_match && desc->device_match[0])
            snprintf(asked, sizeof asked, " a name containing '%s' among %u", desc->device_match, n);
        else
            snprintf(asked, sizeof asked, " any of %u", n);
        return pg_fail(err, PG_ERR_NO_DEVICE,
                       "no usable Vulkan device matches (%s)%s%s; run 'passgraph devices' to list them", asked + 1,
                       why[0] ? ": " : "", why);
    }
    gpu->phys = devs[best];
    vkGetPhysicalDeviceProperties(gpu->phys, &gpu->props);
    vkGetPhysicalDeviceMemoryProperties(gpu->phys, &gpu->mem_props);
    gpu->timestamp_period_ns = gpu->props.limits.timestampPeriod;
    return PG_OK;
}

/* the queue families chosen: the graphics+compute one (fam) and the async compute queue
 * (cfam, -1 for none; cindex its index in its family) */
typedef struct queue_choice {
    VkQueueFamilyProperties qf[16];
    uint32_t nq;
    int fam, cfam;
    uint32_t cindex;
} queue_choice;

static pg_result pick_queues(pg_gpu *gpu, const pg_gpu_desc *desc, queue_choice *q, pg_error *err)
{
    q->nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu->phys, &q->nq, NULL);
    if (q->nq > 16) q->nq = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu->phys, &q->nq, q->qf);
    const VkQueueFamilyProperties *qf = q->qf;
    int fam = -1;
    for (uint32_t i = 0; i < q->nq; i++)
        if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
            (!desc->present_ok || desc->present_ok(gpu->instance, gpu->phys, i, desc->present_user))) {
            fam = (int)i;
            break;
        }
    if (fam < 0)
        return pg_fail(err, PG_ERR_NO_DEVICE, "%s: no graphics+compute queue%s", gpu->props.deviceName,
                       desc->present_ok ? " that can present to the window" : "");
    q->fam = fam;
    gpu->queue_family = (uint32_t)fam;
    gpu->timestamp_valid_bits = qf[fam].timestampValidBits;
    /* async compute: a compute family without graphics, else a second queue of the graphics
     * family, else none (the compiler then plans for one queue) */
    q->cfam = -1;
    q->cindex = 0;
    if (desc->emulate_compute_queue) {
        q->cfam = fam;
    } else if (!desc->no_compute_queue) {
        for (uint32_t i = 0; i < q->nq && q->cfam < 0; i++)
            if ((qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && !(qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
                qf[i].queueCount > 0)
                q->cfam = (int)i;
        if (q->cfam < 0 && qf[fam].queueCount > 1) {
            q->cfam = fam;
            q->cindex = 1;
        }
    }
    if (q->cfam < 0)
        snprintf(gpu->single_queue_why, sizeof gpu->single_queue_why, "%s",
                 desc->no_compute_queue ? "--async-compute off"
                                        : "the device has no second compute-capable queue");
    return PG_OK;
}

/* What the device supports. On a 1.2 device the 1.3 feature and property structs are replaced by
 * the extensions' own (same members); f13 is filled from those so one path follows. The pNext
 * chains the query used are gone (NULL). */
typedef struct dev_features {
    bool has_sgsc, has_m4; /* VK_EXT_subgroup_size_control, VK_KHR_maintenance4 (always on 1.3) */
    bool pipeline_stats;   /* PASSGRAPH_PIPELINE_STATS and VK_KHR_pipeline_executable_properties */
    VkPhysicalDeviceVulkan13Features f13;
    VkPhysicalDeviceVulkan12Features f12;
    VkPhysicalDeviceFeatures2 f2;
} dev_features;

static pg_result query_features(pg_gpu *gpu, dev_features *df, pg_error *err)
{
    gpu->vulkan12 = uses_vulkan12(gpu->phys, &gpu->props, NULL, 0);
    bool has_sgsc = df->has_sgsc =
        !gpu->vulkan12 || has_device_ext(gpu->phys, VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME);
    bool has_m4 = df->has_m4 = !gpu->vulkan12 || has_device_ext(gpu->phys, VK_KHR_MAINTENANCE_4_EXTENSION_NAME);
    df->pipeline_stats = pg_pipeline_stats_wanted();
    if (df->pipeline_stats && !has_device_ext(gpu->phys, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
        df->pipeline_stats = false; /* pipelineExecutableInfo is required with the extension */
        fprintf(stderr, "passgraph: pipeline-stats: %s lacks VK_KHR_pipeline_executable_properties: no statistics\n",
                gpu->props.deviceName);
    }
    VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceSynchronization2Features fs2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
    VkPhysicalDeviceDynamicRenderingFeatures fdr = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES,
                                                    .pNext = &fs2};
    VkPhysicalDeviceExtendedDynamicStateFeaturesEXT feds = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_FEATURES_EXT, .pNext = &fdr};
    VkPhysicalDeviceSubgroupSizeControlFeatures fsg = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES};
    VkPhysicalDeviceMaintenance4Features fm4 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
    void *q12 = &feds;
    if (has_sgsc) { fsg.pNext = q12; q12 = &fsg; }
    if (has_m4) { fm4.pNext = q12; q12 = &fm4; }
    VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                            .pNext = gpu->vulkan12 ? q12 : (void *)&f13};
    VkPhysicalDeviceFeatures2 f2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f12};
    vkGetPhysicalDeviceFeatures2(gpu->phys, &f2);
    bool eds = true;
    if (gpu->vulkan12) {
        f13.synchronization2 = fs2.synchronization2;
        f13.dynamicRendering = fdr.dynamicRendering;
        f13.subgroupSizeControl = fsg.subgroupSizeControl;
        f13.computeFullSubgroups = fsg.computeFullSubgroups;
        f13.maintenance4 = fm4.maintenance4;
        eds = feds.extendedDynamicState;
    }
    df->f13 = f13;
    df->f12 = f12;
    df->f2 = f2;
    df->f13.pNext = df->f12.pNext = df->f2.pNext = NULL;
    if (!f13.synchronization2 || !f13.dynamicRendering || !eds)
        return pg_fail(err, PG_ERR_NO_DEVICE, "%s lacks the synchronization2, dynamicRendering or%s feature",
                       gpu->props.deviceName, gpu->vulkan12 ? " extendedDynamicState" : "");
    return PG_OK;
}

/* the subgroup size, whether compute dispatches can require it exactly, the storage range */
static void query_subgroups(pg_gpu *gpu, const dev_features *df)
{
    const VkPhysicalDeviceVulkan13Features *f13 = &df->f13;
    VkPhysicalDeviceVulkan13Properties p13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
    VkPhysicalDeviceSubgroupSizeControlProperties psg = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES};
    VkPhysicalDeviceSubgroupProperties sp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES,
                                             .pNext = gpu->vulkan12 ? (df->has_sgsc ? (void *)&psg : NULL) : (void *)&p13};
    VkPhysicalDeviceMaintenance3Properties m3 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES,
                                                 .pNext = &sp};
    VkPhysicalDeviceProperties2 pp = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &m3};
    vkGetPhysicalDeviceProperties2(gpu->phys, &pp);
    if (gpu->vulkan12) {
        p13.minSubgroupSize = psg.minSubgroupSize;
        p13.maxSubgroupSize = psg.maxSubgroupSize;
        p13.requiredSubgroupSizeStages = psg.requiredSubgroupSizeStages;
    }
    gpu->subgroup_size = sp.subgroupSize;
    gpu->exact_subgroups = f13->subgroupSizeControl && f13->computeFullSubgroups &&
                           (p13.requiredSubgroupSizeStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                           sp.subgroupSize >= p13.minSubgroupSize && sp.subgroupSize <= p13.maxSubgroupSize &&
                           sp.subgroupSize >= 4 && sp.subgroupSize <= 128 &&
                           sp.subgroupSize <= gpu->props.limits.maxComputeWorkGroupSize[0];
    gpu->max_storage_buffer_range = gpu->props.limits.maxStorageBufferRange;
    gpu->max_buffer_size = gpu->vulkan12 ? UINT64_MAX : p13.maxBufferSize;
    gpu->max_allocation_size = m3.maxMemoryAllocationSize;
    gpu->max_stage_storage_buffers = gpu->props.limits.maxPerStageDescriptorStorageBuffers;
}

/* The features and extensions the device is created with (a pNext chain inside the struct: it
 * is filled in place and must not move before vkCreateDevice). */
typedef struct dev_enable {
    VkPhysicalDeviceVulkan13Features e13;
    VkPhysicalDeviceSynchronization2Features es2;
    VkPhysicalDeviceDynamicRenderingFeatures edr;
    VkPhysicalDeviceExtendedDynamicStateFeaturesEXT eeds;
    VkPhysicalDeviceSubgroupSizeControlFeatures esg;
    VkPhysicalDeviceMaintenance4Features em4;
    VkPhysicalDeviceVulkan12Features e12;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR epep;
    VkPhysicalDeviceFeatures2 e2;
    const char *exts[8];
    uint32_t n_ext;
} dev_enable;

static void fill_enable(const pg_gpu *gpu, const pg_gpu_desc *desc, const dev_features *df, dev_enable *e)
{
    const VkPhysicalDeviceVulkan13Features *f13 = &df->f13;
    const VkPhysicalDeviceVulkan12Features *f12 = &df->f12;
    const VkPhysicalDeviceFeatures2 *f2 = &df->f2;
    e->e13 = (VkPhysicalDeviceVulkan13Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
        .synchronization2 = VK_TRUE,
        .dynamicRendering = VK_TRUE,
        .maintenance4 = f13->maintenance4,
        .subgroupSizeControl = f13->subgroupSizeControl,
        .computeFullSubgroups = f13->computeFullSubgroups,
    };
    e->es2 = (VkPhysicalDeviceSynchronization2Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES, .synchronization2 = VK_TRUE};
    e->edr = (VkPhysicalDeviceDynamicRenderingFeatures){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES, .pNext = &e->es2,
        .dynamicRendering = VK_TRUE};
    e->eeds = (VkPhysicalDeviceExtendedDynamicStateFeaturesEXT){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_FEATURES_EXT, .pNext = &e->edr,
        .extendedDynamicState = VK_TRUE};
    e->esg = (VkPhysicalDeviceSubgroupSizeControlFeatures){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES,
        .subgroupSizeControl = f13->subgroupSizeControl,
        .computeFullSubgroups = f13->computeFullSubgroups};
    e->em4 = (VkPhysicalDeviceMaintenance4Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES, .maintenance4 = f13->maintenance4};
    e->n_ext = 0;
    if (desc->swapchain) e->exts[e->n_ext++] = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    void *e12_next = &e->e13;
    if (gpu->vulkan12) {
        for (size_t i = 0; i < N_EXT12_REQUIRED; i++) e->exts[e->n_ext++] = k_ext12_required[i];
        e12_next = &e->eeds;
        if (df->has_sgsc && (f13->subgroupSizeControl || f13->computeFullSubgroups)) {
            e->exts[e->n_ext++] = VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME;
            e->esg.pNext = e12_next;
            e12_next = &e->esg;
        }
        if (df->has_m4 && f13->maintenance4) {
            e->exts[e->n_ext++] = VK_KHR_MAINTENANCE_4_EXTENSION_NAME;
            e->em4.pNext = e12_next;
            e12_next = &e->em4;
        }
    }
    e->e12 = (VkPhysicalDeviceVulkan12Features){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = e12_next,
        .hostQueryReset = f12->hostQueryReset,
        .timelineSemaphore = f12->timelineSemaphore,
        .scalarBlockLayout = f12->scalarBlockLayout,
        /* 64-bit atomicMin on storage buffers: the visibility pass's compute rasterizer */
        .shaderBufferInt64Atomics = f12->shaderBufferInt64Atomics,
        .shaderSampledImageArrayNonUniformIndexing = f12->shaderSampledImageArrayNonUniformIndexing,
        .runtimeDescriptorArray = f12->runtimeDescriptorArray,
    };
    e->e2 = (VkPhysicalDeviceFeatures2){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &e->e12,
        .features = {
            .samplerAnisotropy = f2->features.samplerAnisotropy,
            .fragmentStoresAndAtomics = f2->features.fragmentStoresAndAtomics,
            .shaderInt64 = f2->features.shaderInt64,
            .depthClamp = f2->features.depthClamp,
            /* gl_PrimitiveID in a fragment shader (the visibility pass's triangle id) */
            .geometryShader = f2->features.geometryShader,
        },
    };
    if (df->pipeline_stats) { /* pipeline_stats.h: the driver's statistics of every pipeline */
        e->exts[e->n_ext++] = VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
        e->epep = (VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR){
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
            .pNext = e->e2.pNext,
            .pipelineExecutableInfo = VK_TRUE};
        e->e2.pNext = &e->epep;
    }
}

/* the logical device with its queues (the async compute one only with timeline semaphores) */
static pg_result create_device(pg_gpu *gpu, const pg_gpu_desc *desc, const dev_features *df,
                               queue_choice *q, pg_error *err)
{
    dev_enable e;
    fill_enable(gpu, desc, df, &e);
    gpu->primitive_id_in_fragment = df->f2.features.geometryShader;
    gpu->nonuniform_sampled_arrays = df->f12.shaderSampledImageArrayNonUniformIndexing;
    gpu->int64_atomics = df->f2.features.shaderInt64 && df->f12.shaderBufferInt64Atomics;
    gpu->shader_int64 = df->f2.features.shaderInt64;
    gpu->timeline_semaphores = df->f12.timelineSemaphore;
    if (q->cfam >= 0 && !df->f12.timelineSemaphore) {
        q->cfam = -1;
        snprintf(gpu->single_queue_why, sizeof gpu->single_queue_why, "the device lacks timelineSemaphore");
    }
    const int fam = q->fam, cfam = q->cfam;
    float prio[2] = {1.0f, 1.0f};
    VkDeviceQueueCreateInfo qci[2] = {{
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = gpu->queue_family,
        .queueCount = cfam == fam && q->cindex == 1 ? 2 : 1,
        .pQueuePriorities = prio,
    }, {
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = (uint32_t)(cfam >= 0 ? cfam : 0),
        .queueCount = 1,
        .pQueuePriorities = prio,
    }};
    VkDeviceCreateInfo dci = {
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &e.e2,
        .queueCreateInfoCount = cfam >= 0 && cfam != fam ? 2 : 1,
        .pQueueCreateInfos = qci,
        .enabledExtensionCount = e.n_ext,
        .ppEnabledExtensionNames = e.exts,
    };
    VkResult r = pg_vk_fault_next("vkCreateDevice") ? VK_ERROR_DEVICE_LOST
                                                    : vkCreateDevice(gpu->phys, &dci, NULL, &gpu->device);
    if (r != VK_SUCCESS) return pg_fail(err, PG_ERR_VULKAN, "vkCreateDevice failed: %s", pg_vk_result_name(r));
    vkGetDeviceQueue(gpu->device, gpu->queue_family, 0, &gpu->queue);
    if (df->pipeline_stats) {
        gpu->exec_props = (PFN_vkGetPipelineExecutablePropertiesKHR)vkGetDeviceProcAddr(
            gpu->device, "vkGetPipelineExecutablePropertiesKHR");
        gpu->exec_stats = (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(
            gpu->device, "vkGetPipelineExecutableStatisticsKHR");
        if (!gpu->exec_props) gpu->exec_stats = NULL;
    }
    if (cfam >= 0) {
        gpu->compute_family = (uint32_t)cfam;
        gpu->compute_emulated = desc->emulate_compute_queue;
        gpu->compute_timestamp_valid_bits = q->qf[cfam].timestampValidBits;
        if (gpu->compute_emulated) gpu->compute_queue = gpu->queue;
        else vkGetDeviceQueue(gpu->device, (uint32_t)cfam, q->cindex, &gpu->compute_queue);
    }
    return PG_OK;
}

/* the 1.3 commands under their core or their extension names (see vk_context.h) */
static pg_result load_commands(pg_gpu *gpu, pg_error *err)
{
    const char *sfx2 = gpu->vulkan12 ? "KHR" : "", *sfx_eds = gpu->vulkan12 ? "EXT" : "";
    struct { PFN_vkVoidFunction *fn; const char *name, *suffix; } cmds[] = {
        {(PFN_vkVoidFunction *)&pg_vk_CmdPipelineBarrier2, "vkCmdPipelineBarrier2", sfx2},
        {(PFN_vkVoidFunction *)&pg_vk_QueueSubmit2, "vkQueueSubmit2", sfx2},
        {(PFN_vkVoidFunction *)&pg_vk_CmdWriteTimestamp2, "vkCmdWriteTimestamp2", sfx2},
        {(PFN_vkVoidFunction *)&pg_vk_CmdBeginRendering, "vkCmdBeginRendering", sfx2},
        {(PFN_vkVoidFunction *)&pg_vk_CmdEndRendering, "vkCmdEndRendering", sfx2},
        {(PFN_vkVoidFunction *)&pg_vk_CmdSetCullMode, "vkCmdSetCullMode", sfx_eds},
        {(PFN_vkVoidFunction *)&pg_vk_CmdSetFrontFace, "vkCmdSetFrontFace", sfx_eds},
    };
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        char name[64];
        snprintf(name, sizeof name, "%s%s", cmds[i].name, cmds[i].suffix);
        PFN_vkVoidFunction f = vkGetInstanceProcAddr(gpu->instance, name);
        if (!f) return pg_fail(err, PG_ERR_NO_DEVICE, "%s: the loader has no %s", gpu->props.deviceName, name);
        *cmds[i].fn = f;
    }
    return PG_OK;
}

/* the command pool of the graphics family, and one of the compute family when it differs */
static pg_result create_command_pools(pg_gpu *gpu, pg_error *err)
{
    VkCommandPoolCreateInfo pci = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = gpu->queue_family,
    };
    VkResult r = vkCreateCommandPool(gpu->device, &pci, NULL, &gpu->cmd_pool);
    if (r != VK_SUCCESS) return pg_fail(err, PG_ERR_VULKAN, "vkCreateCommandPool failed: %s", pg_vk_result_name(r));
    gpu->compute_cmd_pool = gpu->cmd_pool;
    if (gpu->compute_queue && gpu->compute_family != gpu->queue_family) {
        pci.queueFamilyIndex = gpu->compute_family;
        r = vkCreateCommandPool(gpu->device, &pci, NULL, &gpu->compute_cmd_pool);
        if (r != VK_SUCCESS) {
            gpu->compute_cmd_pool = VK_NULL_HANDLE;
            return pg_fail(err, PG_ERR_VULKAN, "vkCreateCommandPool(compute) failed: %s", pg_vk_result_name(r));
        }
    }
    return PG_OK;
}

/* the device line (and the compute queue line) on stderr */
static void print_device(const pg_gpu *gpu, const pg_gpu_desc *desc)
{
    fprintf(stderr, "passgraph: device %s (%s, Vulkan %u.%u%s)%s\n", gpu->props.deviceName,
            device_type_name(gpu->props.deviceType), VK_API_VERSION_MAJOR(gpu->props.apiVersion),
            VK_API_VERSION_MINOR(gpu->props.apiVersion), gpu->vulkan12 ? ", used as 1.2 + extensions" : "",
            desc->validation ? ", validation + sync validation on" : "");
    if (gpu->compute_queue)
        fprintf(stderr, "passgraph: compute queue: %s (family %u%s)\n",
                gpu->compute_emulated ? "emulated on the graphics queue" : "separate", gpu->compute_family,
                gpu->compute_family == gpu->queue_family ? ", the graphics family" : "");
}

pg_result pg_gpu_create(const pg_gpu_desc *desc, pg_gpu **out, pg_error *err)
{
    *out = NULL;
    pg_gpu *gpu = calloc(1, sizeof *gpu);
    if (!gpu) return pg_fail(err, PG_ERR_OOM, "out of memory");
    gpu->validation = desc->validation;
    queue_choice q;
    dev_features df;
    pg_result res;
    if ((res = make_instance(gpu, desc, err)) || (res = pick_device(gpu, desc, err)) ||
        (res = pick_queues(gpu, desc, &q, err)) || (res = query_features(gpu, &df, err)))
        goto fail;
    query_subgroups(gpu, &df);
    if ((res = create_device(gpu, desc, &df, &q, err)) || (res = load_commands(gpu, err)) ||
        (res = create_command_pools(gpu, err)))
        goto fail;
    pg_pipeline_cache_open(gpu);
    if (!desc->quiet) print_device(gpu, desc);
    *out = gpu;
    return PG_OK;
fail:
    pg_gpu_destroy(gpu);
    return res;
}

void pg_gpu_destroy(pg_gpu *gpu)
{
    if (!gpu) return;
    if (gpu->device) {
        vkDeviceWaitIdle(gpu->device);
        pg_pipeline_cache_close(gpu);
        const char *cs = getenv("PASSGRAPH_CACHE_STATS");
        if (cs && cs[0] && strcmp(cs, "0")) {
            pg_shader_cache_stats st;
            pg_shader_cache_stats_get(&st);
            fprintf(stderr,
                    "passgraph: cache: %u shader variants compiled (%.1f ms), %u from memory, %u from disk, "
                    "%u written, %u rejected (lookups %.1f ms); pipeline cache %zu bytes loaded%s\n",
                    st.compiled, st.compile_ms, st.memory_hits, st.disk_hits, st.disk_writes, st.rejected, st.lookup_ms,
                    gpu->pipeline_cache_loaded, pg_cache_enabled() ? "" : " (caches off)");
        }
        if (gpu->compute_cmd_pool && gpu->compute_cmd_pool != gpu->cmd_pool)
            vkDestroyCommandPool(gpu->device, gpu->compute_cmd_pool, NULL);
        if (gpu->cmd_pool) vkDestroyCommandPool(gpu->device, gpu->cmd_pool, NULL);
        vkDestroyDevice(gpu->device, NULL);
    }
    if (gpu->messenger) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                gpu->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy) destroy(gpu->instance, gpu->messenger, NULL);
    }
    if (gpu->instance) vkDestroyInstance(gpu->instance, NULL);
    free(gpu);
}
