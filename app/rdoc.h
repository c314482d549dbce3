/* rdoc.h - frame capture through RenderDoc's in-application API (renderdoc_app.h, Debian
 * librenderdoc-dev). librenderdoc.so is never linked: it is looked up at run time with dlopen,
 * and only as already loaded (RTLD_NOLOAD), because RenderDoc can capture Vulkan only when it
 * was injected at start (renderdoccmd capture, or qrenderdoc's Launch Application). Every
 * failure is a message for the user, never an exit. */
#ifndef PG_RDOC_H
#define PG_RDOC_H

#include <stdbool.h>
#include <stddef.h>

typedef struct pg_rdoc pg_rdoc;

/* Finds RenderDoc in this process. On failure returns NULL and writes why (library not
 * installed, process not started under RenderDoc, API too old, built without the header). */
pg_rdoc *pg_rdoc_open(char *why, size_t why_size);
/* Captures go to PATH_frameN.rdc style names (RenderDoc's template). */
void pg_rdoc_set_path_template(pg_rdoc *r, const char *tmpl);
/* Frames recorded between begin and end (all queues, all devices) form one capture. */
void pg_rdoc_begin(pg_rdoc *r);
/* Ends the capture and moves it to out_path (when not NULL). false + why on failure. */
bool pg_rdoc_end(pg_rdoc *r, const char *out_path, char *why, size_t why_size);
/* Captures the next presented frame (the viewer). */
void pg_rdoc_trigger(pg_rdoc *r);
/* Number of captures written so far and the path of the last one (path may be NULL). */
unsigned pg_rdoc_captures(pg_rdoc *r, char *path, size_t path_size);

#endif
