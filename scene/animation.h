/* animation.h - a glTF file's animation on the CPU: its node hierarchy, skins, morph targets and
 * animation channels as the loader keeps them (pg_scene.anim), the pose at a time (node world
 * matrices, joint matrices, morph weights), and the deformed vertices: the CPU twin of
 * shaders/animate_geometry.comp, which the geometry_animate pass runs every frame on the GPU.
 *
 * The rules are the glTF 2.0 specification's (sections 3.7 and 3.11):
 * - a node's local matrix is T * R * S (or its `matrix`, which animation cannot target);
 * - rotations interpolate by spherical linear interpolation (the shorter arc), LINEAR values
 *   linearly, STEP holds the key at or before the time, CUBICSPLINE is the Hermite spline of the
 *   specification's appendix (tangents scaled by the key interval; rotations normalised after);
 *   before the first key a channel holds its first value, after the last its last value;
 * - a skinned vertex is sum_k w_k * (world(joint_k) * inverseBind_k) * p over up to 8 joints
 *   (JOINTS_0/WEIGHTS_0, then JOINTS_1/WEIGHTS_1): the skinned mesh node's own transform is ignored;
 *   weights are normalised at load over all 8 (a vertex whose weights sum to 0 follows its first
 *   joint);
 * - morph targets add sum_t w_t * delta_t to POSITION, NORMAL and TANGENT (xyz) before skinning or
 *   the node transform; the weights are the node's `weights`, else the mesh's, else 0, animated by
 *   "weights" channels;
 * - normals go by the cofactor matrix of the (blended) upper 3x3 times the sign of its determinant,
 *   tangents by the upper 3x3, both renormalised; a mirroring matrix flips the tangent's handedness.
 *
 * Playing: time t (seconds, --time) loops over [0, end] of the played animation (end = its last key
 * time over all its channels); the played animation is one of the file's (PG_ANIM_FIRST: the first,
 * the default), every one at once (PG_ANIM_ALL, each looping over the longest), or none
 * (PG_ANIM_NONE: the rest pose with the nodes' own transforms and default weights).
 */
#ifndef PG_ANIMATION_H
#define PG_ANIMATION_H

#include "pg_common.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { PG_ANIM_NONE = -1, PG_ANIM_ALL = -2, PG_ANIM_FIRST = 0 };
#define PG_ANIM_STATIC 0xFFFFFFFFu /* pg_scene_anim.vertex_prim of a vertex that never moves */
#define PG_ANIM_MAX_JOINT_SLOTS 65535u /* joint slots are 16-bit per vertex */
#define PG_ANIM_MAX_INFLUENCES 8      /* joints per vertex: JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1 */

