/* scene_gltf_internal.h - what the files of the glTF loader (scene/scene_gltf*.cpp, C++17 over
 * tinygltf) share: the load context, the error helpers, the geometry being built and the functions
 * one file calls in another. C++ only; not part of the scene library's interface (scene.h is).
 *
 *   scene_gltf.cpp             the load order (scene_gltf.cpp's header), the GLB container,
 *                              materials and textures, the hand-out, pg_scene_load_gltf
 *   scene_gltf_validate.cpp    JSON pre-validation, extensionsRequired and the implemented extensions
 *   scene_gltf_images.cpp      tinygltf's image callback (PNG/JPEG via stb_image, WebP via libwebp)
 *                              and file system, samplers, KHR_texture_transform
 *   scene_gltf_compressed.cpp  EXT_meshopt_compression and KHR_draco_mesh_compression decoding
 *   scene_gltf_accessors.cpp   accessors as views (sparse, decoded data) and their elements
 *   scene_gltf_mesh.cpp        attributes (quantized types), primitives -> vertices and indices
 *   scene_gltf_anim.cpp        animations, skins, morph targets (pg_scene_anim)
 *   scene_gltf_nodes.cpp       the node hierarchy, transforms, cameras
 *   scene_gltf_instancing.cpp  EXT_mesh_gpu_instancing: a node's instance transforms
 *   scene_gltf_texture_sources.cpp  which image a texture draws (EXT_texture_webp; the undecoded
 *                              KHR_texture_basisu, MSFT_texture_dds, EXT_texture_avif)
 *   scene_gltf_variants.cpp    KHR_materials_variants: the variants, each primitive's material
 *   scene_gltf_warnings.cpp    the warning lines (pg_scene.warnings)
 *   scene_gltf_util.cpp        what every step uses: messages, throwers, uri/path helpers,
 *                              accessor type sizes, bufferView bytes, matrices (a leaf)
 */
#ifndef PG_SCENE_GLTF_INTERNAL_H
#define PG_SCENE_GLTF_INTERNAL_H

#include "animation.h"
#include "scene.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace pg_gltf {

using json = nlohmann::json;

struct LoadFail {
    pg_result code;
    std::string msg;
};

/* scene_gltf_util.cpp */
std::string strf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
[[noreturn]] void fail(pg_result code, std::string msg);
[[noreturn]] void gfail(std::string msg);
std::string uri_desc(const std::string &uri);
std::string url_decode(const std::string &s);
std::string join_path(const std::string &dir, const std::string &file);

struct Ctx {
    std::string path;     /* as given (prefix of every message) */
    std::string base_dir; /* directory of the file ("." when none) */
    std::string dir_prefix;
    bool is_glb = false;
    size_t glb_bin_size = 0;
    bool glb_has_bin = false;
    json j;
    tinygltf::Model model;
    std::string image_err; /* set by the image callback */
    bool quantization = false; /* KHR_mesh_quantization in extensionsUsed */
    int want_scene = -1;       /* pg_scene_load_opts.gltf_scene */
    /* KHR_materials_variants (scene_gltf_variants.cpp): pg_scene_load_opts.gltf_variant, the
     * variant drawn (-1: the default materials), the file's variant names, and the chosen
     * variant's material of each (mesh, primitive) that maps it */
    std::string want_variant;
    int variant = -1;
    std::vector<std::string> variant_names;
    std::map<std::pair<int, int>, int> variant_material;
    int drawn_scene = -1;      /* the scenes[] index drawn (-1: every root node) */
    unsigned skipped_prims = 0;
    unsigned color1_prims = 0;   /* drawn primitives with COLOR_1.. (ignored) */
    unsigned texcoord2_prims = 0;/* drawn primitives with TEXCOORD_2.. (ignored) */
    unsigned morph_other_prims = 0; /* primitives whose morph targets move other attributes than
                                     * POSITION, NORMAL, TANGENT (TEXCOORD_n, COLOR_n: ignored) */
    std::vector<std::string> warnings; /* without the "PATH: " prefix */
    /* EXT_meshopt_compression: the compressed bufferViews (checked by prevalidate, decoded by
     * decode_meshopt into `decoded`, which view_bytes reads instead of the fallback buffer), and
     * the fallback buffers (never loaded: handed to tinygltf as 4-byte data URIs) */
    struct Meshopt {
        int view, buffer;
        uint64_t offset, length, stride, count;
        int mode;   /* 0 ATTRIBUTES, 1 TRIANGLES, 2 INDICES */
        int filter; /* 0 NONE, 1 OCTAHEDRAL, 2 QUATERNION, 3 EXPONENTIAL */
    };
    std::vector<Meshopt> meshopt;
    std::vector<char> view_is_meshopt;  /* per bufferView */
    std::vector<char> buffer_no_data;   /* per buffer: an EXT_meshopt_compression fallback */
    std::map<int, std::vector<unsigned char>> decoded;
    /* KHR_draco_mesh_compression: decoded accessor data (accessor index -> dense bytes in the
     * accessor's componentType/type) and the bufferView each came from; primitives done */
    std::map<int, std::vector<unsigned char>> draco_data;
    std::map<int, int> draco_view;
    std::map<std::pair<int, int>, bool> draco_done;
    std::map<int, int> draco_index_fix; /* indices accessor without bufferView -> Draco view */
    /* dense copies of sparse accessors (accessor index -> data), owned until hand-out */
    std::map<int, std::vector<unsigned char>> sparse_data;
    /* animation (scene_gltf_anim.cpp): the file has animations, skins or morph targets, so the
     * primitives that move keep their mesh-space vertices; per node: a TRS channel targets it; per
     * skin: its first joint slot */
    bool animated = false;
    std::vector<char> node_animated;
    std::vector<uint32_t> skin_slot_base;
    uint32_t joint_slots = 0;
    unsigned joints2_prims = 0; /* drawn skinned primitives with JOINTS_2.. (ignored: 8 joints a vertex) */
    bool influences8 = false;   /* a vertex weighs a joint of JOINTS_1 */
    unsigned unskinned_prims = 0; /* drawn primitives of a node with a skin but no JOINTS_0/WEIGHTS_0 */
    /* texture-source extensions (scene_gltf_texture_sources.cpp): per texture its EXT_texture_webp
     * image (-1: none) and the first undecoded extension naming an image (empty: none); per image
     * whether only undecoded extensions name it (not decoded: left empty), and how many were */
    std::vector<int> texture_webp;
    std::vector<std::string> texture_undecoded;
    std::vector<char> image_undecoded_only;
    std::vector<size_t> image_media_rewrite; /* images whose data URI tinygltf would refuse (prevalidate) */
    unsigned ignored_channels = 0;
    std::vector<std::string> ignored_pointers; /* KHR_animation_pointer targets not animated */
    std::vector<std::string> ignored_why;      /* other ignored channels: "animations[0].channels[1] (why)" */
    std::vector<std::string> duplicate_targets; /* "animations[0].channels[2] (as channels[0])" */
};

