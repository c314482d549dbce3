/* gen_meshopt.c - writes the EXT_meshopt_compression twin of tests/corpus/gltf/compressed/twin.gltf
 * (meshopt.gltf + meshopt.bin, and the same as meshopt.glb) with the meshoptimizer encoder.
 * Usage: gen_meshopt TWIN.gltf OUTDIR. Deterministic (encoder versions fixed: vertex 0, index 1);
 * the output is committed next to twin.gltf and the ctest gen_meshopt_check regenerates it and
 * compares it byte for byte.
 *
 * One mesh, two primitives drawing the same vertices (the twin's one primitive twice):
 *   POSITION   FLOAT VEC3, byteStride 12    ATTRIBUTES, filter NONE         (lossless)
 *   NORMAL     normalized SHORT VEC3, 8     ATTRIBUTES, filter OCTAHEDRAL   (16-bit octahedral)
 *   TANGENT    normalized SHORT VEC4, 8     ATTRIBUTES, filter QUATERNION   (16 bits; see below)
 *   TEXCOORD_0 FLOAT VEC2, 8                ATTRIBUTES, filter EXPONENTIAL  (24-bit mantissa)
 *   primitive 0 indices UNSIGNED_SHORT      TRIANGLES                       (lossless)
 *   primitive 1 indices UNSIGNED_INT        INDICES                         (lossless)
 * The compressed streams are buffers[0]; buffers[1] is the fallback buffer (no uri, fallback:
 * true). KHR_mesh_quantization (for the SHORT normals/tangents) and EXT_meshopt_compression are
 * both required. The tangents go through the QUATERNION filter as a unit 4-vector: the loader
 * renormalizes xyz and keeps the sign of w, so the twin's
 * tangents come back when the filter is decoded: the vector is (x, y, z, 0.5) normalized (all of
 * the twin's w are +1, checked below, and x > 0 is its largest component, which the filter
 * rebuilds as positive, so no sign flips). */
#include <math.h>
#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

#define MAX_VIEWS 8

typedef struct stream {
    const char *mode, *filter;
    size_t count, stride;
    unsigned char *raw; /* the uncompressed (filter-encoded) bytes */
    size_t comp_off, comp_len, fb_off;
} stream;

static unsigned char g_comp[1 << 20];
static size_t g_comp_len;

static void add_comp(stream *s)
{
    size_t n = 0;
    if (!strcmp(s->mode, "ATTRIBUTES")) {
        n = meshopt_encodeVertexBuffer(g_comp + g_comp_len, sizeof g_comp - g_comp_len, s->raw, s->count, s->stride);
    } else {
        unsigned *idx = malloc(s->count * sizeof *idx);
        for (size_t i = 0; i < s->count; i++) {
            if (s->stride == 2) {
                unsigned short x;
                memcpy(&x, s->raw + 2 * i, 2);
                idx[i] = x;
            } else {
                memcpy(&idx[i], s->raw + 4 * i, 4);
            }
        }
        n = !strcmp(s->mode, "TRIANGLES")
                ? meshopt_encodeIndexBuffer(g_comp + g_comp_len, sizeof g_comp - g_comp_len, idx, s->count)
                : meshopt_encodeIndexSequence(g_comp + g_comp_len, sizeof g_comp - g_comp_len, idx, s->count);
        free(idx);
    }
    if (n == 0) {
        fprintf(stderr, "gen_meshopt: encoding failed\n");
        exit(1);
    }
    s->comp_off = g_comp_len;
    s->comp_len = n;
    g_comp_len += n;
    while (g_comp_len % 4) g_comp[g_comp_len++] = 0;
}

