/* scene.h - CPU-side scene: one vertex/index soup with node transforms baked in, materials,
 * decoded textures with their mip chains, bounds, and features. Loaded from glTF 2.0
 * (core/scene/scene_gltf.cpp, a thin C++ shim over tinygltf) or generated (core/scene/scene_default.c).
 *
 * Ownership: a pg_scene owns all its arrays; free with pg_scene_free().
 */
#ifndef PG_SCENE_H
#define PG_SCENE_H

#include "pg_common.h"
#include "scene_features.h"

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pg_vertex {
    float position[3];
    float normal[3];
    float uv[2];
    float tangent[4]; /* xyz, w = handedness (+-1); zero when the primitive has none */
} pg_vertex;          /* 48 bytes, the GPU vertex layout */

typedef enum pg_alpha_mode { PG_ALPHA_OPAQUE = 0, PG_ALPHA_MASK = 1, PG_ALPHA_BLEND = 2 } pg_alpha_mode;

/* The texture slots of a material (index into pg_material.tex_coord / uv_transform). */
enum {
    PG_TEXSLOT_BASE = 0,
    PG_TEXSLOT_NORMAL = 1,
    PG_TEXSLOT_EMISSIVE = 2,
    PG_TEXSLOT_METALLIC_ROUGHNESS = 3,
    PG_TEXSLOT_OCCLUSION = 4,
    PG_TEXSLOT_COUNT = 5
};

typedef struct pg_material {
    char name[PG_NAME_MAX];
    float base_color[4];     /* factor, linear */
    int base_color_tex;      /* index into scene->textures, -1 if none */
    int normal_tex;          /* -1 if none */
    float normal_scale;
    pg_alpha_mode alpha_mode;/* OPAQUE, MASK (discard), BLEND (transparent pass) */
    float alpha_cutoff;      /* MASK: discard below (default 0.5) */
    float specular;          /* Blinn-Phong specular strength (from roughness/metallic), 0..1 */
    float shininess;         /* Blinn-Phong exponent */
    float metallic;          /* glTF metallicFactor, 0..1 (default 1) */
    float roughness;         /* glTF roughnessFactor, 0..1 (default 1) */
    int metallic_roughness_tex; /* linear texture: G roughness, B metallic (x the factors); -1 if none */
    int occlusion_tex;       /* linear texture: R occlusion; -1 if none */
    float occlusion_strength;/* occlusionTexture.strength, 0..1 (default 1) */
    bool unlit;              /* KHR_materials_unlit: the base colour is the result, no lighting */
    bool double_sided;
    float emissive[3];       /* emissiveFactor times KHR_materials_emissive_strength, linear */
    int emissive_tex;        /* sRGB texture, -1 if none */
    /* per slot (PG_TEXSLOT_*): which TEXCOORD_n the texture reads (0 or 1) */
    uint8_t tex_coord[PG_TEXSLOT_COUNT];
    /* per slot: KHR_texture_transform as a 2x3 row-major matrix, uv' = M * (u, v, 1):
     * {m00, m01, m02, m10, m11, m12}; identity when the slot has none */
    float uv_transform[PG_TEXSLOT_COUNT][6];
    bool has_uv_transform[PG_TEXSLOT_COUNT];
} pg_material;

/* glTF sampler state of a texture (one pg_texture per (image, colour space, sampler) use) */
typedef enum pg_wrap { PG_WRAP_REPEAT = 0, PG_WRAP_CLAMP = 1, PG_WRAP_MIRROR = 2 } pg_wrap;
typedef enum pg_mip_mode { PG_MIP_LINEAR = 0, PG_MIP_NEAREST = 1, PG_MIP_NONE = 2 } pg_mip_mode;
typedef struct pg_sampler_state {
    pg_wrap wrap_s, wrap_t;
    bool mag_nearest, min_nearest; /* false: linear */
    pg_mip_mode mip;               /* NONE: level 0 only (minFilter NEAREST / LINEAR) */
} pg_sampler_state;               /* all zero = glTF's default (repeat, linear, trilinear) */

typedef struct pg_mip {
    uint32_t width, height;
    uint8_t *rgba;            /* width*height*4 bytes, points into pg_texture.data */
} pg_mip;