typedef enum pg_anim_path {
    PG_ANIM_TRANSLATION = 0,
    PG_ANIM_ROTATION = 1,
    PG_ANIM_SCALE = 2,
    PG_ANIM_WEIGHTS = 3,
    /* KHR_animation_pointer on a KHR_lights_punctual light's property (pg_anim_channel.node is the
     * light's index in the extension's array): /extensions/KHR_lights_punctual/lights/N/... */
    PG_ANIM_LIGHT_COLOR = 4,     /* color (width 3) */
    PG_ANIM_LIGHT_INTENSITY = 5, /* intensity */
    PG_ANIM_LIGHT_RANGE = 6,     /* range */
    PG_ANIM_SPOT_INNER = 7,      /* spot/innerConeAngle */
    PG_ANIM_SPOT_OUTER = 8,      /* spot/outerConeAngle */
    /* KHR_animation_pointer on a camera's projection (node is the camera's index in "cameras"):
     * /cameras/N/perspective/... or /cameras/N/orthographic/... */
    PG_ANIM_CAM_YFOV = 9,        /* perspective/yfov */
    PG_ANIM_CAM_ASPECT = 10,     /* perspective/aspectRatio */
    PG_ANIM_CAM_XMAG = 11,       /* orthographic/xmag */
    PG_ANIM_CAM_YMAG = 12,       /* orthographic/ymag */
    PG_ANIM_CAM_ZNEAR = 13,      /* perspective/znear or orthographic/znear */
    PG_ANIM_CAM_ZFAR = 14,       /* perspective/zfar or orthographic/zfar */
    /* KHR_animation_pointer on a material's property (node is the material's index in
     * "materials"): /materials/N/... */
    PG_ANIM_MAT_BASE_COLOR = 15, /* pbrMetallicRoughness/baseColorFactor (width 4) */
    PG_ANIM_MAT_METALLIC = 16,   /* pbrMetallicRoughness/metallicFactor */
    PG_ANIM_MAT_ROUGHNESS = 17,  /* pbrMetallicRoughness/roughnessFactor */
    PG_ANIM_MAT_EMISSIVE = 18,   /* emissiveFactor (width 3) */
    PG_ANIM_MAT_EMISSIVE_STRENGTH = 19, /* extensions/KHR_materials_emissive_strength/emissiveStrength */
    PG_ANIM_MAT_ALPHA_CUTOFF = 20, /* alphaCutoff */
    PG_ANIM_MAT_NORMAL_SCALE = 21, /* normalTexture/scale */
    PG_ANIM_MAT_OCCLUSION_STRENGTH = 22, /* occlusionTexture/strength */
    /* <slot's textureInfo>/extensions/KHR_texture_transform/offset (width 2), rotation, scale
     * (width 2): path PG_ANIM_MAT_UV + 3 x slot (PG_TEXSLOT_*) + 0, 1 or 2 */
    PG_ANIM_MAT_UV = 23,
    PG_ANIM_MAT_LAST = PG_ANIM_MAT_UV + 3 * PG_TEXSLOT_COUNT - 1
} pg_anim_path;
/* a light's animatable properties in a pose: colour r g b, intensity, range, inner and outer cone */
#define PG_ANIM_LIGHT_PROPS 7
/* a camera's: yfov, aspectRatio, xmag, ymag, znear, zfar */
#define PG_ANIM_CAMERA_PROPS 6
/* a material's: base colour r g b a, metallic, roughness, emissive r g b, emissive strength, alpha
 * cutoff, normal scale, occlusion strength (PG_ANIM_MAT_BASE_COLOR + k: the offset of path k is
 * pg_anim_material_offset), then per texture slot offset u v, rotation, scale u v */
#define PG_ANIM_MAT_UV_BASE 13
#define PG_ANIM_MATERIAL_PROPS (PG_ANIM_MAT_UV_BASE + 5 * PG_TEXSLOT_COUNT)
typedef enum pg_anim_interp { PG_INTERP_LINEAR = 0, PG_INTERP_STEP = 1, PG_INTERP_CUBICSPLINE = 2 } pg_anim_interp;

typedef struct pg_anim_channel {
    uint32_t node;          /* the glTF node index (pg_scene_anim.nodes) */
    pg_anim_path path;
    pg_anim_interp interp;
    uint32_t n_keys;        /* >= 1 */
    uint32_t width;         /* floats per value: 3 (T, S), 4 (R, x y z w), the node's weight count */
    float *times;           /* n_keys, non-decreasing, finite */
    float *values;          /* n_keys * width; CUBICSPLINE: n_keys * 3 * width (in-tangent, value,
                               out-tangent per key) */
} pg_anim_channel;

typedef struct pg_animation {
    char name[PG_NAME_MAX]; /* animations[i].name, else "animations[i]" */
    pg_anim_channel *channels;
    uint32_t n_channels;
    float end;              /* the last key time over its channels (0: a still pose) */
} pg_animation;

typedef struct pg_anim_node {
    int32_t parent;         /* -1: a root */
    float translation[3], rotation[4], scale[3]; /* rest TRS (rotation x y z w) */
    bool has_matrix;        /* given by `matrix` (then TRS unused, not animatable) */
    float matrix[16];       /* column-major */
    uint32_t weight_base, n_weights; /* its morph weights in the pose (n_weights 0: none) */
} pg_anim_node;

typedef struct pg_anim_skin {
    uint32_t n_joints;
    uint32_t *joints;          /* node indices */
    float (*inverse_bind)[16]; /* n_joints, column-major (identity when the file has none) */
    uint32_t slot_base;        /* its first joint matrix in pg_anim_pose.joints */
} pg_anim_skin;

/* One deformed primitive: its vertices [first_vertex, first_vertex + n_vertices) of the scene. */
typedef struct pg_anim_prim {
    uint32_t node;             /* rigid: the node whose world matrix moves it */
    int32_t skin;              /* -1: rigid, else pg_scene_anim.skins index */
    uint32_t first_vertex, n_vertices;
    uint32_t n_targets;        /* morph targets: deltas[target_base + t * n_vertices + i] */
    uint32_t target_base;
    uint32_t weight_base;      /* its node's weights in the pose */
    uint32_t wound_mirrored;   /* rigid: 1 while scene->indices hold its triangles wound for a
                                * mirroring world matrix (det < 0): its node's at load (scene.h),
                                * then the last pg_scene_pose's */
} pg_anim_prim;

