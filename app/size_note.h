/* size_note.h - a word before a big frame: the plan's memory estimate, printed as one line when
 * it passes a threshold, and --size checked against the device's maxImageDimension2D.
 *
 * The estimate is the plan's own (core/graph: transient blocks after aliasing plus every
 * resource with its own memory: persistent, imported, outputs, growable buffers). The threshold
 * is 1 GiB; $PASSGRAPH_SIZE_NOTE_MIB sets another (in MiB; 0 prints it always). */
#ifndef PG_SIZE_NOTE_H
#define PG_SIZE_NOTE_H

#include "app.h"
#include "graph.h"

#include <stdio.h>

uint64_t pg_plan_memory_estimate(const pg_graph_plan *plan);
/* Prints "CMD: WxH needs about 9.8 GiB of device memory (plan estimate); this can take minutes
 * on a CPU device" to f when the estimate passes the threshold. */
void pg_size_note_print(FILE *f, const char *cmd, uint32_t width, uint32_t height,
                        const pg_graph_plan *plan);
/* render / bench: refuses a size over the device's maxImageDimension2D; loads and compiles the
 * app's pipeline on the CPU (no device memory yet) and prints the note above. Errors of the
 * load or compile are left to the session, which reports them as before. */
pg_result pg_size_note_check(const pg_app *app, const char *cmd, FILE *f, pg_error *err);

#endif
