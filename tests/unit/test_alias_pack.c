/* test_alias_pack.c - the lifetime x size packer (core/graph/alias_pack.c) on the CPU: hand cases and
 * random lifetimes. Properties: no two items alive at the same time share a byte; an item that
 * may not inherit shares no byte with one that ended before it; offsets honour alignment; blocks
 * hold one klass with a common memory type; blocks contain their members; the total never
 * exceeds one block per item, nor passgraph's earlier one-resource-per-block scheme, and is never below the peak of live bytes (a lower bound). */
#include <stdlib.h>
#include <string.h>

#include "alias_pack.h"
#include "test_util.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rnd(uint32_t n)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (uint32_t)(rng_state % n);
}

/* Checks every guarantee of alias_pack.h; returns the sum of block sizes. */
static uint64_t check_packing(const pg_pack_item *it, uint32_t n, const pg_pack_place *pl, const pg_pack_block *bl,
                              int nb, const char *what)
{
    uint64_t total = 0, sum = 0;
    CHECK_MSG(nb >= (n ? 1 : 0) && nb <= (int)n, "%s: %d blocks for %u items", what, nb, n);
    for (int b = 0; b < nb; b++) total += bl[b].size;
    for (uint32_t i = 0; i < n; i++) {
        sum += it[i].size;
        CHECK_MSG(pl[i].block >= 0 && pl[i].block < nb, "%s: item %u in block %d", what, i, pl[i].block);
        if (pl[i].block < 0 || pl[i].block >= nb) continue;
        const pg_pack_block *b = &bl[pl[i].block];
        const uint64_t al = it[i].alignment ? it[i].alignment : 1;
        CHECK_MSG(pl[i].offset % al == 0, "%s: item %u offset %llu not aligned to %llu", what, i,
                  (unsigned long long)pl[i].offset, (unsigned long long)al);
        CHECK_MSG(pl[i].offset + it[i].size <= b->size, "%s: item %u ends past its block", what, i);
        CHECK_MSG(b->klass == it[i].klass, "%s: item %u in a block of another klass", what, i);
        CHECK_MSG((b->type_bits & it[i].type_bits) == b->type_bits && (b->type_bits || it[i].type_bits == 0),
                  "%s: block type bits %x not within item %u's %x", what, b->type_bits, i, it[i].type_bits);
        for (uint32_t j = 0; j < i; j++) {
            if (pl[j].block != pl[i].block) continue;
            const bool bytes = pl[i].offset < pl[j].offset + it[j].size && pl[j].offset < pl[i].offset + it[i].size;
            const bool time = !(it[i].last < it[j].first || it[j].last < it[i].first);
            const pg_pack_item *later = it[i].first > it[j].first ? &it[i] : &it[j];
            CHECK_MSG(!(bytes && time), "%s: items %u [%d,%d] and %u [%d,%d] alive together share bytes", what, j,
                      it[j].first, it[j].last, i, it[i].first, it[i].last);
            CHECK_MSG(!(bytes && !time && !later->may_inherit),
                      "%s: items %u and %u share bytes though the later one may not inherit", what, j, i);
        }
    }
    CHECK_MSG(total <= sum, "%s: %llu bytes packed > %llu bytes one block per item", what,
              (unsigned long long)total, (unsigned long long)sum);
    return total;
}

/* The largest sum of sizes alive at one time, per klass (summed over klasses): a lower bound. */
static uint64_t peak(const pg_pack_item *it, uint32_t n)
{
    uint64_t total = 0;
    for (uint32_t k = 0; k < 2; k++) {
        uint64_t best = 0;
        for (int t = 0; t < 64; t++) {
            uint64_t s = 0;
            for (uint32_t i = 0; i < n; i++)
                if (it[i].klass == k && it[i].first <= t && t <= it[i].last) s += it[i].size;
            if (s > best) best = s;
        }
        total += best;
    }
    return total;
}

/* passgraph's earlier scheme, written again here: one resource per slot at a time, slots of
 * their own memory; a resource that may inherit joins the free slot closest in size; the total
 * is the sum of slot sizes. */
