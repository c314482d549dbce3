"""flip_oracle.py - an independent LDR-FLIP / HDR-FLIP reference in numpy (float64), written from
the papers, for tests/oracle/metrics_oracle.py:

  [FLIP]  Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild, "FLIP: A Difference
          Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020);
  [HDR]   Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing Errors in Rendered High Dynamic
          Range Images", Eurographics 2021 short paper,

with the conventions passgraph states in image/image_flip.h where the papers leave freedom (kernel
radii, normalisation, replicated borders, the HDR exposure rules and special cases). Nothing here is
taken from passgraph's C sources. Section numbers refer to [FLIP] unless marked [HDR].

Images are float64 arrays of shape (H, W, 3). Maps are (H, W) arrays in [0, 1].
"""
import math
from dataclasses import dataclass

import numpy as np

DEFAULT_PPD = 3840 * math.pi / 180  # 0.7 m wide 4K monitor seen from 0.7 m (Sec. 4 / image_flip.h)


@dataclass(frozen=True)
class Params:
    """The published constants; metrics_oracle.py perturbs one to show its tolerances would notice."""
    qc: float = 0.7        # colour exponent (Sec. 4.1, HyAB^qc)
    qf: float = 0.5        # feature exponent (Sec. 4.2)
    pc: float = 0.4        # redistribution knee, fraction of cmax (Sec. 4.1)
    pt: float = 0.95       # redistribution knee, output value (Sec. 4.1)
    feature_w: float = 0.082  # peak-to-trough width of the edge detector, degrees (Sec. 4.2)


# --- colour spaces -------------------------------------------------------------------------------

def srgb_to_linear(c):
    """IEC 61966-2-1 sRGB decoding (Sec. 4.1 starts from linear RGB)."""
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _rgb_to_xyz_matrix():
    """Linear sRGB -> XYZ, derived from the sRGB primaries and the D65 white point chromaticities
    (IEC 61966-2-1), so that linear (1, 1, 1) maps to the white with Y = 1."""
    prim = {'r': (0.64, 0.33), 'g': (0.30, 0.60), 'b': (0.15, 0.06)}
    wx, wy = 0.3127, 0.3290
    cols = np.array([[x / y, 1.0, (1 - x - y) / y] for (x, y) in prim.values()]).T  # XYZ of each primary, Y = 1
    white = np.array([wx / wy, 1.0, (1 - wx - wy) / wy])
    scale = np.linalg.solve(cols, white)  # primaries' luminances so that they add up to the white
    return cols * scale


RGB2XYZ = _rgb_to_xyz_matrix()
XYZ2RGB = np.linalg.inv(RGB2XYZ)
WHITE = RGB2XYZ @ np.ones(3)  # D65 = XYZ of linear (1, 1, 1) (image_flip.h)


def linear_to_xyz(rgb):
    return rgb @ RGB2XYZ.T


def xyz_to_linear(xyz):
    return xyz @ XYZ2RGB.T


def xyz_to_ycxcz(xyz):
    """YCxCz opponent space (Sec. 4.1, after Zhang & Wandell's S-CIELAB): linear in XYZ."""
    n = xyz / WHITE
    return np.stack([116 * n[..., 1] - 16, 500 * (n[..., 0] - n[..., 1]), 200 * (n[..., 1] - n[..., 2])], axis=-1)


def ycxcz_to_xyz(ycc):
    y = (ycc[..., 0] + 16) / 116
    return np.stack([y + ycc[..., 1] / 500, y, y - ycc[..., 2] / 200], axis=-1) * WHITE


def xyz_to_lab(xyz):
    """CIELAB (CIE 15) with the same white (Sec. 4.1)."""
    d = 6 / 29
    t = xyz / WHITE
    f = np.where(t > d ** 3, np.cbrt(t), t / (3 * d * d) + 4 / 29)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])], axis=-1)


def hunt(lab):
    """Hunt effect (Sec. 4.1): a* and b* scaled by 0.01 L*."""
    s = 0.01 * lab[..., 0]
    return np.stack([lab[..., 0], s * lab[..., 1], s * lab[..., 2]], axis=-1)


def hyab(lab1, lab2):
    """HyAB distance (Sec. 4.1, Abasi et al.): |dL| + Euclidean distance in (a, b)."""
    d = lab1 - lab2
    return np.abs(d[..., 0]) + np.hypot(d[..., 1], d[..., 2])


# --- filtering -----------------------------------------------------------------------------------

def correlate_replicate(img, kernel):
    """Direct 2D correlation of an (H, W) image with a (2r+1)^2 kernel, borders replicated
    (image_flip.h). The kernels used here are symmetric, or antisymmetric with only the magnitude of
    the response used, so correlation and convolution give the same result."""
    r = kernel.shape[0] // 2
    p = np.pad(img, r, mode='edge')
    win = np.lib.stride_tricks.sliding_window_view(p, kernel.shape)
    return np.einsum('ijkl,kl->ij', win, kernel, optimize=True)