#define PG_MAX_MIPS 16
typedef struct pg_texture {
    char name[PG_NAME_MAX];
    bool srgb;                /* base colour, emissive: sRGB; normal maps: linear */
    pg_sampler_state sampler;
    uint32_t n_mips;          /* full chain down to 1x1 */
    pg_mip mips[PG_MAX_MIPS];
    uint8_t *data;            /* one allocation holding all mips */
    size_t data_size;
} pg_texture;

typedef struct pg_primitive {
    uint32_t first_index;
    uint32_t index_count;
    int32_t vertex_offset;    /* added to each index */
    uint32_t material;        /* index into scene->materials */
    float bounds_min[3], bounds_max[3];
} pg_primitive;

/* A camera of the glTF file, placed by its node's world transform (one entry per camera NODE
 * reached in the default scene, in depth-first node order; a camera used by two nodes appears
 * twice). glTF cameras look down their local -Z with +Y up. */
typedef enum pg_camera_type { PG_CAMERA_PERSPECTIVE = 0, PG_CAMERA_ORTHOGRAPHIC = 1 } pg_camera_type;
typedef struct pg_scene_camera {
    char name[PG_NAME_MAX];      /* cameras[i].name, else "cameras[i]" */
    char node_name[PG_NAME_MAX]; /* nodes[n].name, else "nodes[n]" */
    int gltf_camera, gltf_node;  /* indices in the file */
    pg_camera_type type;
    float yfov_rad;              /* perspective */
    float aspect_ratio;          /* perspective; 0 when the file gives none */
    float xmag, ymag;            /* orthographic */
    float znear;
    float zfar;                  /* 0 = infinite (perspective without zfar) */
    float position[3];           /* world */
    float forward[3], up[3];     /* world, unit length (node -Z and +Y, orthonormalised) */
} pg_scene_camera;

/* A KHR_lights_punctual light placed by its node's world transform (one entry per node that
 * references a light, reached in the drawn scene, depth-first; a light used by two nodes appears
 * twice). The node's scale moves and turns it but scales neither its range nor its intensity
 * (the extension's rule). */
typedef enum pg_light_type { PG_LIGHT_POINT = 0, PG_LIGHT_SPOT = 1, PG_LIGHT_DIRECTIONAL = 2 } pg_light_type;
/* The brightest light passgraph takes, colour x intensity in the largest channel: a point or spot
 * light (candela), and a directional one (lux: it is stored as a point light 1e15 units away, its
 * colour times 1e30, which must stay a float when a few of them are summed; the sun gives about
 * 1.2e5 lux). The loaders refuse brighter lights; an animated value is clamped. Past 1.07e9 lux
 * the sun's record overflowed, and the lightcut dropped it while RIS halved it. */
#define PG_LIGHT_MAX_CANDELA 1e30
#define PG_LIGHT_MAX_LUX 1e7
typedef struct pg_scene_light {
    char name[PG_NAME_MAX];      /* lights[i].name, else "KHR_lights_punctual.lights[i]" */
    int gltf_light, gltf_node;   /* indices in the file */
    pg_light_type type;
    float color[3];              /* linear RGB, the file's colour (default white) */
    float intensity;             /* candela (point, spot) or lux (directional); default 1 */
    float range;                 /* 0: none given (infinite reach in the extension) */
    float inner_cone, outer_cone;/* spot: radians, 0 <= inner < outer <= pi/2 */
    float position[3];           /* world */
    float direction[3];          /* world, unit: where the light points (the node's -Z) */
} pg_scene_light;