static uint64_t slot_scheme(const pg_pack_item *it, uint32_t n)
{
    uint32_t order[64];
    for (uint32_t i = 0; i < n; i++) order[i] = i;
    for (uint32_t a = 1; a < n; a++) /* by first use, stable */
        for (uint32_t b = a; b > 0 && it[order[b]].first < it[order[b - 1]].first; b--) {
            uint32_t t = order[b];
            order[b] = order[b - 1];
            order[b - 1] = t;
        }
    int last[64];
    uint64_t size[64], total = 0;
    uint32_t ns = 0;
    for (uint32_t k = 0; k < n; k++) {
        const pg_pack_item *x = &it[order[k]];
        int best = -1;
        uint64_t bd = 0;
        for (uint32_t s = 0; x->may_inherit && s < ns; s++) {
            if (!(last[s] < x->first)) continue;
            uint64_t d = size[s] > x->size ? size[s] - x->size : x->size - size[s];
            if (best < 0 || d < bd) {
                best = (int)s;
                bd = d;
            }
        }
        if (best < 0) {
            best = (int)ns++;
            size[best] = 0;
        }
        last[best] = x->last;
        if (x->size > size[best]) size[best] = x->size;
    }
    for (uint32_t s = 0; s < ns; s++) total += size[s];
    return total;
}

static void test_hand_cases(void)
{
    pg_pack_place pl[8];
    pg_pack_block bl[8];
    { /* a chain t1 [0,1], t2 [1,2], t3 [2,3]: t1 and t3 share bytes, t2 sits next to them */
        pg_pack_item it[3] = {{128, 16, ~0u, 0, 0, 1, true}, {128, 16, ~0u, 0, 1, 2, true}, {128, 16, ~0u, 0, 2, 3, true}};
        int nb = pg_alias_pack(it, 3, true, pl, bl);
        CHECK(nb == 1);
        const uint64_t t = check_packing(it, 3, pl, bl, nb, "chain");
        CHECK_MSG(t == 256, "chain: %llu bytes", (unsigned long long)t);
        CHECK(pl[0].offset == pl[2].offset && pl[1].offset != pl[0].offset);
        /* sizes of 100 aligned to 16: stacked the second would start at 112 (212 B); two blocks
         * of their own take 200 B, and the packer keeps those */
        for (int i = 0; i < 3; i++) it[i].size = 100;
        nb = pg_alias_pack(it, 3, true, pl, bl);
        CHECK(nb == 2 && check_packing(it, 3, pl, bl, nb, "chain 100") == 200);
    }
    { /* a small and a large resource alive after a large one: both go into its bytes */
        pg_pack_item it[3] = {{1000, 1, ~0u, 0, 0, 0, true}, {600, 1, ~0u, 0, 1, 1, true}, {400, 1, ~0u, 0, 1, 1, true}};
        int nb = pg_alias_pack(it, 3, true, pl, bl);
        CHECK(nb == 1 && bl[0].size == 1000);
        check_packing(it, 3, pl, bl, nb, "split");
        /* one block per resource at offset 0 (the old scheme) needs 1000 + 400 */
    }
    { /* may not inherit: the later item gets bytes nobody used before */
        pg_pack_item it[2] = {{100, 1, ~0u, 0, 0, 0, true}, {100, 1, ~0u, 0, 1, 1, false}};
        int nb = pg_alias_pack(it, 2, true, pl, bl);
        CHECK(check_packing(it, 2, pl, bl, nb, "inherit") == 200);
    }
    { /* klasses and memory types that do not meet never share a block */
        pg_pack_item it[4] = {{100, 1, 0x1, 0, 0, 0, true}, {100, 1, 0x2, 0, 1, 1, true},
                              {100, 1, 0x3, 1, 2, 2, true}, {100, 1, 0x0, 1, 3, 3, true}};
        int nb = pg_alias_pack(it, 4, true, pl, bl);
        CHECK(nb == 4);
        check_packing(it, 4, pl, bl, nb, "types");
    }
    { /* alignment padding that would make sharing cost more than separate blocks */
        pg_pack_item it[2] = {{10, 1, ~0u, 0, 0, 1, true}, {10, 4096, ~0u, 0, 0, 1, true}};
        int nb = pg_alias_pack(it, 2, true, pl, bl);
        CHECK(check_packing(it, 2, pl, bl, nb, "padding") == 20);
    }
    { /* share = false: one block per item, offset 0 */
        pg_pack_item it[2] = {{100, 1, ~0u, 0, 0, 0, true}, {100, 1, ~0u, 0, 1, 1, true}};
        int nb = pg_alias_pack(it, 2, false, pl, bl);
        CHECK(nb == 2 && pl[0].offset == 0 && pl[1].offset == 0 && pl[0].block != pl[1].block);
    }
    CHECK(pg_alias_pack(NULL, PG_PACK_MAX + 1, true, pl, bl) == -1);
}