# CSF parameters (Sec. 4.1, Table / Eq. 2): (a, b) pairs per YCxCz channel.
CSF = [((1.0, 0.0047),), ((1.0, 0.0053),), ((34.1, 0.04), (13.5, 0.025))]


def csf_radius(ppd):
    """ceil(3 sqrt(b_max / (2 pi^2)) ppd): three standard deviations of the widest Gaussian."""
    bmax = max(b for ch in CSF for (_, b) in ch)
    return int(math.ceil(3 * math.sqrt(bmax / (2 * math.pi ** 2)) * ppd))


def csf_kernels(ppd):
    """Eq. 2: s(r) = sum a sqrt(pi/b) exp(-pi^2 r^2 / b), r in degrees, sampled on the pixel grid
    (1/ppd degrees apart) as a full 2D kernel and normalised to sum 1."""
    r = csf_radius(ppd)
    x = np.arange(-r, r + 1) / ppd
    r2 = x[None, :] ** 2 + x[:, None] ** 2
    out = []
    for ch in CSF:
        k = sum(a * math.sqrt(math.pi / b) * np.exp(-math.pi ** 2 * r2 / b) for (a, b) in ch)
        out.append(k / k.sum())
    return out


def feature_kernels(ppd, w):
    """Sec. 4.2: Gaussian with sigma = 0.5 w ppd pixels, radius ceil(3 sigma); the edge kernel is its
    first x derivative (-x g), the point kernel its second ((x^2/sigma^2 - 1) g); in each, the
    positive weights are scaled to sum 1 and the negative ones to sum -1."""
    sd = 0.5 * w * ppd
    r = int(math.ceil(3 * sd))
    x = np.arange(-r, r + 1, dtype=np.float64)
    X, Y = np.meshgrid(x, x)  # X varies along columns
    g = np.exp(-(X ** 2 + Y ** 2) / (2 * sd * sd))
    ks = []
    for k in (-X * g, (X ** 2 / (sd * sd) - 1) * g):
        pos, neg = k[k > 0].sum(), -k[k < 0].sum()
        ks.append(np.where(k > 0, k / pos, k / neg))
    return ks  # edge, point (x direction; the y direction is the transpose)


# --- LDR-FLIP --------------------------------------------------------------------------------------

def cmax_value(p):
    """Largest colour error (Sec. 4.1): HyAB between Hunt-adjusted pure green and pure blue, ^qc."""
    g = hunt(xyz_to_lab(linear_to_xyz(np.array([0.0, 1.0, 0.0]))))
    b = hunt(xyz_to_lab(linear_to_xyz(np.array([0.0, 0.0, 1.0]))))
    return float(hyab(g, b)) ** p.qc


def redistribute(e, cmax, p):
    """Eq. 4: errors below pc cmax are mapped linearly to [0, pt), the rest to [pt, 1]; clamped to <= 1
    (image_flip.h)."""
    k = p.pc * cmax
    out = np.where(e < k, (p.pt / k) * e, p.pt + (e - k) / (cmax - k) * (1 - p.pt))
    return np.minimum(out, 1.0)


def _color_preprocess(ycc, kernels):
    """Sec. 4.1: CSF filtering per YCxCz channel, back to linear RGB clamped to [0, 1], CIELAB, Hunt."""
    filt = np.stack([correlate_replicate(ycc[..., i], kernels[i]) for i in range(3)], axis=-1)
    rgb = np.clip(xyz_to_linear(ycxcz_to_xyz(filt)), 0.0, 1.0)
    return hunt(xyz_to_lab(linear_to_xyz(rgb)))


def _features(yn, kx_edge, kx_point):
    """Sec. 4.2: edge and point strengths = length of the (x, y) filter responses."""
    e = np.hypot(correlate_replicate(yn, kx_edge), correlate_replicate(yn, kx_edge.T))
    q = np.hypot(correlate_replicate(yn, kx_point), correlate_replicate(yn, kx_point.T))
    return e, q


def ldr_flip_parts(test_lin, ref_lin, ppd=DEFAULT_PPD, p=Params()):
    """The two per-pixel quantities FLIP combines, for two linear-RGB display images in [0, 1]:
    the HyAB distance of the filtered colours (before ^qc) and the feature difference
    max(|d edge|, |d point|) (before /sqrt(2) and ^qf)."""
    kernels = csf_kernels(ppd)
    ycc_t = xyz_to_ycxcz(linear_to_xyz(test_lin))
    ycc_r = xyz_to_ycxcz(linear_to_xyz(ref_lin))
    # Colour pipeline (Sec. 4.1, Eq. 3)
    de = hyab(_color_preprocess(ycc_r, kernels), _color_preprocess(ycc_t, kernels))
    # Feature pipeline (Sec. 4.2, Eq. 5) on the unfiltered normalised achromatic channel Y/Yn
    ke, kp = feature_kernels(ppd, p.feature_w)
    er, pr = _features((ycc_r[..., 0] + 16) / 116, ke, kp)
    et, pt = _features((ycc_t[..., 0] + 16) / 116, ke, kp)
    return de, np.maximum(np.abs(er - et), np.abs(pr - pt))


