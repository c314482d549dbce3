#!/usr/bin/env python3
"""nvlabs_compare.py PG_METRIC_EVAL NVLABS_PYTHON_DIR - passgraph's LDR-FLIP and HDR-FLIP against
NVlabs' own Python implementation (https://github.com/NVlabs/flip, the folder holding its numpy
`flip_api.py`: `python/` of versions before 1.4, from which on their Python calls their C++; it
needs OpenCV, Debian's python3-opencv), on the image pairs of metrics_oracle.py. Not a ctest: NVlabs' code is not part of passgraph and is not
fetched by it; run it by hand with a checkout of theirs.

For every pair it prints passgraph's mean FLIP and NVlabs', the largest and mean per-pixel
difference of the maps, and for HDR-FLIP both exposure ranges. HDR pairs with values NVlabs' tool
does not define the same way are left out (NaN, Inf or negative values: image_flip.h's
conventions; a reference whose median luminance is 0: passgraph takes the median of the positive
luminances, NVlabs' np.percentile gives 0 and a stop exposure of +inf).

Exit 0 when every pair agrees within the tolerances below (float32 arithmetic on both sides, and
NVlabs' float32 kernels, explain them), 1 otherwise.
"""
import importlib
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics_oracle as mo  # noqa: E402  (re-runs itself under /usr/bin/python3 when numpy is missing)
import flip_oracle as fo  # noqa: E402

np = mo.np

MAP_TOL = 2e-4    # largest |map difference| on a pixel (measured 8.8e-5: edges_shift)
MEAN_TOL = 2e-5   # |mean FLIP difference| (measured 9.3e-6: flat_colours, where only the colour term counts)
EXPOSURE_TOL = 1e-4  # stops
SKIPPED_HDR = {'hdr_nonfinite': 'NaN, Inf and negative values', 'hdr_half_black': 'median luminance 0',
               'hdr_black_ref': 'black reference (no exposure range)'}


def chw(img):
    return np.ascontiguousarray(np.transpose(img[..., :3], (2, 0, 1)))


def nv_ldr(nv, test_u8, ref_u8, ppd):
    t = chw(test_u8.astype(np.float32) / 255.0)
    r = chw(ref_u8.astype(np.float32) / 255.0)
    return np.asarray(nv.compute_ldrflip(r, t, ppd)).squeeze(0).astype(np.float64)


def nv_hdr(nv, test_f, ref_f, ppd):
    """HDR-FLIP as NVlabs' flip.py runs it: exposures from the reference (compute_exposure_params),
    max(2, ceil(stop - start)) of them, LDR-FLIP of the sRGB-encoded ACES tone maps, the per-pixel max."""
    t, r = chw(test_f.astype(np.float32)), chw(ref_f.astype(np.float32))
    start, stop = nv.compute_exposure_params(r)
    n = 1 if start == stop else int(max(2, np.ceil(stop - start)))
    step = (stop - start) / max(n - 1, 1)
    best = None
    for i in range(n):
        e = start + i * step
        rs = nv.color_space_transform(nv.tone_map(r, e), 'linrgb2srgb')
        ts = nv.color_space_transform(nv.tone_map(t, e), 'linrgb2srgb')
        m = np.asarray(nv.compute_ldrflip(rs, ts, ppd)).squeeze(0)
        best = m if best is None else np.maximum(best, m)
    return best.astype(np.float64), float(start), float(stop), n


def main():
    if len(sys.argv) != 3:
        print('usage: nvlabs_compare.py PATH/TO/pg_metric_eval NVLABS_FLIP/python')
        return 2
    exe, nvdir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    sys.path.insert(0, nvdir)
    try:
        nv = importlib.import_module('flip_api')
    except ImportError as e:
        print('nvlabs_compare: cannot import flip_api from %s: %s' % (nvdir, e))
        return 1
    bad, rows = 0, []
    with tempfile.TemporaryDirectory(prefix='pg_nvlabs_') as tmp:
        pg = mo.Passgraph(exe, tmp)
        for name, (test, ref), ppd in mo.ldr_pairs():
            p = ppd if ppd is not None else fo.DEFAULT_PPD
            pg_map, out = pg.flip('ldr', test, ref, ppd)
            nv_map = nv_ldr(nv, test, ref, p)
            d = np.abs(pg_map - nv_map)
            ok = d.max() <= MAP_TOL and abs(out['mean'] - nv_map.mean()) <= MEAN_TOL
            bad += not ok
            rows.append((name, 'ldr', out['mean'], float(nv_map.mean()), float(d.max()), float(d.mean()), '', ok))
        for name, (test, ref), ppd in mo.hdr_pairs():
            if name in SKIPPED_HDR:
                print('%s: left out (%s)' % (name, SKIPPED_HDR[name]))
                continue
            p = ppd if ppd is not None else fo.DEFAULT_PPD
            pg_map, out = pg.flip('hdr', test, ref, ppd)
            nv_map, start, stop, n = nv_hdr(nv, test, ref, p)
            d = np.abs(pg_map - nv_map)
            de = max(abs(out['start_exposure'] - start), abs(out['stop_exposure'] - stop))
            ok = (d.max() <= MAP_TOL and abs(out['mean'] - nv_map.mean()) <= MEAN_TOL and de <= EXPOSURE_TOL
                  and out['exposures'] == n)
            bad += not ok
            note = 'exposures %.5f..%.5f n=%d vs %.5f..%.5f n=%d' % (out['start_exposure'], out['stop_exposure'],
                                                                   out['exposures'], start, stop, n)
            rows.append((name, 'hdr', out['mean'], float(nv_map.mean()), float(d.max()), float(d.mean()), note, ok))
    print('%-22s %4s %12s %12s %10s %10s  %s' % ('pair', '', 'passgraph', 'NVlabs', 'max|diff|', 'mean|diff|', ''))
    for name, kind, a, b, dmax, dmean, note, ok in rows:
        print('%-22s %4s %12.8f %12.8f %10.2e %10.2e  %s%s' % (name, kind, a, b, dmax, dmean, note,
                                                              '' if ok else '  DISAGREE'))
    print('nvlabs_compare: %s (map %g, mean %g, exposure %g)' % (
        '%d pair(s) disagree' % bad if bad else 'all agree', MAP_TOL, MEAN_TOL, EXPOSURE_TOL))
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
