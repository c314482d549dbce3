/* rdoc.c - see rdoc.h. */
#include "rdoc.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#if defined(__has_include)
#if __has_include(<renderdoc_app.h>)
#include <renderdoc_app.h>
#define PG_HAVE_RENDERDOC_APP 1
#endif
#endif

#ifdef PG_HAVE_RENDERDOC_APP
struct pg_rdoc {
    RENDERDOC_API_1_4_1 *api;
};

static const char *k_lib = "librenderdoc.so";

static bool library_installed(void)
{
    char dirs[4096] = "";
    const char *ld = getenv("LD_LIBRARY_PATH");
    snprintf(dirs, sizeof dirs, "%s%s/usr/lib:/usr/lib/x86_64-linux-gnu:/usr/lib/aarch64-linux-gnu:/usr/local/lib:"
             "/usr/lib64", ld ? ld : "", ld && *ld ? ":" : "");
    for (char *save = NULL, *d = strtok_r(dirs, ":", &save); d; d = strtok_r(NULL, ":", &save)) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", d, k_lib);
        if (access(path, R_OK) == 0) return true;
    }
    return false;
}

pg_rdoc *pg_rdoc_open(char *why, size_t why_size)
{
    void *lib = dlopen(k_lib, RTLD_NOW | RTLD_NOLOAD);
    if (!lib) {
        /* not loaded. Whether it is installed is told by looking for the file, not by loading it
         * (RenderDoc starts its capture machinery when loaded and cannot be unloaded). */
        if (library_installed())
            snprintf(why, why_size,
                     "this process was not started under RenderDoc (%s is installed but not loaded): run "
                     "'renderdoccmd capture -w passgraph ...' (or launch passgraph from qrenderdoc)", k_lib);
        else
            snprintf(why, why_size,
                     "%s not found: RenderDoc is not installed (Debian: apt-get install renderdoccmd "
                     "librenderdoc), and passgraph must be started under it ('renderdoccmd capture -w "
                     "passgraph ...')", k_lib);
        return NULL;
    }
    pRENDERDOC_GetAPI get = (pRENDERDOC_GetAPI)dlsym(lib, "RENDERDOC_GetAPI");
    RENDERDOC_API_1_4_1 *api = NULL;
    if (!get || !get(eRENDERDOC_API_Version_1_4_1, (void **)&api) || !api) {
        snprintf(why, why_size, "%s has no in-application API 1.4.1 (RenderDoc older than 1.5?)", k_lib);
        return NULL;
    }
    pg_rdoc *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    r->api = api;
    return r;
}

void pg_rdoc_set_path_template(pg_rdoc *r, const char *tmpl) { r->api->SetCaptureFilePathTemplate(tmpl); }

void pg_rdoc_begin(pg_rdoc *r) { r->api->StartFrameCapture(NULL, NULL); }

unsigned pg_rdoc_captures(pg_rdoc *r, char *path, size_t path_size)
{
    uint32_t n = r->api->GetNumCaptures();
    if (path && path_size) {
        path[0] = 0;
        uint32_t len = 0;
        if (n && r->api->GetCapture(n - 1, NULL, &len, NULL) && len <= path_size)
            r->api->GetCapture(n - 1, path, &len, NULL);
    }
    return n;
}

bool pg_rdoc_end(pg_rdoc *r, const char *out_path, char *why, size_t why_size)
{
    uint32_t before = r->api->GetNumCaptures();
    if (!r->api->EndFrameCapture(NULL, NULL) || r->api->GetNumCaptures() == before) {
        snprintf(why, why_size, "RenderDoc did not write a capture (EndFrameCapture failed)");
        return false;
    }
    char path[4096];
    pg_rdoc_captures(r, path, sizeof path);
    if (!path[0]) {
        snprintf(why, why_size, "RenderDoc wrote a capture but did not say where");
        return false;
    }
    if (out_path && strcmp(out_path, path) != 0 && rename(path, out_path) != 0) {
        snprintf(why, why_size, "moving the capture %s to %s: %s", path, out_path, strerror(errno));
        return false;
    }
    return true;
}

void pg_rdoc_trigger(pg_rdoc *r) { r->api->TriggerCapture(); }

#else /* built without renderdoc_app.h */
struct pg_rdoc {
    int unused;
};
pg_rdoc *pg_rdoc_open(char *why, size_t why_size)
{
    snprintf(why, why_size, "passgraph was built without renderdoc_app.h (Debian: librenderdoc-dev; "
                            "tools/setup.sh installs it)");
    return NULL;
}
void pg_rdoc_set_path_template(pg_rdoc *r, const char *tmpl) { (void)r, (void)tmpl; }
void pg_rdoc_begin(pg_rdoc *r) { (void)r; }
bool pg_rdoc_end(pg_rdoc *r, const char *out_path, char *why, size_t why_size)
{
    (void)r, (void)out_path;
    snprintf(why, why_size, "no RenderDoc");
    return false;
}
void pg_rdoc_trigger(pg_rdoc *r) { (void)r; }
unsigned pg_rdoc_captures(pg_rdoc *r, char *path, size_t path_size)
{
    (void)r;
    if (path && path_size) path[0] = 0;
    return 0;
}
#endif
