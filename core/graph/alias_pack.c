/* alias_pack.c - lifetime x size packing (see alias_pack.h).
 *
 * Items are first grouped (same klass, a common memory type: greedy, in index order). Inside a
 * group every item gets the lowest aligned offset at which it shares no byte with an already
 * placed item it conflicts with (first fit over the ends of those items). Two orders are tried
 * (largest first; earliest first), and a third placement: the earlier scheme of passgraph (whole
 * slots, one resource at a time, each joining the slot of the right size that is free: best fit
 * by size, in first-use order) with the slots stacked. The smallest extent is kept; when the
 * slots as separate blocks (no padding between them) would take less, they are used instead, so
 * the result is never worse than that scheme (nor than one block per item, its worst case). */
#include "alias_pack.h"

#include <string.h>

bool pg_pack_conflict(const pg_pack_item *a, const pg_pack_item *b)
{
    if (!(a->last < b->first || b->last < a->first)) return true; /* alive at the same time */
    const pg_pack_item *later = a->first > b->first ? a : b;
    return !later->may_inherit;
}

static uint64_t align_up(uint64_t v, uint64_t a)
{
    if (a <= 1) return v;
    return (v + a - 1) & ~(a - 1);
}

/* Places the items idx[0..m) in the given order; returns the extent. */
static uint64_t place_group(const pg_pack_item *items, const uint32_t *idx, uint32_t m, uint64_t *off)
{
    uint64_t extent = 0;
    for (uint32_t k = 0; k < m; k++) {
        const pg_pack_item *it = &items[idx[k]];
        const uint64_t al = it->alignment ? it->alignment : 1;
        /* candidates: 0 and the aligned end of every conflicting placed item; the lowest that
         * fits wins */
        uint64_t best = UINT64_MAX;
        for (uint32_t c = 0; c <= k; c++) {
            uint64_t cand;
            if (c == k) cand = 0;
            else if (pg_pack_conflict(it, &items[idx[c]])) cand = align_up(off[c] + items[idx[c]].size, al);
            else continue;
            if (cand >= best) continue;
            bool fits = true;
            for (uint32_t j = 0; j < k && fits; j++) {
                if (!pg_pack_conflict(it, &items[idx[j]])) continue;
                const uint64_t js = off[j], je = off[j] + items[idx[j]].size;
                if (cand < je && js < cand + it->size) fits = false;
            }
            if (fits) best = cand;
        }
        off[k] = best;
        if (best + it->size > extent) extent = best + it->size;
    }
    return extent;
}

/* The slot scheme: idx sorted by first use; returns the extent with the slots stacked, and
 * each item's slot, the number of slots and the sum of their sizes (as separate blocks). */
static uint64_t place_slots(const pg_pack_item *items, const uint32_t *idx, uint32_t m, uint64_t *off, int *slot_of,
                            uint32_t *n_slots_out, uint64_t *slot_sum)
{
    int slot_last[PG_PACK_MAX];
    uint64_t slot_size[PG_PACK_MAX], slot_align[PG_PACK_MAX];
    uint32_t n_slots = 0;
    for (uint32_t k = 0; k < m; k++) {
        const pg_pack_item *it = &items[idx[k]];
        int best = -1;
        uint64_t best_diff = 0;
        for (uint32_t sl = 0; it->may_inherit && sl < n_slots; sl++) {
            if (!(slot_last[sl] < it->first)) continue;
            const uint64_t diff = slot_size[sl] > it->size ? slot_size[sl] - it->size : it->size - slot_size[sl];
            if (best < 0 || diff < best_diff) {
                best = (int)sl;
                best_diff = diff;
            }
        }
        if (best < 0) {
            best = (int)n_slots++;
            slot_size[best] = 0;
            slot_align[best] = 1;
        }
        slot_of[k] = best;
        slot_last[best] = it->last; /* it starts after the slot's last member ended */
        if (it->size > slot_size[best]) slot_size[best] = it->size;
        if (it->alignment > slot_align[best]) slot_align[best] = it->alignment;
    }
    uint64_t end = 0, slot_off[PG_PACK_MAX];
    *slot_sum = 0;
    for (uint32_t sl = 0; sl < n_slots; sl++) {
        slot_off[sl] = align_up(end, slot_align[sl]);
        end = slot_off[sl] + slot_size[sl];
        *slot_sum += slot_size[sl];
    }
    *n_slots_out = n_slots;
    for (uint32_t k = 0; k < m; k++) off[k] = slot_off[slot_of[k]];
    return end;
}

