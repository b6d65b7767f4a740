#pragma once
// Image-space particle-based volume rendering, I-PBVR (particle-based paper, 3.4, 3.5 and 4.1):
// no sort. Every tet's exact segment on every pixel ray (project/tet_fragments.h) holds an
// opaque particle with probability equal to the segment's opacity alpha = 1 - exp(-optical
// depth), at the depth where the opacity's cumulative distribution along the segment reaches a
// uniform number (the inverse-function method, equations 20-25; exact here: the optical depth
// is in closed form, TransferFunction::mean_extinction), coloured by the transfer function at
// the scalar there. The nearest particle of each pixel wins; the repetitions' pictures are
// averaged in floating point. The expected picture is the spec's ray integral, and several
// volumes overlapping in space (fused rendering) need nothing more: their particles compete for
// the nearest place.
//
// Beyond the paper — stratified repetitions: the R repetitions of one segment on one pixel take
// the R points of a randomly rotated lattice (project/pbvr/pbvr_sampling.h) instead of independent
// numbers, the same number deciding presence (u < alpha) and depth (the CDF at u / alpha). Each
// repetition alone is exactly distributed (every segment's rotation is independent, so the
// estimator stays unbiased), while over the R repetitions each segment holds a particle in
// floor or ceil of alpha R of them, at depths spread over its distribution, and (each segment
// taking its own lattice generator) the segments of a ray fill their joint space evenly rather
// than independently. `stratified = false` gives the paper's independent repetitions.
//
// Also beyond the paper — the winner's expected colour: with one volume (whose segments do not
// overlap on a ray, so which segment holds the nearest particle does not depend on the depth
// inside it) and the inverse-CDF depth, the colour of the nearest particle is replaced by its
// expectation given the segment, the segment's mean colour C / alpha (a conditional
// expectation: the same expected picture, less noise, and no depth to draw). It comes from the
// volume's shader when one is given (VolumeData::shader: the pre-integrated table, within
// half an 8-bit level of the exact integral); otherwise the particle's colour is drawn.
//
// Also beyond the paper — a control variate: whether a repetition has any particle on a pixel
// is the largest part of the noise where the volume is half transparent, and its probability is
// known without an order, 1 - T with T the product of (1 - alpha) over the pixel's segments. The
// picture is mean(colour) - beta (mean(has a particle) - (1 - T)), with beta per pixel the
// segments' colours weighted by their opacities less the colour behind: beta depends on no
// random number, so the estimator stays unbiased whatever beta is, and the closer beta is to the
// mean colour the particles bring, the less noise is left (none for a uniform colour).
// `control_variate = false` gives the plain mean.

#include <project/pbvr/pbvr_common.h>
#include <project/pbvr/pbvr_sampling.h>

#include <cstdint>
#include <vector>

namespace tr {

struct ImagePbvrOptions {
    int repetitions = 64;    // pictures averaged (>= 1)
    std::uint64_t seed = 1;  // the same seed gives the same picture, whatever the thread count
    ParticleDepth depth = ParticleDepth::kInverseCdf;
    bool stratified = true;       // stratify the repetitions of each segment (above)
    bool control_variate = true;  // take out the known part of the noise (above)
};

struct ImagePbvrStats {
    std::size_t fragments = 0;  // (cell, pixel) segments of positive length
    std::size_t particles = 0;  // particles drawn over all repetitions
    double raster_ms = 0;
};

// The picture. Preconditions: the scene's sizes agree (scalar per point, opaque buffers of the
// camera's size), repetitions >= 1 and repetitions x pixels at most kMaxParticleSamples (the
// pipeline checks and says so). Cost: O(fragments + particles drawn), the particles about
// R x (the sum of the opacities along a ray) per pixel; memory per worker 8 bytes per pixel of
// a 32 x 32 tile per repetition (up to 1024 repetitions at a time: 8 MB) plus the tile's
// fragments.
//
// `alpha`, when given, is resized to width x height (row-major, row 0 at the top, as Image) and
// receives per pixel the weight the estimator gives to what lies behind, subtracted from 1: with
// the control variate the known opacity 1 - T (T the product of (1 - alpha) over the pixel's
// segments: the picture is C + T b exactly), without it the fraction of repetitions with a
// particle on the pixel; 0 where no segment is. The returned picture is then, up to float
// rounding, the picture the same call (same seed) returns over black with no opaque colour
// plus (1 - alpha) times the background or opaque colour, and that picture over black is
// itself an unbiased estimate of the premultiplied colour (premultiplied RGBA for a
// compositor). An opaque depth without an opaque colour stops the segments there. Asking for
// alpha changes no bit of the picture.
Image render_image_pbvr(const VolumeScene& scene, const ImagePbvrOptions& options,
                        ImagePbvrStats* stats = nullptr, std::vector<float>* alpha = nullptr);

}  // namespace tr
