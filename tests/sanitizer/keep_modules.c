/* keep_modules.c - linked into the test executables and passgraph in sanitizer builds only
 * (-DPG_SANITIZE=ON, tests/CMakeLists.txt).
 *
 * The Vulkan loader dlopen()s the driver (Mesa lavapipe, which pulls in libLLVM) and the
 * validation layer, and dlclose()s them in vkDestroyInstance. LeakSanitizer runs at exit, after
 * that: allocations made inside an unloaded module then show up as "(<unknown module>)" frames,
 * or with another library's name when the address range was reused, so no suppression can name
 * them and a leak of ours could not be told from one of the driver's. Defining dlclose() in the
 * executable interposes the libc one for every library (the loader included): the handle is
 * kept, the module stays mapped, and LSan prints and matches real frames (lsan.supp).
 * Nothing else changes: dlopen() of an already loaded module just reuses it. */
#include <stddef.h>

__attribute__((visibility("default"), used)) int dlclose(void *handle)
{
    (void)handle;
    return 0;
}