def combine(de, fd, p=Params()):
    """Colour error (Eq. 4 redistribution of HyAB^qc), feature error ((fd / sqrt(2))^qf, Eq. 5) and
    their combination colour^(1 - feature) (Sec. 4.3, Eq. 6)."""
    dc = redistribute(de ** p.qc, cmax_value(p), p)
    df = (fd / math.sqrt(2)) ** p.qf
    return dc ** (1.0 - df)


def ldr_flip_linear(test_lin, ref_lin, ppd=DEFAULT_PPD, p=Params()):
    """LDR-FLIP map of two linear-RGB display images in [0, 1], (H, W, 3) float64."""
    return combine(*ldr_flip_parts(test_lin, ref_lin, ppd, p), p)


def decode_rgba8(img):
    return srgb_to_linear(img[..., :3].astype(np.float64) / 255.0)


def ldr_flip(test_u8, ref_u8, ppd=DEFAULT_PPD, p=Params()):
    """LDR-FLIP of two (H, W, >=3) uint8 sRGB-encoded images: (map, mean)."""
    m = ldr_flip_linear(decode_rgba8(test_u8), decode_rgba8(ref_u8), ppd, p)
    return m, float(m.mean())


# --- HDR-FLIP ------------------------------------------------------------------------------------

# ACES fit (Narkowicz) with HDR-FLIP's 0.6 pre-scale folded in ([HDR] Sec. 3, image_flip.h)
ACES = (0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14)


def tone_map(x):
    k0, k1, k3, k4, k5 = ACES
    return np.clip((k0 * x * x + k1 * x) / (k3 * x * x + k4 * x + k5), 0.0, 1.0)


def aces_inverse(t):
    """x >= 0 with tone_map(x) = t: the positive root of (k0 - t k3) x^2 + (k1 - t k4) x - t k5 = 0."""
    k0, k1, k3, k4, k5 = ACES
    a, b, c = k0 - t * k3, k1 - t * k4, -t * k5
    return (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)


def sanitize_hdr(img):
    """image_flip.h: a pixel with a NaN/Inf in R, G or B becomes black (and is counted); negative
    values become 0 (the tone mapper clips them anyway)."""
    rgb = img[..., :3].astype(np.float64)
    bad = ~np.all(np.isfinite(rgb), axis=-1)
    rgb = np.where(bad[..., None], 0.0, np.maximum(rgb, 0.0))
    return rgb, int(bad.sum())


def exposure_range(ref_rgb):
    """[HDR] Sec. 3: start = log2(x85 / Y_max), stop = log2(x85 / Y_median) from the reference's
    luminance; passgraph's rules: Y_max = 0 gives (0, 0); Y_median = 0 uses the median of the
    positive luminances. Exposures = max(2, ceil(stop - start))."""
    lum = ref_rgb @ np.array([0.2126, 0.7152, 0.0722])
    x85 = aces_inverse(0.85)
    ymax = float(lum.max())
    if ymax == 0.0:
        start = stop = 0.0
    else:
        ymed = float(np.median(lum))  # even count: mean of the two middle values
        if ymed == 0.0:
            ymed = float(np.median(lum[lum > 0]))
        start, stop = math.log2(x85 / ymax), math.log2(x85 / ymed)
    n = max(2, int(math.ceil(stop - start)))
    return start, stop, n


def hdr_flip(test_f, ref_f, ppd=DEFAULT_PPD, p=Params(), keep_parts=False):
    """HDR-FLIP of two (H, W, >=3) scene-linear float images ([HDR] Sec. 3): LDR-FLIP of the
    tone-mapped, clamped linear display images at each exposure; the map is the per-pixel max.
    keep_parts: stats['parts'] lists each exposure's ldr_flip_parts."""
    t, bad_t = sanitize_hdr(test_f)
    r, bad_r = sanitize_hdr(ref_f)
    start, stop, n = exposure_range(r)
    hmap, parts = None, []
    for i in range(n):
        c = start + i * (stop - start) / (n - 1)
        de, fd = ldr_flip_parts(tone_map(2.0 ** c * t), tone_map(2.0 ** c * r), ppd, p)
        if keep_parts:
            parts.append((de, fd))
        m = combine(de, fd, p)
        hmap = m if hmap is None else np.maximum(hmap, m)
    stats = {'mean': float(hmap.mean()), 'start_exposure': start, 'stop_exposure': stop, 'exposures': n,
             'nonfinite_test': bad_t, 'nonfinite_ref': bad_r}
    if keep_parts:
        stats['parts'] = parts
    return hmap, stats