typedef struct pg_scene {
    char name[PG_NAME_MAX];
    char path[PG_PATH_MAX];   /* "default" for the generated scene */
    pg_vertex *vertices;
    uint32_t n_vertices;
    /* Optional per-vertex streams, n_vertices entries each, NULL when no drawn primitive has the
     * attribute (then no shader path reads it): COLOR_0 as linear RGBA (white where a primitive
     * has none), TEXCOORD_1 (a copy of TEXCOORD_0 where a primitive has none; warned when its
     * material reads set 1). */
    float (*colors)[4];
    float (*uv1)[2];
    uint32_t *indices;        /* 16-bit glTF indices are widened */
    uint32_t n_indices;
    pg_primitive *primitives;
    uint32_t n_primitives;
    pg_material *materials;
    uint32_t n_materials;
    pg_texture *textures;
    uint32_t n_textures;
    float bounds_min[3], bounds_max[3];
    pg_scene_features features; /* light_count left 0 here */
    bool gltf_materials;        /* the materials are a glTF file's metallic-roughness materials:
                                   features.auto_shading is PG_SHADING_PBR (else Lambert) */
    pg_scene_camera *cameras;   /* owned (freed by pg_scene_free); NULL when n_cameras == 0;
                                   the built-in atrium has none */
    uint32_t n_cameras;
    pg_scene_light *lights;     /* the file's KHR_lights_punctual lights; owned; NULL when none */
    uint32_t n_lights;
    /* What the loader could not draw as the file asks, one line each, "PATH: cause: what is
     * drawn instead" (e.g. "x.gltf: 2 skins ignored: rendered in bind pose"); in load order, one
     * line per kind of feature (one per extensionsUsed entry, the 17th on summed up in one line). Owned by the scene: warnings[i] and the array are
     * malloc'd and freed by pg_scene_free(); NULL / 0 when there are none (always for the default
     * scene). The library never prints them: the tools print each once per loaded scene
     * (pg_scene_print_warnings). */
    char **warnings;
    uint32_t n_warnings;
    /* glTF `scenes`: how many the file has, and which one is drawn (-1: none was, every root node
     * is: a file without `scenes`) with its name ("scenes[i]" when it has none); 0 / -1 for the
     * built-in atrium */
    uint32_t n_gltf_scenes;
    int gltf_scene;
    bool gltf_scene_chosen;   /* picked by pg_scene_load_opts.gltf_scene, not the file's default */
    bool gltf_scene_named;    /* the file has a "scene" key (its default); else scenes[0] is drawn */
    char gltf_scene_name[PG_NAME_MAX];
#define PG_SCENE_GLTF_SCENE_NAMES 16
    char gltf_scene_names[PG_SCENE_GLTF_SCENE_NAMES][PG_NAME_MAX]; /* the first 16 scenes' names
                                                                    * ("scenes[i]" when unnamed) */
    /* KHR_materials_variants: how many the file names, which one is drawn (-1: the default
     * materials) and its name, and the first ones as "0 'red', 1 'blue'" (for
     * pg_scene_variant_line) */
    uint32_t n_gltf_variants;
    int gltf_variant;
    char gltf_variant_name[PG_NAME_MAX];
    char gltf_variant_list[512];
#define PG_SCENE_VARIANT_NAMES 16
    char gltf_variant_names[PG_SCENE_VARIANT_NAMES][PG_NAME_MAX]; /* the first 16 variants' names */
    /* The environment light (environment.h): set by the tools after loading (--environment, or the
     * neutral default sky for a glTF file without lights: pg_scene_set_environment), never by the
     * loaders; owned; NULL when there is none (features.has_environment). */
    struct pg_environment *environment;
    /* The file's animation, skins and morph targets (animation.h): NULL when no drawn primitive
     * moves (features.has_animation). The vertices above are the rest pose (or the pose
     * pg_scene_pose put there); the geometry_animate pass deforms anim->local on the GPU. */
    struct pg_scene_anim *anim;
} pg_scene;

/* What a load may choose (pg_scene_load_ex). */
typedef struct pg_scene_load_opts {
    int gltf_scene; /* the glTF scene to draw: -1 = the file's `scene`, else scenes[0] (the
                       default); N >= 0: scenes[N] (out of range: PG_ERR_INVALID_ARG naming the
                       count; refused for the built-in atrium) */
    const char *gltf_variant; /* KHR_materials_variants: the variant to draw, an index or a name;
                                 NULL or "": the default materials (unknown: PG_ERR_INVALID_ARG
                                 listing the file's variants; refused for the built-in atrium) */
} pg_scene_load_opts;

typedef struct pg_camera {
    float position[3];
    float target[3];
    float up[3];
    float fov_y_deg;
    float near_z, far_z;
    float aspect;             /* width / height */
    float ortho_height;       /* > 0: orthographic, the full view height in scene units (2 x the
                                 glTF ymag; the width follows the aspect); 0: perspective */
} pg_camera;

