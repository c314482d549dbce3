/* alias_pack.h - lifetime x size packing of transient resources into shared memory blocks.
 *
 * Pure (no Vulkan calls, no allocation). The compiler calls it with estimated sizes and
 * alignments (core/graph/graph_lifetimes.c, compile phase 6: the offsets the dump shows); the runtime calls it
 * again, one plan block at a time, with the real vkGet*MemoryRequirements (core/runtime/graph_execute_memory.c),
 * so a run-time block only ever holds members of one plan block.
 *
 * Guarantees of pg_alias_pack():
 *   - two items whose lifetimes [first, last] overlap never share a byte;
 *   - an item that may not inherit (its first access does not overwrite every byte) never shares
 *     a byte with an item that ended before it started;
 *   - items share a block only when they have the same klass and a common memory type bit
 *     (the block's type_bits is the AND of its members'); an item with type_bits 0 is alone;
 *   - every offset is a multiple of the item's alignment (alignments are powers of two; 0 = 1);
 *   - the sum of the block sizes never exceeds the sum of the item sizes (one block per item), nor
 *     that of passgraph's earlier scheme (one resource per block at a time, best fit by size).
 */
#ifndef PG_ALIAS_PACK_H
#define PG_ALIAS_PACK_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_pack_item {
    uint64_t size;
    uint64_t alignment;   /* power of two; 0 is taken as 1 */
    uint32_t type_bits;   /* memory types the item can live in (VkMemoryRequirements) */
    uint32_t klass;       /* only items of one klass share a block (e.g. image vs buffer) */
    int first, last;      /* lifetime, inclusive, in executed-pass positions */
    bool may_inherit;     /* its first access overwrites every byte: may start where others were */
} pg_pack_item;

typedef struct pg_pack_place {
    int block;            /* index into the blocks written by pg_alias_pack */
    uint64_t offset;      /* byte offset inside that block */
} pg_pack_place;

typedef struct pg_pack_block {
    uint32_t klass;
    uint32_t type_bits;
    uint64_t size;        /* highest end offset of its members */
    uint64_t alignment;   /* largest member alignment */
} pg_pack_block;

/* True when items a and b may not share a byte (overlapping lifetimes, or the later one may not
 * inherit the earlier one's bytes). */
bool pg_pack_conflict(const pg_pack_item *a, const pg_pack_item *b);

/* Places n items (at most PG_PACK_MAX). share = false gives every item its own block at offset
 * 0. Writes place[n] and blocks[<= n]; returns the number of blocks, or -1 when n is too large. */
#define PG_PACK_MAX 256
int pg_alias_pack(const pg_pack_item *items, uint32_t n, bool share, pg_pack_place *place,
                  pg_pack_block *blocks);

#ifdef __cplusplus
}
#endif
#endif
