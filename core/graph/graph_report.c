/* graph_report.c - pg_graph_plan_print(): a readable text report of a compiled graph (the short
 * names of values it prints are graph_names.c's).
 *
 * The report is for people: passes in execution order with what they touch and the barriers
 * before them, what was culled and why, the resources with their lifetimes and memory blocks, and
 * totals (including what aliasing saved). It reads the plan only. */
#include "graph.h"
#include "graph_report.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <vulkan/vulkan_core.h>

static const char *pass_name_at(const pg_graph_plan *plan, int pos)
{
    if (pos < 0) return "-";
    if ((uint32_t)pos >= plan->n_order) return "(end)";
    return plan->passes[plan->order[pos]].name;
}

uint32_t pg_graph_plan_count_barriers(const pg_graph_plan *plan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < plan->n_passes; i++) n += plan->passes[i].n_barriers;
    return n;
}

uint32_t pg_graph_plan_count_culled(const pg_graph_plan *plan)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < plan->n_passes; i++) n += plan->passes[i].culled;
    return n;
}

double pg_graph_plan_saving_percent(const pg_graph_plan *plan)
{
    if (!plan->transient_bytes_unaliased || plan->transient_bytes_aliased > plan->transient_bytes_unaliased)
        return 0.0;
    return 100.0 * (double)(plan->transient_bytes_unaliased - plan->transient_bytes_aliased) /
           (double)plan->transient_bytes_unaliased;
}

static void print_barrier(FILE *f, const pg_graph_plan *plan, const pg_barrier *b)
{
    char ss[160], sa[160], ds[160], da[160];
    pg_stage_names(b->src_stages, ss, sizeof ss);
    pg_access_mask_names(b->src_access, sa, sizeof sa);
    pg_stage_names(b->dst_stages, ds, sizeof ds);
    pg_access_mask_names(b->dst_access, da, sizeof da);
    const char *name = b->resource >= 0 && (uint32_t)b->resource < plan->n_resources
                           ? plan->resources[b->resource].name
                           : "?";
    fprintf(f, "      barrier %-12s %s/%s -> %s/%s", name, ss, sa, ds, da);
    if (b->is_image)
        fprintf(f, ", %s -> %s", pg_layout_name(b->old_layout), pg_layout_name(b->new_layout));
    fprintf(f, "  (%s", b->why);
    if (b->alias_prev >= 0 && (uint32_t)b->alias_prev < plan->n_resources)
        fprintf(f, " after '%s'", plan->resources[b->alias_prev].name);
    fprintf(f, ")\n");
}

/* The memory timeline as text: one row per transient resource, grouped by memory block, one
 * 3-character column per executed pass plus 'E' (read back after the last pass):
 *   "[==" first pass, "===" live, "==]" last pass, "[=]" one pass only, " . " not live. */
static void print_timeline(FILE *f, const pg_graph_plan *plan)
{
    const uint32_t n_cols = plan->n_order + 1;
    fprintf(f, "\nmemory timeline (transient resources by memory block; columns are the executed "
               "passes, E = read back after the last pass):\n");
    if (!plan->n_blocks) {
        fprintf(f, "  no transient resources\n");
        return;
    }
    fprintf(f, "  %-26s", "");
    for (uint32_t k = 0; k < n_cols; k++) {
        if (k < plan->n_order) fprintf(f, "%3u", k % 1000);
        else fprintf(f, "  E");
    }
    fprintf(f, "\n");
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        char bytes[32];
        pg_fmt_bytes(bl->size_bytes, bytes, sizeof bytes);
        fprintf(f, "  #%u %s %s%s\n", b, pg_res_kind_name(bl->kind), bytes,
                bl->n_members > 1 ? " (shared)" : "");
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const pg_plan_resource *pr = &plan->resources[bl->members[m]];
            fprintf(f, "    %-24.24s", pr->name);
            for (uint32_t k = 0; k < n_cols; k++) {
                const int kk = (int)k;
                const char *cell = " . ";
                if (kk >= pr->first_pass && kk <= pr->last_pass && pr->first_pass >= 0) {
                    if (pr->first_pass == pr->last_pass) cell = "[=]";
                    else if (kk == pr->first_pass) cell = "[==";
                    else if (kk == pr->last_pass) cell = "==]";
                    else cell = "===";
                }
                fputs(cell, f);
            }
            fprintf(f, "\n");
        }
    }
    fprintf(f, "  passes:");
    for (uint32_t k = 0; k < plan->n_order; k++)
        fprintf(f, "%s %u %s%s", k ? "," : "", k, plan->passes[plan->order[k]].name,
                !plan->async ? "" : plan->passes[plan->order[k]].queue == PG_QUEUE_COMPUTE ? " [compute]" : " [graphics]");
    fprintf(f, "\n");
}

