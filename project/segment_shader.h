#pragma once
// Colour and opacity of one ray segment through a tet, given the scalar at its front and back
// and its length: the three integrators of the CPU renderer.
//
// - kExpTexture: the paper's section 3.2: opacity 1 - exp(-u v) from a 2D lookup texture
//   (bilinear), u the thickness, v the mean extinction of the two ends; colour c at the mean
//   scalar. The CPU renderer pairs it with the paper's Shirley-Tuchman projection (thickness
//   and scalars interpolated across each cell's projected triangles).
// - kPreintegrated: a pre-integrated table over (front scalar, back scalar, length) (Engel,
//   Kraus, Ertl 2001), trilinear, so colour and opacity varying inside a cell are integrated.
// - kExact: the segment's integral computed per fragment: split where the scalar crosses a
//   control point, then sub-steps short enough that extinction and colour are nearly constant.

#include <core/math.h>
#include <project/transfer_function.h>

#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace tr {

enum class Integrator { kExpTexture, kPreintegrated, kExact };

std::string_view integrator_name(Integrator integrator);  // "exp-texture", ...
std::optional<Integrator> parse_integrator(std::string_view name);

// The lookup tables of a SegmentShader as they are, for renderers that sample them elsewhere
// (the OpenGL renderer's textures). Texel centres sit on the grid points below.
struct SegmentShaderTables {
    // kExpTexture: exp_size x exp_size floats; index j * exp_size + i holds 1 - exp(-u v) with
    // u = max_length * i / (exp_size - 1), v = kappa_max * j / (exp_size - 1). Empty otherwise.
    std::span<const float> exp_table;
    int exp_size = 0;
    // kPreintegrated: premultiplied RGBA at ((f * pre_scalars + b) * pre_lengths + l) * 4 for
    // front scalar s_lo + (s_hi - s_lo) * f / (pre_scalars - 1), back scalar likewise with b,
    // length max_length * l / (pre_lengths - 1). Empty otherwise.
    std::span<const float> preint_table;
    int pre_scalars = 0;
    int pre_lengths = 0;
    double s_lo = 0, s_hi = 1;  // scalar range of the tables
    double max_length = 1;      // the longest segment the tables cover
    double kappa_max = 0;       // largest extinction (the exp texture's v range)
};

struct ShadedSegment {
    Vec3f color;  // premultiplied
    float alpha;
};

class SegmentShader {
  public:
    // `max_length`: the longest segment expected (the lookup tables cover [0, max_length]; longer
    // segments are integrated directly). Cost of construction: exp-texture 256x256 table
    // (fast); preintegrated 128x128x32 table (about 0.1-0.3 s); exact nothing.
    SegmentShader(const TransferFunction& tf, Integrator integrator, double max_length);

    ShadedSegment shade(double s_front, double s_back, double length) const;

    Integrator integrator() const { return integrator_; }
    SegmentShaderTables tables() const;

  private:
    ShadedSegment exact(double s_front, double s_back, double length) const;
    ShadedSegment exp_texture(double s_front, double s_back, double length) const;
    ShadedSegment preintegrated(double s_front, double s_back, double length) const;

    const TransferFunction& tf_;
    Integrator integrator_;
    double max_length_;
    double s_lo_, s_hi_;  // scalar range of the tables (the control points' range)
    double scalar_scale_ = 1, length_scale_ = 1;  // table steps per unit scalar and length
    double kappa_max_;                 // largest extinction, for the exp texture's v axis
    std::vector<float> exp_table_;     // kExpTexture: kExpSize x kExpSize, 1 - exp(-u v)
    std::vector<float> preint_table_;  // kPreintegrated: (s_f, s_b, l) -> r, g, b, a
    std::vector<double> breakpoints_;  // control-point scalars, sorted
};

}  // namespace tr