/* Loads a .gltf (JSON + external/embedded buffers and images) or .glb. Errors name the file and
 * the glTF object, e.g. "x.gltf: accessors[4]: count 100 (...) exceeds bufferView 2 (48 bytes)":
 * PG_ERR_IO when the file itself cannot be read, PG_ERR_PARSE for JSON syntax / a broken GLB
 * container, PG_ERR_GLTF for content (missing buffer or image files, ranges, types, indices,
 * non-finite values, cycles, undecodable, non-PNG/JPEG or > 16384 px images, glTF 1.0, an
 * extensionsRequired entry other than KHR_texture_transform, bad KHR_texture_transform values), PG_ERR_LIMIT past 2^32 vertices. A directory is
 * "PATH: is a directory (expected a glTF 2.0 .gltf/.glb file)" (PG_ERR_IO); a file that is neither
 * JSON nor GLB (an .obj, say) is "PATH: not a glTF 2.0 file (passgraph reads .gltf and .glb
 * only)" (PG_ERR_PARSE). Features the loader does not draw are listed in scene->warnings (see
 * the README "Scenes" table): skins and morph targets (bind pose / base geometry), unimplemented
 * extensions in extensionsUsed, alphaMode BLEND (opaque), COLOR_1+, TEXCOORD_2+ and texCoord >= 2,
 * sampler values outside the glTF enums, emission, occlusion and metallic-roughness textures,
 * point/line primitives. Sparse accessors are applied. COLOR_0 fills scene->colors, TEXCOORD_1
 * scene->uv1 (when a texture reads it), textureInfo texCoord / KHR_texture_transform fill
 * pg_material.tex_coord / uv_transform, glTF samplers fill pg_texture.sampler.
 * Details (core/scene/scene_gltf.cpp header): the node hierarchy of `scene` (else scenes[0], else every
 * root node) is baked into the vertices (normals by the inverse-transpose, a mirroring transform
 * flips the winding and the tangent handedness); one pg_primitive per drawn (node, primitive)
 * pair, its indices local (add vertex_offset); TRIANGLES/STRIP/FAN are drawn, points and lines
 * skipped with a line in scene->warnings; missing normals are computed (area-weighted), missing tangents
 * are computed for normal-mapped materials; materials keep their glTF indices (a white "default"
 * material is appended for primitives without one); textures are decoded to RGBA8 with full mip
 * chains, one pg_texture per (image, sRGB-or-linear, sampler state) use. name = the file stem. Camera nodes of
 * the same hierarchy fill scene->cameras (pg_scene_camera; bad camera objects are PG_ERR_GLTF
 * naming "cameras[i].perspective.yfov" etc.). */
pg_result pg_scene_load_gltf(const char *path, pg_scene **out, pg_error *err);
/* The same with load options (NULL: the defaults). */
pg_result pg_scene_load_gltf_ex(const char *path, const pg_scene_load_opts *opts, pg_scene **out, pg_error *err);
/* The built-in atrium (columns, arches, several procedural materials, tens of thousands of
 * triangles). Deterministic. */
pg_result pg_scene_create_default(pg_scene **out, pg_error *err);
/* "default" -> generated scene, else glTF. */
pg_result pg_scene_load(const char *path_or_default, pg_scene **out, pg_error *err);
pg_result pg_scene_load_ex(const char *path_or_default, const pg_scene_load_opts *opts, pg_scene **out,
                           pg_error *err);
/* One line saying which glTF scene is drawn when the file has several ("x.gltf has 3 scenes;
 * drawing scene 0 'day' (the file's default); --gltf-scene N draws another"), else "" (returns
 * false). */
bool pg_scene_choice_line(const pg_scene *scene, char *buf, size_t size);
/* One line saying which material variant is drawn when the file has KHR_materials_variants
 * ("x.gltf has 3 material variants (0 'red', 1 'blue', 2 'green'); drawing the default materials;
 * --variant N|NAME draws one"), else "" (returns false). */
bool pg_scene_variant_line(const pg_scene *scene, char *buf, size_t size);
void pg_scene_free(pg_scene *scene);
/* Gives the scene an environment light (owned from then on; NULL removes it) and sets
 * features.has_environment; call before pg_scene_gpu_create. */