static void write_json(FILE *f, const stream *st, int ns, size_t n_vertices, size_t fb_len, int glb)
{
    fprintf(f, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"passgraph gen_meshopt.c\"},\n");
    fprintf(f, "\"extensionsUsed\":[\"KHR_mesh_quantization\",\"EXT_meshopt_compression\"],\n");
    fprintf(f, "\"extensionsRequired\":[\"KHR_mesh_quantization\",\"EXT_meshopt_compression\"],\n");
    fprintf(f, "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"grid\"}],\n");
    fprintf(f, "\"meshes\":[{\"primitives\":[\n");
    for (int p = 0; p < 2; p++)
        fprintf(f, " {\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TANGENT\":2,\"TEXCOORD_0\":3},\"indices\":%d,"
                   "\"material\":0}%s\n", 4 + p, p ? "" : ",");
    fprintf(f, "]}],\n");
    fprintf(f, "\"materials\":[{\"name\":\"clay\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.5,0.3,1],"
               "\"metallicFactor\":0,\"roughnessFactor\":0.5}}],\n");
    fprintf(f, "\"accessors\":[\n");
    fprintf(f, " {\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},\n", n_vertices);
    fprintf(f, " {\"bufferView\":1,\"componentType\":5122,\"normalized\":true,\"count\":%zu,\"type\":\"VEC3\"},\n",
            n_vertices);
    fprintf(f, " {\"bufferView\":2,\"componentType\":5122,\"normalized\":true,\"count\":%zu,\"type\":\"VEC4\"},\n",
            n_vertices);
    fprintf(f, " {\"bufferView\":3,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},\n", n_vertices);
    fprintf(f, " {\"bufferView\":4,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"},\n", st[4].count);
    fprintf(f, " {\"bufferView\":5,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}\n", st[5].count);
    fprintf(f, "],\n\"bufferViews\":[\n");
    for (int i = 0; i < ns; i++) {
        const stream *s = &st[i];
        int attr = !strcmp(s->mode, "ATTRIBUTES");
        fprintf(f, " {\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%zu,", s->fb_off, s->count * s->stride);
        if (attr) fprintf(f, "\"byteStride\":%zu,", s->stride);
        fprintf(f, "\"target\":%d,\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":%zu,"
                   "\"byteLength\":%zu,\"byteStride\":%zu,\"count\":%zu,\"mode\":\"%s\"",
                attr ? 34962 : 34963, s->comp_off, s->comp_len, s->stride, s->count, s->mode);
        if (strcmp(s->filter, "NONE")) fprintf(f, ",\"filter\":\"%s\"", s->filter);
        fprintf(f, "}}}%s\n", i + 1 < ns ? "," : "");
    }
    fprintf(f, "],\n\"buffers\":[\n");
    if (glb)
        fprintf(f, " {\"byteLength\":%zu},\n", g_comp_len);
    else
        fprintf(f, " {\"byteLength\":%zu,\"uri\":\"meshopt.bin\"},\n", g_comp_len);
    fprintf(f, " {\"byteLength\":%zu,\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}\n", fb_len);
    fprintf(f, "]}\n");
}

