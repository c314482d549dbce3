/* accuracy_bounds.h - the per-pixel accuracy bounds of the approximate shipped pipelines against
 * the exact ones (naive / reference): |pipeline - reference| <= A |reference| + B peak for every
 * pixel and HDR channel. Asserted by test_gpu_clustered (atrium, Sponza sweeps), test_gpu_framing
 * (orthographic camera) and test_gpu_scenes (every generated glTF scene). */
#ifndef PG_TEST_ACCURACY_BOUNDS_H
#define PG_TEST_ACCURACY_BOUNDS_H

/* ---- bounds --------------------------------------------------------------------------------
 * Measured on lavapipe (Mesa 22.3, 320x180) over every frame of the sweep with every light shaded
 * (no overflow; the 5000/10000-light frames with max_lights=8192 set for the measurement, which
 * gives the same lists as an uncapped assignment). "Margin 2x" means: the bound is twice a pair
 * (A0, B0) that every measured pixel meets, so the worst measured pixel uses at most half of it
 * (bound: lines, worst_px_usage <= 0.5). README.md ("Pipelines") and docs/accuracy.md quote these values: change
 * them together.
 *
 * Deferred float, rgba32f position. The HDR target is rgba16f, whose step is at most 2^-10
 * (9.8e-4) of the value; deferred float differs from naive by one such step where the world ->
 * camera-relative subtraction rounds differently (measured: never more than one step). A = two
 * steps, B covers half-float subnormals and dark pixels; worst usage measured 0.38. */
#define FLOAT_PX_A 2e-3
#define FLOAT_PX_B 1e-5
/* oct16: normal 2x16-bit octahedral, albedo sRGB8, position rebuilt from the D32 depth.
 * Measured: every pixel within 0.0126 |ref| + 0.003 peak (Sponza, 1000 lights); margin 2x.
 * Display: 6 steps (Sponza, 5000 lights), 3.4% of the pixels > 1 step (atrium, 5000 lights:
 * a bright image, mostly in the coarse upper display steps); margin 2x. */
#define OCT16_PX_A 0.03
#define OCT16_PX_B 6e-3
#define OCT16_DISPLAY_MAX_STEP 12
/* The oct16 bounds hold to far/near = 1e5 (the Sponza, cis565, near 0.01, far 1000: measured 4
 * steps; test_gpu_framing check_near_plane). Past it the D32 depth cannot hold the view depth
 * (docs/accuracy.md, "Position from depth"): at far/near 1e6 measured 128 steps, 2.6% of the pixels
 * > 1 step; the frame carries a note instead of a bound. */
#define OCT16_DISPLAY_SHARE 0.07
/* packed: as oct16 but the position rebuilt from a stored float32 view depth. Measured: every
 * pixel within 0.0066 |ref| + 0.001 peak (atrium, 1 light); margin 2x (rounded up). Display:
 * 2 steps, 0.46% of the pixels > 1 step (atrium, 10000 lights); margin 2x. */
#define PACKED_PX_A 0.015
#define PACKED_PX_B 2e-3
#define PACKED_DISPLAY_MAX_STEP 4
#define PACKED_DISPLAY_SHARE 0.01
/* visibility (pipelines/visibility.json, both resolve paths; test_gpu_visibility): the surface is
 * rebuilt from the triangle in compute, with the point and attributes from the pixel ray.
 * Untextured scenes: every pixel within VIS_PX_A |ref| + VIS_PX_B peak of naive (rgba16f);
 * measured: every pixel within (2e-3, 2e-5) but one of models/desk_lamp.gltf (usage 1.02 there);
 * since the object framing fills 90% of the frame, models/mug.gltf reaches 1.15 of (4e-3, 4e-5)
 * (a grazing pixel: the image's RMSE is 9e-6 of the peak); the bound is twice that worst, rounded
 * up. Textured: the mip level
 * comes from analytic coarse-quad derivatives and the Vulkan spec's isotropic scale factor
 * (pg_grad_lod), not the rasterizer's own LOD arithmetic, so filtering differs where a pixel sits
 * at a mip transition. Measured (lavapipe, 50 scenes at 128x72 and 320x180): RMSE at most 0.0028
 * of the peak, display steps at most 78 and at most 1.8% of the pixels more than one step off,
 * all on tests/corpus/gltf/features/slots.gltf (one colour texture read as base colour, normal map
 * through TEXCOORD_1 with a transform, and emissive: a mip transition flips the normal) and
 * models/tree.gltf (18 steps, 1.7%); the Sponza (cis565, 320x180): RMSE 3e-6 of the peak, 2 steps
 * at most. Margin 2x. */