/* The submission batches of a two-queue plan: queue, passes, waits, ownership transfers. */
static void print_queues(FILE *f, const pg_graph_plan *plan)
{
    fprintf(f, "\nqueues: graphics + compute (%s); %u submission batches:\n",
            plan->qfot ? "separate families: ownership transfers" : "one family: semaphores, no ownership transfer",
            plan->n_batches);
    char st[256], ac[256];
    for (uint32_t b = 0; b < plan->n_batches; b++) {
        const pg_plan_batch *bt = &plan->batches[b];
        fprintf(f, "  batch %u on %s:", b, pg_queue_name(bt->queue));
        for (uint32_t o = bt->first; o < bt->first + bt->count; o++)
            fprintf(f, "%s %s", o == bt->first ? "" : ",", plan->passes[plan->order[o]].name);
        if (!bt->count) fprintf(f, " (no passes)");
        fprintf(f, "%s\n", bt->last ? " (last: final barriers, fence)" : "");
        if (bt->prev_frame_wait >= 0)
            fprintf(f, "      waits for batch %d of the previous frame at all_commands\n", bt->prev_frame_wait);
        for (uint32_t w = 0; w < bt->n_waits; w++) {
            pg_stage_names(bt->waits[w].stages, st, sizeof st);
            fprintf(f, "      waits for batch %d at %s (%s)\n", bt->waits[w].batch, st, bt->waits[w].why);
        }
        for (uint32_t q = 0; q < plan->n_qfots; q++) {
            const pg_qfot *t = &plan->qfots[q];
            if (t->acquire_batch == (int)b) {
                pg_stage_names(t->dst_stages, st, sizeof st);
                pg_access_mask_names(t->dst_access, ac, sizeof ac);
                fprintf(f, "      acquire %-14s %s -> %s  %s/%s", plan->resources[t->resource].name,
                        pg_queue_name(t->src_queue), pg_queue_name(t->dst_queue), st, ac);
                if (t->is_image)
                    fprintf(f, ", %s -> %s", pg_layout_name(t->old_layout), pg_layout_name(t->new_layout));
                fprintf(f, "  (from batch %d, for '%s')\n", t->release_batch, plan->passes[t->consumer_pass].name);
            }
        }
        for (uint32_t q = 0; q < plan->n_qfots; q++) {
            const pg_qfot *t = &plan->qfots[q];
            if (t->release_batch == (int)b) {
                pg_stage_names(t->src_stages, st, sizeof st);
                pg_access_mask_names(t->src_access, ac, sizeof ac);
                fprintf(f, "      release %-14s %s -> %s  %s/%s", plan->resources[t->resource].name,
                        pg_queue_name(t->src_queue), pg_queue_name(t->dst_queue), st, ac);
                if (t->is_image)
                    fprintf(f, ", %s -> %s", pg_layout_name(t->old_layout), pg_layout_name(t->new_layout));
                fprintf(f, "  (at the end, to batch %d)\n", t->acquire_batch);
            }
        }
    }
}

/* The heading: the pipeline, the output image and the immediate mode, each when there is one. */
static void print_heading(FILE *f, const pg_graph_plan *plan, const pg_pipeline *pipeline)
{
    if (pipeline)
        fprintf(f, "pipeline '%s'%s%s%s\n", pipeline->name, pipeline->path[0] ? " (" : "",
                pipeline->path, pipeline->path[0] ? ")" : "");
    if (plan->output >= 0 && (uint32_t)plan->output < plan->n_resources) {
        const pg_plan_resource *o = &plan->resources[plan->output];
        fprintf(f, "output '%s' %ux%u", o->name, o->width, o->height);
        if (plan->hdr_output >= 0 && (uint32_t)plan->hdr_output < plan->n_resources)
            fprintf(f, ", hdr_output '%s'", plan->resources[plan->hdr_output].name);
        fprintf(f, "\n");
    }
    if (plan->immediate)
        fprintf(f, "mode: immediate (declaration order, no aliasing, before every pass a full barrier "
                   "all_commands/memory_write -> all_commands/memory_read|memory_write)\n");
}