static void put32(FILE *f, unsigned v)
{
    unsigned char b[4] = {v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >> 24) & 255};
    fwrite(b, 1, 4, f);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gen_meshopt TWIN.gltf OUTDIR\n");
        return 2;
    }
    pg_scene *s = NULL;
    pg_error err = {0};
    if (pg_scene_load_gltf(argv[1], &s, &err) != PG_OK) {
        fprintf(stderr, "gen_meshopt: %s\n", err.msg);
        return 1;
    }
    if (s->n_primitives != 1) {
        fprintf(stderr, "gen_meshopt: expected one primitive\n");
        return 1;
    }
    meshopt_encodeVertexVersion(0);
    meshopt_encodeIndexVersion(1);
    const size_t n = s->n_vertices, ni = s->n_indices;
    float *v4 = malloc(n * 4 * sizeof(float));
    stream st[6] = {
        {"ATTRIBUTES", "NONE", n, 12, NULL, 0, 0, 0},       {"ATTRIBUTES", "OCTAHEDRAL", n, 8, NULL, 0, 0, 0},
        {"ATTRIBUTES", "QUATERNION", n, 8, NULL, 0, 0, 0}, {"ATTRIBUTES", "EXPONENTIAL", n, 8, NULL, 0, 0, 0},
        {"TRIANGLES", "NONE", ni, 2, NULL, 0, 0, 0},       {"INDICES", "NONE", ni, 4, NULL, 0, 0, 0},
    };
    for (int i = 0; i < 6; i++) st[i].raw = calloc(st[i].count, st[i].stride);
    for (size_t i = 0; i < n; i++) memcpy(st[0].raw + 12 * i, s->vertices[i].position, 12);
    for (size_t i = 0; i < n; i++) {
        memcpy(&v4[4 * i], s->vertices[i].normal, 12);
        v4[4 * i + 3] = 0;
    }
    meshopt_encodeFilterOct(st[1].raw, n, 8, 16, v4);
    for (size_t i = 0; i < n; i++) {
        const float *t = s->vertices[i].tangent;
        if (t[3] != 1.0f) {
            fprintf(stderr, "gen_meshopt: tangent %zu has w %g (expected 1)\n", i, t[3]);
            return 1;
        }
        /* w = 0.5 (not 1): x (>= 0.86 on this grid) is then the largest component, the one the
         * filter drops and rebuilds, so skipping the filter's decoding cannot go unnoticed */
        const float q[4] = {t[0], t[1], t[2], 0.5f};
        float l = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int k = 0; k < 4; k++) v4[4 * i + (size_t)k] = q[k] / l;
    }
    meshopt_encodeFilterQuat(st[2].raw, n, 8, 16, v4);
    for (size_t i = 0; i < n; i++) memcpy(&v4[2 * i], s->vertices[i].uv, 8);
    meshopt_encodeFilterExp(st[3].raw, n, 8, 24, v4);
    for (size_t i = 0; i < ni; i++) {
        unsigned short x = (unsigned short)s->indices[i];
        memcpy(st[4].raw + 2 * i, &x, 2);
        memcpy(st[5].raw + 4 * i, &s->indices[i], 4);
    }
    size_t fb = 0;
    for (int i = 0; i < 6; i++) {
        add_comp(&st[i]);
        st[i].fb_off = fb;
        fb += st[i].count * st[i].stride;
        fb = (fb + 3) & ~(size_t)3;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/meshopt.bin", argv[2]);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(g_comp, 1, g_comp_len, f) != g_comp_len || fclose(f)) {
        fprintf(stderr, "gen_meshopt: cannot write %s\n", path);
        return 1;
    }
    snprintf(path, sizeof path, "%s/meshopt.gltf", argv[2]);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "gen_meshopt: cannot write %s\n", path);
        return 1;
    }
    write_json(f, st, 6, n, fb, 0);
    fclose(f);
    /* the GLB: the same JSON (buffers[0] is the BIN chunk), padded with spaces */
    char *js = NULL;
    size_t jl = 0;
    FILE *m = open_memstream(&js, &jl);
    write_json(m, st, 6, n, fb, 1);
    fclose(m);
    size_t jpad = (4 - jl % 4) % 4;
    snprintf(path, sizeof path, "%s/meshopt.glb", argv[2]);
    f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "gen_meshopt: cannot write %s\n", path);
        return 1;
    }
    fwrite("glTF", 1, 4, f);
    put32(f, 2);
    put32(f, (unsigned)(12 + 8 + jl + jpad + 8 + g_comp_len));
    put32(f, (unsigned)(jl + jpad));
    put32(f, 0x4E4F534Au);
    fwrite(js, 1, jl, f);
    fwrite("   ", 1, jpad, f);
    put32(f, (unsigned)g_comp_len);
    put32(f, 0x004E4942u);
    fwrite(g_comp, 1, g_comp_len, f);
    fclose(f);
    free(js);
    for (int i = 0; i < 6; i++) free(st[i].raw);
    free(v4);
    pg_scene_free(s);
    printf("gen_meshopt: %zu vertices, %zu indices, %zu compressed bytes (fallback %zu)\n", n, ni, g_comp_len, fb);
    return 0;
}