void pg_scene_set_environment(pg_scene *scene, struct pg_environment *env);
/* Appends a copy of `line` to scene->warnings (PG_ERR_OOM when it cannot). */
pg_result pg_scene_add_warning(pg_scene *scene, const char *line, pg_error *err);
/* Writes each warning as "PREFIXwarning: LINE\n" to f (prefix e.g. "passgraph render: ", may be
 * NULL). */
void pg_scene_print_warnings(const pg_scene *scene, const char *prefix, FILE *f);

/* Builds a full mip chain (box filter; sRGB textures are filtered in linear space) from an
 * RGBA8 image it copies. */
pg_result pg_texture_init(pg_texture *tex, const char *name, const uint8_t *rgba, uint32_t w,
                          uint32_t h, bool srgb, pg_error *err);
/* A material with glTF's defaults: white, no textures, opaque, cutoff 0.5, normal scale 1, no
 * emissive, TEXCOORD_0 and identity transforms everywhere, specular 0.04, shininess 1. */
void pg_material_init(pg_material *m, const char *name);
/* The texture of material slot PG_TEXSLOT_* (index into scene->textures), -1 when it has none. */
int pg_material_slot_texture(const pg_material *m, int slot);
void pg_texture_release(pg_texture *tex);
/* KHR_texture_transform's offset, rotation (radians, counter-clockwise in UV space) and scale as
 * the 2x3 row-major matrix M = T * R * S of pg_material.uv_transform:
 *   { sx cos r, sy sin r, ox,  -sx sin r, sy cos r, oy }  (computed in double) */
void pg_material_uv_transform(const double offset[2], double rotation, const double scale[2], float m[6]);
/* Blinn-Phong's specular strength and exponent from glTF metallic and roughness (clamped to [0, 1];
 * NaN reads as glTF's default 1): specular = 0.04 + 0.5 (1 - r)(1 - m), shininess = 2 / (r^4 + 1e-4) - 2
 * in [1, 512] */
void pg_material_specular_from(double metallic, double roughness, float *specular, float *shininess);

/* ---- helpers shared by the loaders (glTF shim, default scene); usable by tools ----
 * Indices are local to verts (0..n_verts-1); out-of-range triangles are skipped. */
/* Area-weighted smooth vertex normals over the triangles that share each vertex; a vertex no
 * triangle gives a normal gets (0,1,0). */
void pg_mesh_compute_normals(pg_vertex *verts, uint32_t n_verts, const uint32_t *indices,
                             uint32_t n_indices);
/* Tangents from positions, normals and UVs in the glTF convention: tangent.xyz = direction of
 * increasing u, bitangent = cross(N, T.xyz) * w = direction of DEcreasing v (up in the image, as
 * glTF's UV origin is the top-left). Per-triangle dP/du, dP/dv accumulated per vertex weighted by
 * triangle area, then Gram-Schmidt against the normal; w = +-1 from the handedness of the
 * accumulated bitangent. Normals must be set (unit length) first. */
void pg_mesh_compute_tangents(pg_vertex *verts, uint32_t n_verts, const uint32_t *indices,
                              uint32_t n_indices);
/* Recomputes each primitive's bounds (from the vertices its indices reach), the scene bounds and
 * the features (from the materials the primitives with triangles actually use). */
void pg_scene_finalize(pg_scene *scene);

/* A sensible view of the whole scene from its bounds: position (min.x + 0.2*size.x,
 * min.y + 0.18*size.y, center.z), looking along +X at (max.x, same height, center.z), up +Y,
 * fov_y 60 deg, near = max(0.01, 0.001*diagonal), far = 2*diagonal. For the atrium-like scenes
 * this stands inside the nave looking down its length. The tools use it for the built-in atrium
 * only (tools/app.h pg_scene_default_view); loaded glTF get pg_camera_frame_object or a glTF camera. */
pg_camera pg_camera_default_for_scene(const pg_scene *scene, float aspect);