/* A pass's "reads:" (writes == false) or "writes:" line; nothing when it has no such slot. */
static void print_pass_slots(FILE *f, const pg_graph_plan *plan, const pg_plan_pass *pp, bool writes)
{
    bool any = false;
    for (uint32_t s = 0; s < pp->n_slots; s++) {
        const pg_plan_slot *sl = &pp->slots[s];
        if (sl->is_write != writes) continue;
        fprintf(f, "%s%s %s (%s%s)", any ? "," : (writes ? "      writes:" : "      reads: "),
                "", plan->resources[sl->resource].name,
                sl->decl.unused ? "unused" : pg_access_name(sl->decl.access),
                sl->decl.unused         ? ""
                : sl->decl.initializes ? ", initialized by the pass"
                : sl->decl.partial     ? ", partial"
                                       : "");
        any = true;
    }
    if (any) fprintf(f, "\n");
}

/* One executed pass: its line, the barriers before it, what it reads and writes, its defines. */
static void print_executed_pass(FILE *f, const pg_graph_plan *plan, uint32_t k)
{
    const pg_plan_pass *pp = &plan->passes[plan->order[k]];
    fprintf(f, "  [%u] %s (%s)", k, pp->name, pp->type && pp->type->name ? pp->type->name : "?");
    if (plan->async) fprintf(f, " on %s, batch %d: %s", pg_queue_name(pp->queue), pp->batch, pp->queue_reason);
    fprintf(f, "\n");
    for (uint32_t b = 0; b < pp->n_barriers; b++) print_barrier(f, plan, &pp->barriers[b]);
    print_pass_slots(f, plan, pp, false);
    print_pass_slots(f, plan, pp, true);
    for (uint32_t d = 0; d < pp->decl.n_defines && d < PG_MAX_DEFINES; d++)
        fprintf(f, "%s%s", d ? " " : "      defines: ", pp->decl.defines[d]);
    if (pp->decl.n_defines) fprintf(f, "\n");
}

/* The passes in execution order, then the barriers after the last one. */
static void print_execution_order(FILE *f, const pg_graph_plan *plan)
{
    fprintf(f, "\nexecution order (%u passes):\n", plan->n_order);
    for (uint32_t k = 0; k < plan->n_order; k++) print_executed_pass(f, plan, k);
    if (plan->n_final_barriers) {
        fprintf(f, "  after the last pass:\n");
        for (uint32_t b = 0; b < plan->n_final_barriers; b++)
            print_barrier(f, plan, &plan->final_barriers[b]);
    }
}

/* The culled passes and resources with their reasons, then the explain lines. */
static void print_culled(FILE *f, const pg_graph_plan *plan, uint32_t n_culled)
{
    fprintf(f, "\nculled passes:%s\n", n_culled ? "" : " none");
    for (uint32_t i = 0; i < plan->n_passes; i++)
        if (plan->passes[i].culled)
            fprintf(f, "  %s: %s\n", plan->passes[i].name, plan->passes[i].cull_reason);
    bool any_res_culled = false;
    for (uint32_t r = 0; r < plan->n_resources; r++) any_res_culled |= plan->resources[r].culled;
    fprintf(f, "\nculled resources:%s\n", any_res_culled ? "" : " none");
    for (uint32_t r = 0; r < plan->n_resources; r++)
        if (plan->resources[r].culled)
            fprintf(f, "  %s: %s\n", plan->resources[r].name, plan->resources[r].cull_reason);
    fprintf(f, "\nexplain (left out, culled, and why):%s\n", plan->n_explain ? "" : " nothing");
    for (uint32_t e = 0; e < plan->n_explain && e < PG_MAX_EXPLAIN; e++)
        fprintf(f, "  %s\n", plan->explain[e]);
}

