#version 460
// luminance_histogram.comp - pixels of the HDR image per bin of log2 luminance
// (renderer/passes/luminance_histogram.c). HIST_BINS comes from the pass's declare (option
// "bins"). Two dispatches of one pipeline: mode 0 (one group) clears the bins, mode 1 (one
// invocation a pixel) counts in shared memory, then adds each group's counts with atomicAdd.
layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 1, binding = 0) uniform sampler2D hdr;
layout(set = 1, binding = 1, std430) buffer Bins { uint bins[]; };
layout(push_constant) uniform Push { float min_ev; float max_ev; uint mode; } pc;

shared uint local_bins[HIST_BINS];

// Rec.709 luminance; L <= 0 (and NaN) -> bin 0, beyond the range -> the end bins
uint hist_bin(vec3 c)
{
    float l = dot(c, vec3(0.2126, 0.7152, 0.0722));
    if (!(l > 0.0)) return 0u;
    float t = (log2(l) - pc.min_ev) / (pc.max_ev - pc.min_ev) * float(HIST_BINS);
    return uint(clamp(floor(t), 0.0, float(HIST_BINS - 1)));
}

void main()
{
    uint li = gl_LocalInvocationIndex;
    if (pc.mode == 0u) {
        for (uint b = li; b < uint(HIST_BINS); b += 256u) bins[b] = 0u;
        return;
    }
    for (uint b = li; b < uint(HIST_BINS); b += 256u) local_bins[b] = 0u;
    barrier();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, textureSize(hdr, 0)))) atomicAdd(local_bins[hist_bin(texelFetch(hdr, p, 0).rgb)], 1u);
    barrier();
    for (uint b = li; b < uint(HIST_BINS); b += 256u)
        if (local_bins[b] != 0u) atomicAdd(bins[b], local_bins[b]);
}