static void test_random(void)
{
    static pg_pack_item it[64];
    static pg_pack_place pl[64];
    static pg_pack_block bl[64];
    uint64_t packed = 0, separate = 0, lower = 0, slots_total = 0, packed_simple = 0;
    int at_peak = 0, better_than_slots = 0, n_simple = 0;
    const int rounds = 3000;
    for (int round = 0; round < rounds; round++) {
        const uint32_t n = 1 + rnd(40);
        for (uint32_t i = 0; i < n; i++) {
            const int a = (int)rnd(24), len = (int)rnd(8);
            const uint64_t aligns[4] = {1, 256, 4096, 65536};
            it[i] = (pg_pack_item){
                .size = round % 3 == 0 ? (uint64_t)(1 + rnd(8)) * 65536 : 1 + rnd(1u << 20),
                .alignment = round % 2 ? aligns[rnd(4)] : 1,
                .type_bits = round % 5 == 0 ? (1u << rnd(3)) | (1u << rnd(3)) : ~0u,
                .klass = round % 7 == 0 ? rnd(2) : 0,
                .first = a,
                .last = a + len,
                .may_inherit = rnd(4) != 0,
            };
        }
        char what[32];
        snprintf(what, sizeof what, "random round %d", round);
        const int nb = pg_alias_pack(it, n, true, pl, bl);
        const uint64_t t = check_packing(it, n, pl, bl, nb, what);
        uint64_t s = 0;
        for (uint32_t i = 0; i < n; i++) s += it[i].size;
        const bool simple = round % 5 && round % 7; /* one klass, all memory types */
        if (simple) {
            const uint64_t pk = peak(it, n);
            CHECK_MSG(t >= pk, "%s: %llu packed below the peak %llu", what, (unsigned long long)t,
                      (unsigned long long)pk);
            lower += pk;
            at_peak += t == pk;
            { /* never worse than the slot scheme */
                const uint64_t old = slot_scheme(it, n);
                CHECK_MSG(t <= old, "%s: %llu packed > %llu with the slot scheme", what, (unsigned long long)t,
                          (unsigned long long)old);
                better_than_slots += t < old;
                slots_total += old;
                packed_simple += t;
                n_simple++;
            }
        }
        packed += t;
        separate += s;
        /* deterministic */
        pg_pack_place pl2[64];
        pg_pack_block bl2[64];
        bool same = pg_alias_pack(it, n, true, pl2, bl2) == nb;
        for (uint32_t i = 0; i < n; i++) same = same && pl[i].block == pl2[i].block && pl[i].offset == pl2[i].offset;
        CHECK_MSG(same, "%s: not deterministic", what);
    }
    printf("test_alias_pack: %d random rounds: packed %.1f%% of one block per item; %d single-klass rounds "
           "at the live-bytes peak (lower bound sum %.1f%% of packed); %d single-klass rounds: %.1f%% of the slot "
           "scheme's bytes, smaller in %d\n",
           rounds, 100.0 * (double)packed / (double)separate, at_peak, 100.0 * (double)lower / (double)packed,
           n_simple, 100.0 * (double)packed_simple / (double)slots_total, better_than_slots);
    CHECK(packed < separate);
}

int main(void)
{
    test_hand_cases();
    test_random();
    return pg_test_finish("test_alias_pack");
}