/* One row of the resource table. */
static void print_resource_row(FILE *f, const pg_graph_plan *plan, const pg_plan_resource *pr)
{
    char size[32], bytes[32], life[2 * PG_NAME_MAX + 8], block[48];
    if (pr->kind == PG_RES_IMAGE)
        snprintf(size, sizeof size, "%ux%u", pr->width, pr->height);
    else
        snprintf(size, sizeof size, "-");
    pg_fmt_bytes(pr->size_bytes, bytes, sizeof bytes);
    if (pr->culled)
        snprintf(life, sizeof life, "(culled)");
    else
        snprintf(life, sizeof life, "%s..%s", pass_name_at(plan, pr->first_pass),
                 pass_name_at(plan, pr->last_pass));
    if (pr->block >= 0)
        snprintf(block, sizeof block, "#%d @ %" PRIu64, pr->block, pr->block_offset);
    else
        snprintf(block, sizeof block, pr->growable ? "own (grow)"
                                      : pr->queues == 3u && pr->lifetime == PG_LIFETIME_TRANSIENT ? "own (2 queues)"
                                                                                                 : "-");
    fprintf(f, "  %-16s %-6s %-10s %-11s %-12s %-10s %-31s %s%s\n", pr->name,
            pg_res_kind_name(pr->kind), pg_lifetime_name(pr->lifetime),
            pr->kind == PG_RES_IMAGE ? pg_format_get(pr->format)->name : "-", size, bytes,
            life, block, pr->is_output ? " (output)" : "");
}

/* The resource table: kind, lifetime, format, size, bytes, live range, memory block. */
static void print_resources(FILE *f, const pg_graph_plan *plan)
{
    fprintf(f, "\nresources:\n");
    fprintf(f, "  %-16s %-6s %-10s %-11s %-12s %-10s %-31s %s\n", "name", "kind", "lifetime",
            "format", "size", "bytes", "lifetime (first..last)", "block @ offset");
    for (uint32_t r = 0; r < plan->n_resources; r++) print_resource_row(f, plan, &plan->resources[r]);
}

/* The memory blocks with their members, live ranges and offsets. */
static void print_blocks(FILE *f, const pg_graph_plan *plan)
{
    fprintf(f, "\nmemory blocks%s:\n", plan->aliasing_disabled ? " (aliasing disabled)" : "");
    for (uint32_t b = 0; b < plan->n_blocks; b++) {
        const pg_plan_block *bl = &plan->blocks[b];
        char bytes[32];
        pg_fmt_bytes(bl->size_bytes, bytes, sizeof bytes);
        fprintf(f, "  #%u %s %s%s%s:", b, pg_res_kind_name(bl->kind), bytes, plan->async ? ", queue " : "",
                plan->async ? pg_queue_name(bl->queue) : "");
        for (uint32_t m = 0; m < bl->n_members && m < PG_MAX_RESOURCES; m++) {
            const pg_plan_resource *pr = &plan->resources[bl->members[m]];
            fprintf(f, "%s %s [%d..%d]", m ? "," : "", pr->name, pr->first_pass, pr->last_pass);
            if (pr->block_offset) fprintf(f, " @ %" PRIu64, pr->block_offset);
        }
        fprintf(f, "\n");
    }
}

/* The totals line: passes, culled, barriers, transient memory before and after aliasing. */
static void print_totals(FILE *f, const pg_graph_plan *plan, uint32_t n_culled)
{
    char un[32], al[32];
    pg_fmt_bytes(plan->transient_bytes_unaliased, un, sizeof un);
    pg_fmt_bytes(plan->transient_bytes_aliased, al, sizeof al);
    fprintf(f, "\ntotals: %u passes run, %u culled; %u barriers (+%u after the last pass); "
               "transient memory %s (%" PRIu64 " B) unaliased -> %s (%" PRIu64
               " B) aliased, saving %.1f%%\n",
            plan->n_order, n_culled, pg_graph_plan_count_barriers(plan), plan->n_final_barriers, un,
            plan->transient_bytes_unaliased, al, plan->transient_bytes_aliased, pg_graph_plan_saving_percent(plan));
}

void pg_graph_plan_print(const pg_graph_plan *plan, const pg_pipeline *pipeline, void *FILE_ptr)
{
    FILE *f = FILE_ptr ? (FILE *)FILE_ptr : stdout;
    if (!plan) {
        fprintf(f, "(no plan)\n");
        return;
    }
    const uint32_t n_culled = pg_graph_plan_count_culled(plan);
    print_heading(f, plan, pipeline);
    print_execution_order(f, plan);
    if (plan->async) print_queues(f, plan);
    print_culled(f, plan, n_culled);
    print_resources(f, plan);
    print_blocks(f, plan);
    print_timeline(f, plan);
    print_totals(f, plan, n_culled);
}
