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
#define OCT16_DISPLAY_SHARE 0.07
/* packed: as oct16 but the position rebuilt from a stored float32 view depth. Measured: every
 * pixel within 0.0066 |ref| + 0.001 peak (atrium, 1 light); margin 2x (rounded up). Display:
 * 2 steps, 0.46% of the pixels > 1 step (atrium, 10000 lights); margin 2x. */
#define PACKED_PX_A 0.015
#define PACKED_PX_B 2e-3
#define PACKED_DISPLAY_MAX_STEP 4
#define PACKED_DISPLAY_SHARE 0.01
#endif