/* column-major 4x4, double */
struct Mat4 {
    double m[16];
};

struct Out {
    std::vector<pg_vertex> verts;
    std::vector<uint32_t> idx;
    std::vector<pg_primitive> prims;
    std::vector<uint32_t> prim_gltf_material; /* -1 (UINT32_MAX) = default material */
    std::vector<char> prim_has_uv1;           /* the primitive has TEXCOORD_1 */
    std::vector<char> prim_has_uv0;           /* the primitive has TEXCOORD_0 */
    std::vector<float> colors;                /* COLOR_0, 4 per vertex; empty when no primitive has it */
    std::vector<float> uv1;                   /* TEXCOORD_1, 2 per vertex; empty when none has it */
    /* animation (Ctx.animated only): per vertex the mesh-space vertex of a moving primitive and its
     * pg_anim_prim (PG_ANIM_STATIC: a static vertex, its local entry filled at hand-out); joint
     * slots and weights (8 per vertex, from the first skinned primitive on); morph deltas; each
     * morphing node's weights (node -> first weight) */
    std::vector<pg_vertex> local;
    std::vector<uint32_t> vertex_prim;
    std::vector<uint16_t> joints;
    std::vector<float> weights;
    std::vector<pg_anim_delta> deltas;
    std::vector<pg_anim_prim> aprims;
    std::vector<float> rest_weights;
    std::map<int, std::pair<uint32_t, uint32_t>> node_weights; /* node -> (base, count) */
};

struct Walker {
    Ctx &c;
    Out &o;
    std::vector<char> on_path;
    size_t visits = 0;
    size_t instances = 0; /* EXT_mesh_gpu_instancing instances drawn so far */
    bool count_only = false; /* the first walk: only adds up the bytes the second will bake */
    uint64_t planned = 0;

    /* scene_gltf_nodes.cpp; moving: an ancestor is animated (its primitives move with it) */
    void visit(int ni, const Mat4 &parent, int depth, bool moving = false);
};
/* scene_gltf_validate.cpp */
bool extension_implemented(const std::string &e);
void check_json_depth(const std::string &t);
const json *opt_object(const json &o, const char *key, const std::string &where);
uint64_t uint_field(const json &o, const char *key, const std::string &where, bool required,
                    uint64_t def = 0);
bool is_regular_file(const std::string &p, uint64_t *size);
void prevalidate(Ctx &c);

/* scene_gltf_variants.cpp: KHR_materials_variants read and checked, the chosen variant resolved
 * (before the node walk); the material primitive (mi, pi) draws (dflt: its own); the variants as
 * "0 'red', 1 'blue'" */
void variants_prepare(Ctx &c);
int variant_material(const Ctx &c, int mi, int pi, int dflt);
std::string variant_list_line(const Ctx &c);