typedef struct pg_anim_delta {
    float position[4], normal[4], tangent[4]; /* xyz, w 0 */
} pg_anim_delta; /* 48 bytes, the GPU layout */

typedef struct pg_scene_anim {
    pg_anim_node *nodes;       /* every node of the file */
    uint32_t n_nodes;
    pg_anim_skin *skins;
    uint32_t n_skins, n_joint_slots;
    pg_animation *animations;
    uint32_t n_animations;
    pg_anim_prim *prims;
    uint32_t n_prims;
    float *rest_weights;       /* n_weights: each morphing node's default weights */
    uint32_t n_weights;
    uint32_t n_vertices;       /* the scene's */
    pg_vertex *local;          /* n_vertices: a deformed vertex in its mesh's space; a static one as
                                  the scene has it (world) */
    uint32_t *vertex_prim;     /* n_vertices: index into prims, or PG_ANIM_STATIC */
    uint16_t (*joints)[PG_ANIM_MAX_INFLUENCES]; /* n_vertices absolute joint slots; NULL without skins */
    float (*weights)[PG_ANIM_MAX_INFLUENCES];   /* n_vertices, normalised over all 8; NULL without skins */
    uint32_t influences;       /* 4, or 8 when a vertex has a non-zero weight in JOINTS_1/WEIGHTS_1 */
    pg_anim_delta *deltas;
    uint32_t n_deltas;
    uint32_t n_lights;         /* the file's KHR_lights_punctual lights */
    uint8_t *light_animated;   /* n_lights: 1 where a channel animates the light's properties */
    float (*light_rest)[PG_ANIM_LIGHT_PROPS]; /* n_lights: the file's values (of the animated ones) */
    uint32_t n_cameras;        /* the file's cameras */
    uint8_t *camera_animated;  /* n_cameras: 1 where a channel animates the camera's projection */
    float (*camera_rest)[PG_ANIM_CAMERA_PROPS]; /* n_cameras: the file's values (of the animated ones) */
    uint32_t n_materials;      /* the file's materials */
    uint32_t *material_animated; /* n_materials: bit k set where a channel animates path
                                    PG_ANIM_MAT_BASE_COLOR + k of the material (0: none) */
    float (*material_rest)[PG_ANIM_MATERIAL_PROPS]; /* n_materials: the file's values (of the animated ones) */
    uint32_t n_animated_materials;
} pg_scene_anim;

typedef struct pg_anim_pose {
    float *node_world;  /* 16 per node */
    float *joints;      /* 16 per joint slot: world(joint) x inverseBind */
    float *weights;     /* n_weights */
    float (*lights)[PG_ANIM_LIGHT_PROPS]; /* n_lights: each light's properties at the pose's time */
    float (*cameras)[PG_ANIM_CAMERA_PROPS]; /* n_cameras: each camera's projection at the pose's time */
    float (*materials)[PG_ANIM_MATERIAL_PROPS]; /* n_materials: each material's properties at the pose's time */
    struct {            /* pg_anim_pose_eval's working memory, allocated with the pose: no allocation a frame */
        float (*t)[3], (*r)[4], (*s)[3]; /* per node TRS */
        float *local;                     /* 16 per node */
        uint32_t *stack;
        uint8_t *done;
    } work;
} pg_anim_pose;

void pg_scene_anim_free(pg_scene_anim *a);

/* A pose's arrays and working memory, sized for `a`: evaluating it then allocates nothing. */
pg_result pg_anim_pose_alloc(const pg_scene_anim *a, pg_anim_pose *out, pg_error *err);
void pg_anim_pose_release(pg_anim_pose *p);
/* The pose at `time` seconds of animation `animation` (an index, PG_ANIM_ALL or PG_ANIM_NONE; an
 * index out of range is the rest pose), into a pose allocated for `a`. */
void pg_anim_pose_eval(const pg_scene_anim *a, int animation, double time, pg_anim_pose *pose);
/* The time within the played animation's loop that `time` maps to. */
double pg_anim_local_time(const pg_scene_anim *a, int animation, double time);
/* The deformed scene vertices under the pose (n_vertices), the CPU twin of
 * shaders/animate_geometry.comp. */