/* Object framing, the default for loaded glTF without a camera (README "Scenes"), fov_y 45 deg:
 * - direction: a flat scene (its thinnest bounds extent under 0.1 x the middle one: a plate, not a
 *   rod) is seen from the
 *   front, along that axis from the side its triangles' area-weighted normals face (a floor from
 *   above with -Z at the top of the image; a wall or panel with +Y up); any other from the 3/4
 *   view (sin 35 cos 25, sin 25, cos 35 cos 25) (from above, front = +Z as glTF models face), up +Y;
 * - distance: every vertex (the box corners of a scene without vertices; the unit box without
 *   bounds) projects inside 90% of both the vertical and horizontal half-angles, and the target is
 *   moved so the vertices' screen box is centred (five correction steps, within 1% of the image);
 * - near / far hug the vertices' depth range (5% padding), so depth precision follows the object.
 * out_radius gets r = half the box diagonal (1 without bounds), out_distance d (camera to
 * target); both may be NULL. */
pg_camera pg_camera_frame_object(const pg_scene *scene, float aspect, float *out_radius,
                                 float *out_distance);

/* The pg_camera of scene->cameras[index] for an output of `aspect` (width / height): perspective
 * keeps yfov (the file's aspectRatio is not forced: the output size decides the width), znear,
 * zfar; an infinite zfar becomes the distance from the camera to the farthest corner of the
 * scene bounds times 2 (at least 1000 * znear). Orthographic: ortho_height = 2 ymag (xmag is not
 * forced either: the output aspect decides the width), znear, zfar (a znear of 0, which glTF
 * allows, becomes 1e-6 zfar: the depth slices of the clusters are logarithmic). */
pg_result pg_camera_from_scene(const pg_scene *scene, uint32_t index, float aspect, pg_camera *out,
                               pg_error *err);

/* Finds a camera by "N" (index into scene->cameras) or a name (camera name first, then node
 * name). Not found: PG_ERR_INVALID_ARG "--camera X: no such camera in FILE; available: 0 'a'
 * (node 'n'), 1 ... , or auto" (or "the scene has no cameras; use --camera auto"). */
pg_result pg_scene_find_camera(const pg_scene *scene, const char *spec, uint32_t *out_index,
                               pg_error *err);

/* Column-major 4x4 matrices (element row r, column c at m[c*4 + r]; p' = M * p).
 * pg_camera_view: right-handed look-at; camera space +X right, +Y up, looking down -Z.
 * pg_camera_proj: perspective to Vulkan clip space: y_ndc = -1 is the TOP of the image (view +Y
 * is negated so the image is upright with a positive-height viewport), z_ndc = 0 at near_z and 1
 * at far_z (standard depth, not reversed), w_clip = -z_view. With ortho_height > 0 the same
 * conventions orthographically: x_ndc = x / (h/2 * aspect), y_ndc = -y / (h/2),
 * z_ndc = (-z - near) / (far - near), w_clip = 1 (frame uniforms clip.w = 1 tells the shaders).
 * pg_mat4_mul: out = a * b (out may alias a or b).
 * pg_mat4_invert: general inverse (double precision cofactors); returns false and leaves out
 * untouched when m is singular (|det| <= 1e-12 * max|m_ij|^4) or not finite. */
void pg_camera_view(const pg_camera *cam, float out_view[16]);
void pg_camera_proj(const pg_camera *cam, float out_proj[16]);
/* The depth planes pg_camera_proj uses: near (0.01 when not > 0), far (1000 x near when not above
 * it). The frame uniforms' clip planes are these. */
void pg_camera_depth_planes(const pg_camera *cam, float *near_z, float *far_z);
/* A perspective camera's near plane raised to PG_NEAR_FAR_MIN x the distance of the scene's farthest
 * point (its bounds' farthest corner, within far): a float depth (standard Z) of 1 - near / z differs
 * from the cleared 1 only while near / z is above 2^-25 (3e-8), so a glTF znear of 1e-8 with zfar 100
 * drew nothing; 1e-6 keeps about 16 depth steps at the farthest point. Returns true when it raised it. */
#define PG_NEAR_FAR_MIN 1e-6
bool pg_camera_raise_near(pg_camera *cam, const pg_scene *scene);
void pg_mat4_mul(const float a[16], const float b[16], float out[16]);
bool pg_mat4_invert(const float m[16], float out[16]);

#ifdef __cplusplus
}
#endif
#endif