/* scene_gltf_texture_sources.cpp: the texture-source extensions, before tinygltf parses the file */
void texture_sources(Ctx &c);

/* scene_gltf_images.cpp */
bool fs_file_exists(const std::string &abs, void *user);
bool fs_read_whole_file(std::vector<unsigned char> *out, std::string *err, const std::string &abs,
                        void *user);
std::string image_desc(const Ctx &c, int idx);
bool load_image_cb(tinygltf::Image *image, const int idx, std::string *, std::string *, int, int,
                   const unsigned char *bytes, int size, void *user);
std::string first_lines(const std::string &s);
pg_sampler_state sampler_state(const tinygltf::Sampler &sm);
bool texture_transform(const json &ti, const std::string &where, float m[6], int *tex_coord);

/* scene_gltf_compressed.cpp */
void decode_meshopt(Ctx &c);
void decode_draco(Ctx &c, int mi, int pi);

/* scene_gltf_util.cpp (needs Ctx) */
int type_comps(int t);
const char *ctype_name(int ct);
size_t ctype_size(int ct);
std::pair<const unsigned char *, size_t> view_bytes(const Ctx &c, int bvi, const std::string &who);
const int *find_attr(const tinygltf::Primitive &p, const char *name);
/* scene_gltf_accessors.cpp: accessors as range-checked views */
struct View {
    int index = -1;
    const unsigned char *base = nullptr;
    size_t stride = 0, count = 0;
    int type = 0, ctype = 0, ncomp = 0;
    bool normalized = false;
};
View get_view(Ctx &c, int ai);
/* element i as floats (glTF's conversions of normalized and integer types) */
void read_floats(const View &v, size_t i, float *out);
void view_floats(const View &v, size_t i, float *out);
/* element i of an index view (UNSIGNED_BYTE/SHORT/INT) */
uint32_t read_index(const View &v, size_t i);
const char *type_name(int t);
/* meshes[mi].primitives[pi] of nodes[ni] under its world transform M; `moving`: the node or an
 * ancestor is animated; instances: EXT_mesh_gpu_instancing transforms, each applied before M (the
 * primitive decoded once, placed once per instance) */
void emit_primitive(Ctx &c, Out &o, int mi, int pi, const Mat4 &M, int ni = -1, bool moving = false,
                    const std::vector<Mat4> *instances = nullptr);

/* scene_gltf_anim.cpp */
/* Before the walk: whether the file animates anything, the animated nodes, the skins' joint slots. */
void anim_prepare(Ctx &c);
/* A moving primitive's skin attributes and morph targets (its vertices at o.verts[base..base+n);
 * vertex i reads the accessors' element src[i], or i when src is NULL; src_n: their count). */
void anim_primitive(Ctx &c, Out &o, const tinygltf::Primitive &prim, int ni, size_t base, size_t n,
                    const uint32_t *src, size_t src_n, const std::string &pw);
/* After the walk: the scene's pg_scene_anim (NULL when no drawn primitive moves). */
pg_scene_anim *anim_hand_out(Ctx &c, const Out &o);

/* scene_gltf_util.cpp: matrices */
Mat4 mat_identity();
Mat4 mat_mul(const Mat4 &a, const Mat4 &b);
/* T * R * S with q normalised (a zero-length q fails naming rot_where) */
Mat4 mat_trs(const double t[3], const double q[4], const double s[3], const std::string &rot_where);

/* scene_gltf_nodes.cpp */

/* scene_gltf_instancing.cpp: how many EXT_mesh_gpu_instancing instances nodes[ni] has (0: no
 * extension), checked, and with out their transforms; *total counts the scene's instances
 * (PG_ERR_LIMIT past 2^20) */
size_t node_instances(Ctx &c, int ni, size_t *total, std::vector<Mat4> *out);
void camera_visit(const Ctx &c, int ni, const Mat4 &parent, std::vector<pg_scene_camera> &out);
/* one camera object of the file, checked (no node: placement left 0, gltf_node -1) */
pg_scene_camera camera_object(const Ctx &c, int ci);
/* KHR_lights_punctual: the lights of the nodes under ni, placed by their world transforms;
 * bad values fail naming "KHR_lights_punctual.lights[i].FIELD" or "nodes[n].extensions..." */
void light_visit(const Ctx &c, int ni, const Mat4 &parent, std::vector<pg_scene_light> &out);
/* one light object of the extension, checked (placement left 0) */
pg_scene_light light_object(const Ctx &c, int li);
/* PASSGRAPH_lights_table (docs/scenes.md): the root extension's point lights appended to out;
 * bad values fail naming "extensions.PASSGRAPH_lights_table.FIELD" or the record */
void table_lights(const Ctx &c, std::vector<pg_scene_light> &out);

/* scene_gltf_warnings.cpp */
std::string plural(size_t n, const char *one, const char *many);
void collect_warnings(Ctx &c);

} // namespace pg_gltf

#endif
