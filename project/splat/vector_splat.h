#pragma once
// Textured vector splats (texture-mapping paper, 4.2): a field given at points with a scalar and
// a vector, each point drawn as a rectangle facing the viewer, aligned with its projected
// vector, textured with an anisotropic streak texture (motion-blurred particles, brighter
// toward the direction of motion), its colour from the scalar and its length from the
// projected speed; composited whole, back to front. Animation: a cycle of N textures in which
// the streaks move along the rectangle and re-enter at its back, so that frame k + N is frame k
// and playing the frames in a loop shows the flow moving.
//
// The streak texture T(k, u, v) of frame k, u in [0, 1] along the rectangle (1: its end in the
// direction of motion), v in [-1/2, 1/2] across it: `streaks` streaks in evenly spaced lanes,
// each a Gaussian of width streak_width across its lane times a ramp along it that rises from 0
// at its tail to 1 at its head (streak_length behind the head: brighter toward the motion),
// the head at frac(phase + k / N) (periodic in u: a streak leaving the front re-enters at the
// back), times a window fading the rectangle's ends over 0.15 of its length. T is in [0, 1].
//
// A point's splat: the vector's component across the view (for perspective, across the ray to
// the point) projected on the image gives the rectangle's direction; its half-length is
// spacing (min_half_length + (max_half_length - min_half_length) speed / fastest), speed that
// component's length and fastest the largest among the points drawn; its half-width spacing
// half_width. Along a pixel's ray it adds the optical depth tau = kappa h density T(u, v) (kappa
// the transfer function's extinction at the point's scalar, h the spacing) and the colour of
// the scalar: alpha = 1 - exp(-tau), colour c alpha. Points of zero extinction or zero
// projected speed (no direction to show) are not drawn. Opaque geometry: a splat is drawn on a
// pixel only where its centre lies in front of the pixel's surface. The renderer samples the
// frame's texture once on a 513 x 129 grid over (u, v) and reads it bilinearly.

#include <core/camera.h>
#include <core/image.h>
#include <project/transfer_function.h>
#include <project/view.h>

#include <cstddef>
#include <span>
#include <vector>

namespace tr {

struct StreakTextureOptions {
    int cycle = 8;                // N: frames in the cycle (>= 1)
    int streaks = 3;              // streaks per texture (>= 1), one per lane
    double streak_length = 0.45;  // of the rectangle's length, tail to head (0, 1]
    double streak_width = 0.07;   // Gaussian width across the lane, of the rectangle's width
};

class StreakTexture {
  public:
    // Preconditions (checked): cycle >= 1, streaks >= 1, 0 < streak_length <= 1,
    // streak_width > 0.
    explicit StreakTexture(const StreakTextureOptions& options = {});

    const StreakTextureOptions& options() const { return options_; }

    // T(frame, u, v) in [0, 1]; frame is taken modulo the cycle (any integer); 0 outside
    // u in [0, 1], |v| <= 1/2. Cost: O(streaks).
    double operator()(int frame, double u, double v) const;

  private:
    StreakTextureOptions options_;
};

// The view (camera, background, opaque layer: project/view.h) and the points drawn in it.
struct VectorSplatInputs : View {
    std::span<const Vec3> points;
    std::span<const float> scalar;  // one per point
    std::span<const Vec3> vectors;  // one per point
    double spacing = 1.0;           // h (> 0), world units
    const TransferFunction* tf = nullptr;
    const StreakTexture* texture = nullptr;
    int frame = 0;                  // which texture of the cycle (modulo the cycle)
    double half_width = 0.75;       // in spacings
    double min_half_length = 0.75;  // in spacings, at zero projected speed
    double max_half_length = 2.5;   // in spacings, at the fastest
    double density = 1.0;           // optical depth per kappa h at T = 1
};

struct VectorSplatStats {
    std::size_t splats_drawn = 0;  // points drawn (non-zero extinction and projected speed)
    std::size_t fragments = 0;     // (splat, pixel) pairs composited
    double fastest = 0;            // the largest projected speed, world units per time
    double raster_ms = 0;
};

// The picture of one frame. Preconditions (checked): scalar and vectors one per point,
// spacing > 0, 0 < min_half_length <= max_half_length, half_width > 0, opaque buffers of the
// camera's size. Cost: O(points log points) for the order plus the rectangles' areas in pixels
// times the texture's streaks; memory O(points + pixels).
Image render_vector_splats(const VectorSplatInputs& in, VectorSplatStats* stats = nullptr);

// The direction on the image (unit, in the coordinates of CameraFrame::project) along which the
// splat of a point at `point` with vector `vector` points, and its projected speed (the
// length of the vector's component across the view); {0, 0}, 0 when that component is 0 or the
// point lies behind a perspective eye.
struct ProjectedVector {
    glm::dvec2 direction{0.0};
    double speed = 0;
};
ProjectedVector project_vector(const CameraFrame& camera, const Vec3& point, const Vec3& vector);

}  // namespace tr
