/* gen_draco.cpp - writes the KHR_draco_mesh_compression twins of
 * tests/corpus/gltf/compressed/twin.gltf with the Draco encoder (Debian libdraco):
 *   draco.gltf + draco.bin     no quantization, sequential connectivity (lossless: the decoded
 *                              triangles carry the twin's exact values; points may be renumbered)
 *   draco_q.gltf + draco_q.bin edgebreaker connectivity, POSITION quantized to 14 bits, NORMAL
 *                              and TANGENT (a generic attribute) to 12, TEXCOORD_0 to 12 (lossy)
 * Usage: gen_draco TWIN.gltf OUTDIR. Deterministic; the output is committed next to twin.gltf and
 * the ctest gen_draco_check regenerates it and compares it byte for byte. The accessors have no
 * bufferView (KHR_draco_mesh_compression is required); their counts are the decoded ones. */
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "scene.h"
}

static bool write_file(const std::string &path, const void *data, size_t n)
{
    FILE *f = fopen(path.c_str(), "wb");
    if (!f) return false;
    bool ok = fwrite(data, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static int emit(const pg_scene *s, const std::string &dir, const std::string &stem, bool quantize)
{
    const uint32_t nf = s->n_indices / 3;
    draco::TriangleSoupMeshBuilder b;
    b.Start(int(nf));
    const int ap = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int an = b.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int at = b.AddAttribute(draco::GeometryAttribute::GENERIC, 4, draco::DT_FLOAT32);
    const int au = b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (uint32_t f = 0; f < nf; f++) {
        const pg_vertex *v[3];
        for (int k = 0; k < 3; k++) v[k] = &s->vertices[s->indices[3 * f + uint32_t(k)]];
        const draco::FaceIndex fi(f);
        b.SetAttributeValuesForFace(ap, fi, v[0]->position, v[1]->position, v[2]->position);
        b.SetAttributeValuesForFace(an, fi, v[0]->normal, v[1]->normal, v[2]->normal);
        b.SetAttributeValuesForFace(at, fi, v[0]->tangent, v[1]->tangent, v[2]->tangent);
        b.SetAttributeValuesForFace(au, fi, v[0]->uv, v[1]->uv, v[2]->uv);
    }
    std::unique_ptr<draco::Mesh> mesh = b.Finalize();
    if (!mesh) {
        fprintf(stderr, "gen_draco: mesh builder failed\n");
        return 1;
    }
    draco::Encoder enc;
    if (quantize) {
        enc.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
        enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
        enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 12);
        enc.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, 12);
        enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    } else {
        enc.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    }
    enc.SetSpeedOptions(5, 5);
    draco::EncoderBuffer eb;
    draco::Status st = enc.EncodeMeshToBuffer(*mesh, &eb);
    if (!st.ok()) {
        fprintf(stderr, "gen_draco: %s\n", st.error_msg());
        return 1;
    }
    /* the decoded counts (the encoder may merge or reorder points) */
    draco::DecoderBuffer db;
    db.Init(eb.data(), eb.size());
    draco::Decoder dec;
    auto r = dec.DecodeMeshFromBuffer(&db);
    if (!r.ok()) {
        fprintf(stderr, "gen_draco: %s\n", r.status().error_msg());
        return 1;
    }
    std::unique_ptr<draco::Mesh> back = std::move(r).value();
    const size_t np = back->num_points(), nidx = size_t(back->num_faces()) * 3;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    const draco::PointAttribute *pp = back->GetAttributeByUniqueId(uint32_t(mesh->attribute(ap)->unique_id()));
    for (size_t i = 0; i < np && pp; i++) {
        float p[3];
        pp->ConvertValue<float>(pp->mapped_index(draco::PointIndex(uint32_t(i))), 3, p);
        for (int k = 0; k < 3; k++) {
            lo[k] = p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = p[k] > hi[k] ? p[k] : hi[k];
        }
    }
    size_t blen = (eb.size() + 3) & ~size_t(3);
    std::vector<char> bin(blen, 0);
    std::copy(eb.data(), eb.data() + eb.size(), bin.begin());
    if (!write_file(dir + "/" + stem + ".bin", bin.data(), bin.size())) {
        fprintf(stderr, "gen_draco: cannot write %s/%s.bin\n", dir.c_str(), stem.c_str());
        return 1;
    }
    std::string path = dir + "/" + stem + ".gltf";
    FILE *f = fopen(path.c_str(), "w");
    if (!f) {
        fprintf(stderr, "gen_draco: cannot write %s\n", path.c_str());
        return 1;
    }
    fprintf(f, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"passgraph gen_draco.cpp\"},\n");
    fprintf(f, "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],\n");
    fprintf(f, "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\n");
    fprintf(f, "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"grid\"}],\n");
    fprintf(f, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TANGENT\":2,"
               "\"TEXCOORD_0\":3},\"indices\":4,\"material\":0,\n");
    fprintf(f, " \"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":0,\"attributes\":{\"POSITION\":%d,"
               "\"NORMAL\":%d,\"TANGENT\":%d,\"TEXCOORD_0\":%d}}}}]}],\n",
            int(mesh->attribute(ap)->unique_id()), int(mesh->attribute(an)->unique_id()),
            int(mesh->attribute(at)->unique_id()), int(mesh->attribute(au)->unique_id()));
    fprintf(f, "\"materials\":[{\"name\":\"clay\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.5,0.3,1],"
               "\"metallicFactor\":0,\"roughnessFactor\":0.5}}],\n");
    fprintf(f, "\"accessors\":[\n");
    fprintf(f, " {\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\",\"min\":[%.9g,%.9g,%.9g],"
               "\"max\":[%.9g,%.9g,%.9g]},\n",
            np, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    fprintf(f, " {\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},\n", np);
    fprintf(f, " {\"componentType\":5126,\"count\":%zu,\"type\":\"VEC4\"},\n", np);
    fprintf(f, " {\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},\n", np);
    fprintf(f, " {\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"}\n", nidx);
    fprintf(f, "],\n\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu}],\n", eb.size());
    fprintf(f, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s.bin\"}]}\n", blen, stem.c_str());
    fclose(f);
    printf("gen_draco: %s: %zu points, %zu indices, %zu bytes\n", stem.c_str(), np, nidx, eb.size());
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: gen_draco TWIN.gltf OUTDIR\n");
        return 2;
    }
    pg_scene *s = nullptr;
    pg_error err = {};
    if (pg_scene_load_gltf(argv[1], &s, &err) != PG_OK) {
        fprintf(stderr, "gen_draco: %s\n", err.msg);
        return 1;
    }
    int rc = emit(s, argv[2], "draco", false);
    if (!rc) rc = emit(s, argv[2], "draco_q", true);
    pg_scene_free(s);
    return rc;
}