int pg_alias_pack(const pg_pack_item *items, uint32_t n, bool share, pg_pack_place *place,
                  pg_pack_block *blocks)
{
    if (n > PG_PACK_MAX) return -1;
    int n_blocks = 0;
    if (!share) {
        for (uint32_t i = 0; i < n; i++) {
            blocks[n_blocks] = (pg_pack_block){items[i].klass, items[i].type_bits, items[i].size,
                                               items[i].alignment ? items[i].alignment : 1};
            place[i] = (pg_pack_place){n_blocks++, 0};
        }
        return n_blocks;
    }
    /* groups: klass + common memory type */
    int group[PG_PACK_MAX];
    uint32_t gbits[PG_PACK_MAX], gklass[PG_PACK_MAX];
    uint32_t n_groups = 0;
    for (uint32_t i = 0; i < n; i++) {
        group[i] = -1;
        for (uint32_t g = 0; g < n_groups && items[i].type_bits; g++)
            if (gklass[g] == items[i].klass && (gbits[g] & items[i].type_bits)) {
                group[i] = (int)g;
                gbits[g] &= items[i].type_bits;
                break;
            }
        if (group[i] < 0) {
            gklass[n_groups] = items[i].klass;
            gbits[n_groups] = items[i].type_bits;
            group[i] = (int)n_groups++;
        }
    }
    for (uint32_t g = 0; g < n_groups; g++) {
        uint32_t idx[3][PG_PACK_MAX], m = 0;
        uint64_t sum = 0, max_align = 1;
        for (uint32_t i = 0; i < n; i++)
            if (group[i] == (int)g) {
                idx[0][m] = idx[1][m] = idx[2][m] = i;
                m++;
                sum += items[i].size;
                if (items[i].alignment > max_align) max_align = items[i].alignment;
            }
        /* order 0: largest first (ties: earliest first, then index); order 1: earliest first
         * (ties: largest first, then index); order 2 (slots): earliest first, then index;
         * insertion sorts keep it stable */
        for (int o = 0; o < 3; o++)
            for (uint32_t a = 1; a < m; a++) {
                const uint32_t v = idx[o][a];
                uint32_t b = a;
                while (b > 0) {
                    const pg_pack_item *x = &items[idx[o][b - 1]], *y = &items[v];
                    const bool before = o == 0   ? (y->size > x->size || (y->size == x->size && y->first < x->first))
                                        : o == 1 ? (y->first < x->first || (y->first == x->first && y->size > x->size))
                                                 : y->first < x->first;
                    if (!before) break;
                    idx[o][b] = idx[o][b - 1];
                    b--;
                }
                idx[o][b] = v;
            }
        uint64_t off[3][PG_PACK_MAX], e[3];
        e[0] = place_group(items, idx[0], m, off[0]);
        e[1] = place_group(items, idx[1], m, off[1]);
        int slot_of[PG_PACK_MAX];
        uint32_t n_slots = 0;
        uint64_t slot_sum = 0;
        e[2] = place_slots(items, idx[2], m, off[2], slot_of, &n_slots, &slot_sum);
        int o = 0;
        for (int c = 1; c < 3; c++)
            if (e[c] < e[o]) o = c;
        const uint64_t extent = e[o];
        if (slot_sum < extent && slot_sum <= sum) {
            /* alignment padding between the slots costs more than it saves: the slots as
             * blocks of their own (offset 0 each) */
            const int first = n_blocks;
            for (uint32_t sl = 0; sl < n_slots; sl++)
                blocks[first + (int)sl] = (pg_pack_block){gklass[g], gbits[g], 0, 1};
            for (uint32_t k = 0; k < m; k++) {
                const pg_pack_item *it = &items[idx[2][k]];
                pg_pack_block *b = &blocks[first + slot_of[k]];
                if (it->size > b->size) b->size = it->size;
                if (it->alignment > b->alignment) b->alignment = it->alignment;
                b->type_bits = gbits[g];
                place[idx[2][k]] = (pg_pack_place){first + slot_of[k], 0};
            }
            n_blocks += (int)n_slots;
            continue;
        }
        if (extent > sum) { /* padding made sharing worse than separate blocks */
            for (uint32_t k = 0; k < m; k++) {
                const pg_pack_item *it = &items[idx[0][k]];
                blocks[n_blocks] = (pg_pack_block){it->klass, it->type_bits, it->size,
                                                   it->alignment ? it->alignment : 1};
                place[idx[0][k]] = (pg_pack_place){n_blocks++, 0};
            }
            continue;
        }
        blocks[n_blocks] = (pg_pack_block){gklass[g], gbits[g], extent, max_align};
        for (uint32_t k = 0; k < m; k++) place[idx[o][k]] = (pg_pack_place){n_blocks, off[o][k]};
        n_blocks++;
    }
    return n_blocks;
}