void pg_anim_deform(const pg_scene_anim *a, const pg_anim_pose *pose, pg_vertex *out);
/* Whether `pose` mirrors moving primitive `prim`: a rigid primitive whose node's world matrix has
 * det < 0 (an animated scale through -1 makes it change). Where this differs from the winding its
 * indices hold (pg_anim_prim.wound_mirrored, as uploaded), its triangles face the other way: the
 * rasterizers swap their front face (renderer/scene_gpu_anim.h), the CPU rewinds them
 * (pg_scene_pose). Always false for a skinned primitive: the specification leaves the winding of
 * a skin's mirroring joints open. */
bool pg_anim_prim_mirrored(const pg_scene_anim *a, const pg_anim_pose *pose, uint32_t prim);

/* Finds --animation SPEC: "none", "all", an index or a name. Not found: PG_ERR_INVALID_ARG naming
 * what the file has. */
pg_result pg_anim_find(const pg_scene_anim *a, const char *spec, int *out, pg_error *err);
/* One line for --explain: what plays ("animation 0 'Walk' of 3 (1.67 s loop) at t = 0.5 s; 1 skin,
 * 2 morph targets") or "" when the scene has no animation (returns false). */
bool pg_anim_describe(const pg_scene *scene, int animation, double time, char *buf, size_t size);

/* KHR_animation_pointer on lights: whether a channel animates light `gltf_light`'s properties, and
 * L's colour, intensity, range and spot cones set from the pose (left as they are, false, when
 * none is animated). The values are kept valid: colour and intensity >= 0, a range > 0, cones with
 * 0 <= inner < outer <= pi/2. */
bool pg_anim_light_animated(const pg_scene_anim *a, int gltf_light);
bool pg_anim_light_props(const pg_scene_anim *a, const pg_anim_pose *pose, pg_scene_light *L);
/* Likewise for a camera's projection: yfov and aspectRatio (perspective), xmag and ymag
 * (orthographic), znear and zfar, kept valid (yfov in (0, pi), magnifications not 0, znear > 0 for a
 * perspective camera, zfar 0 (infinite, perspective) or past znear). */
bool pg_anim_camera_animated(const pg_scene_anim *a, int gltf_camera);
bool pg_anim_camera_props(const pg_scene_anim *a, const pg_anim_pose *pose, pg_scene_camera *C);

/* Likewise for a material (materials[gltf_material] of the file): its factors and texture transforms
 * from the pose into M, kept valid (base colour, metallic, roughness, alpha cutoff, occlusion strength
 * in [0, 1]; emissive, its strength and normal scale finite and >= 0 where the spec says so), the
 * emissive as factor x strength and each slot's transform as the loader builds it
 * (pg_material_uv_transform); Blinn-Phong's specular and shininess follow metallic and roughness
 * (pg_material_specular_from). */
bool pg_anim_material_animated(const pg_scene_anim *a, int gltf_material);
bool pg_anim_material_props(const pg_scene_anim *a, const pg_anim_pose *pose, int gltf_material, pg_material *M);
/* the offset in a material's properties of path p (PG_ANIM_MAT_*), -1 for another path; its width */
int pg_anim_material_offset(pg_anim_path p, uint32_t *width);

/* Poses the scene on the CPU: scene->vertices become the deformed vertices at `time` (the
 * triangles of a primitive rewound where the pose mirrors it otherwise than its indices are wound:
 * pg_anim_prim_mirrored), the file
 * lights and the glTF cameras on nodes move with their nodes, bounds are recomputed (so framing
 * follows the animated geometry), with their animated colour, intensity, range and cones, and the
 * animated materials take their properties at `time`. A scene without animation is left as is. */
pg_result pg_scene_pose(pg_scene *scene, int animation, double time, pg_error *err);
/* Places glTF camera `index` by its node's world matrix in `pose` (a pose of scene->anim), with its
 * animated projection (pg_anim_camera_props): the
 * viewer's glTF camera follows its node as the clock plays. False, the camera left as it was, when
 * the scene has no animation, the camera no node, or the matrix is singular there. */
bool pg_scene_pose_camera(pg_scene *scene, uint32_t index, const pg_anim_pose *pose);

#ifdef __cplusplus
}
#endif
#endif