#define VIS_PX_A 1e-2
#define VIS_PX_B 1e-4
/* The same under the pbr light model (the default for a glTF file's materials). A glossy highlight
 * (roughness 0.1..0.25: a = 0.01..0.06) turns a normal that differs by d radians into a change of
 * about 2d/a of the GGX D, so the surface visibility rebuilds from the pixel ray (its normal and
 * point differ from the rasterizer's interpolation by ~1e-5..1e-4) moves those pixels more than
 * under Lambert. Measured (lavapipe, 128x72, the untextured corpus scenes): resolve=shade against
 * naive at most 3.57 of (VIS_PX_A, VIS_PX_B) (models/desk_lamp.gltf: chrome, roughness 0.2);
 * resolve=gbuffer against naive at most 2.95 of (PACKED_PX_A, PACKED_PX_B) (models/mug.gltf: glaze,
 * roughness 0.25). Twice those, rounded up. RMSE and display steps keep the bounds above.
 * test_gpu_visibility holds to VIS_PBR_PX_* the pixels whose naive and visibility normals are within
 * 1e-3 rad (2 x 1e-3 / 0.04 = 5% at roughness 0.2, inside 8e-2; the lavapipe pixels above are
 * further apart: the others measure 0.012 of it there, 0.39 on an H100) and the rest to 4x it. */
#define VIS_PBR_PX_A 8e-2
#define VIS_PBR_PX_B 8e-4
#define VIS_PACKED_PBR_PX_A 0.09
#define VIS_PACKED_PBR_PX_B 1.2e-2
#define VIS_RMSE_REL 6e-3
#define VIS_DISPLAY_MAX_STEP 160
#define VIS_DISPLAY_SHARE 0.04

/* ---- the environment light (test_gpu_environment, docs/accuracy.md "Environment light") --------
 * Against a CPU Monte Carlo integral of the same environment and BRDF (8192 samples an estimator,
 * in double), per pixel and channel |gpu - cpu| <= REL cpu + ABS, on a 5 x 5 grid of spheres
 * (metallic x roughness) under a sky with a bright soft window, 160x90, lavapipe.
 * The split-sum of the filtered environment (every shading pipeline): measured worst 0.196 relative
 * (metallic 1, roughness 0.7: the split-sum's approximation, largest for rough metals seen
 * off-normal), mean 0.025 over every pixel; bound 1.5x the worst, 2x the mean.
 * The reference's Monte Carlo (cosine, GGX and environment-table samples with multiple importance
 * sampling): 1024 rounds measured worst 0.009, mean 8e-4; the default 256 rounds worst 0.0135, mean
 * 0.0018; bounds about 2x the worst (the mean bound is a quarter of the pixel bound). */
#define ENV_SPLIT_SUM_PX_REL 0.3
#define ENV_SPLIT_SUM_MEAN_REL 0.05
#define ENV_REF_PX_REL 0.02
#define ENV_REF_DEFAULT_PX_REL 0.03
#define ENV_PX_ABS 0.01
/* Whole images (test_gpu_environment silhouette(): models/mug.gltf under the neutral sky, the
 * reference at its default 256 rounds): naive within ENV_SPLIT_SUM_PX_REL |ref| + ENV_SILHOUETTE_PEAK
 * peak at every pixel, silhouettes included, where N.V reaches 0 and the split-sum is furthest from
 * the integral (measured 0.45 of this bound; 1.08 of it with 0.01 peak instead of 0.05). */
#define ENV_SILHOUETTE_PEAK 0.05
#endif
