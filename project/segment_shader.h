#pragma once
// Colour and opacity of one ray segment through a tet, given the scalar at its front and back
// and its length: the three integrators of the CPU renderer.
//
// - kPreintegrated (default): opacity exact in the length, alpha = 1 - exp(-tau), the optical
//   depth tau = length * K with K the mean extinction over [front, back]
//   (TransferFunction::mean_extinction, closed form), read bilinearly from a 253 x 253 table
//   where that is accurate to 2e-4 relative (measured per cell; the closed form elsewhere).
//   Premultiplied colour alpha * cbar: the mean colour cbar (a convex combination of the glow
//   colours along the segment) depends on (front, back, tau) only, and is read trilinearly from
//   a 64 x 64 x 32 table over (front, back, r = tau / (1 + tau)): r in [0, 1] covers every
//   optical depth, and cbar is smooth in r up to r = 1 (infinitely thick: the colour just behind
//   the front). Every control point sits on a node of the scalar axes (no cell straddles a kink
//   of the transfer function), with narrow cells where the opacity falls to zero. Building the
//   table measures each cell's interpolation error against the directly integrated mean colour
//   (at the centre, face centres and edge midpoints; on a 3 x 3 grid where the cell touches a
//   control point on the diagonal); the segments of cells off by more than 0.3 of an 8-bit
//   level, or (beyond the optically thin) across which the extinction changes more than 5-fold,
//   are integrated directly instead. A pixel's error is at most the largest error of the mean
//   colours composited into it: against kExact, 0.35 of a level at most per segment over
//   random segments, optically thin to opaque, through the tests' transfer functions (steps,
//   zero plateaus, 200 control points included; tests/project/segment_shader_test.cpp), and
//   pictures within one level after rounding (tests/project/renderer_test.cpp, the realdata
//   scenes in tests/apps/cli_render_realdata_test.cpp). Parts of a segment beyond the control
//   points are uniform slabs (closed form).
// - kExact: the segment's integral computed per fragment: split where the scalar crosses a
//   control point (every one), then midpoint sub-steps short enough that extinction and colour
//   are nearly constant (optical depth at most 0.02 a step, at most 256 steps a piece).
// - kExpTexture: the paper's section 3.2: opacity 1 - exp(-u v) from a 2D lookup texture
//   (bilinear), u the thickness, v the mean of the extinctions at the two ends; colour c at the
//   mean scalar. The CPU renderer pairs it with the paper's Shirley-Tuchman projection
//   (thickness and scalars interpolated across each cell's projected triangles). Its error is
//   the paper's approximation (the mean of the ends' extinctions for the mean extinction, the
//   colour at the mean scalar for the mean colour), which grows with a cell's optical depth and
//   with the colour change across it. Its bound, measured against the reference ray caster and
//   asserted (less a margin) by the tests: on the realdata quick scenes at least 52 dB over the
//   foreground and at most 4 levels, except tetra_mesh (cells spanning much of the colour map)
//   at 29.5 dB and 43 levels; on the tests' optically thin wavy field 48 dB and 14 levels; the
//   ventilation grid made optically thick 61 dB and 4 levels; cells five unit distances deep at
//   opacity 0.6 to 0.99, 31 dB and 87 levels; one cube four unit distances deep at opacity 0.99
//   with the colour changing across it, 22 dB and 91 levels. It is the paper's method, kept to
//   compare with, not an accurate one for optically thick cells.

#include <core/math.h>
#include <project/transfer_function.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace tr {

enum class Integrator { kExpTexture, kPreintegrated, kExact };

namespace detail {
struct Preintegration;  // kPreintegrated's tables (project/detail/preintegration.h)
struct LazyPreintTable;
}  // namespace detail

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
    // length max_length * l / (pre_lengths - 1): the segment's colour and opacity as
    // SegmentShader::shade gives them at those grid points (64 x 64 x 32). Trilinear
    // interpolation in the length is only as good as the length steps are thin optically; the
    // CPU renderer does not sample this table (see kPreintegrated above). Empty otherwise.
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

// A ray segment: the scalar at its front and back, its length (world units).
struct SegmentQuery {
    double s_front, s_back, length;
};

class SegmentShader {
  public:
    // `tf` must outlive the shader. `max_length`: the longest segment expected (the exp texture
    // and the (front, back, length) table of tables() cover [0, max_length]; longer segments
    // are integrated directly by kExpTexture; kPreintegrated takes any length). Cost of
    // construction: exp-texture a 256 x 256 table (fast); preintegrated the two tables and their
    // error measurement, 0.13 s of CPU for an 11-point colour map (optically thin or thick; the
    // old table took 0.11 and 0.45 s), about 0.3 s with steps and zero plateaus, threaded over
    // rows; exact nothing. tables() builds the (front, back, length) table on its first call
    // (15-200 ms).
    SegmentShader(const TransferFunction& tf, Integrator integrator, double max_length);

    // Colour and opacity of a segment of `length` (world units; <= 0 gives nothing) along
    // which the scalar runs linearly from s_front to s_back. Thread-safe (const). Cost:
    // kPreintegrated a few table reads (more in the cells integrated directly); kExact up to
    // 256 sub-steps per piece between control points; kExpTexture one texture read.
    ShadedSegment shade(double s_front, double s_back, double length) const;
    // out[i] = shade(queries[i]) for every i: a renderer's batch (one cell's pixels), which lets
    // the processor overlap the segments' lookups. Precondition: out.size() >= queries.size().
    void shade(std::span<const SegmentQuery> queries, std::span<ShadedSegment> out) const;

    // Whether every segment whose scalars lie between s0 and s1 shades to nothing (colour and
    // opacity exactly 0, whatever the integrator): the transfer function is clear there.
    bool clear_between(double s0, double s1) const { return tf_.clear_between(s0, s1); }

    Integrator integrator() const { return integrator_; }
    SegmentShaderTables tables() const;

    // kPreintegrated: how many of the mean-colour table's cells integrate their segments
    // directly (their measured interpolation error exceeds 0.3 of an 8-bit level, or the
    // extinction changes sharply across them), of how many (0 for the other integrators).
    std::size_t direct_cells() const;
    std::size_t table_cells() const;

  private:
    ShadedSegment exact(double s_front, double s_back, double length) const;
    ShadedSegment exp_texture(double s_front, double s_back, double length) const;
    // The texture read at thickness `length` and mean extinction `mean_extinction`, the colour
    // at `s_mean`; the end scalars for what the texture does not cover (integrated directly).
    ShadedSegment exp_texture_at(double length, double mean_extinction, double s_mean,
                                 double s_front, double s_back) const;
    // kPreintegrated for any scalars (the parts beyond the control points are uniform slabs);
    // for scalars in [s_lo_, s_hi_] (the common path); its mean extinction at table coordinates
    // (x, y), read or in closed form; its end from the optical depth tau.
    ShadedSegment preintegrated(double s_front, double s_back, double length) const;
    ShadedSegment preintegrated_inside(double s_front, double s_back, double length) const;
    float table_extinction(double s_front, double s_back, float x, float y) const;
    float closed_form_extinction(double s_front, double s_back) const;
    ShadedSegment preintegrated_finish(double s_front, double s_back, double length, float tau,
                                       float x, float y) const;
    // The segment integrated directly, where the mean-colour table is not accurate enough:
    // optical depth in closed form, mean colour from the pieces between control points with the
    // colour quadratic in optical depth on each (what the table is built from; error < 1e-4).
    ShadedSegment direct(double s_front, double s_back, double length) const;

    const TransferFunction& tf_;
    Integrator integrator_;
    double max_length_;
    double s_lo_, s_hi_;               // scalar range of the tables (the control points' range)
    double kappa_max_;                 // largest extinction, for the exp texture's v axis
    std::vector<double> breakpoints_;  // control-point scalars, sorted, unique
    std::vector<float> exp_table_;     // kExpTexture: kExpSize x kExpSize, 1 - exp(-u v)
    double exp_u_scale_ = 0, exp_v_scale_ = 0;  // kExpTexture: texels per unit of u and of v
    // kPreintegrated: its tables (immutable, shared by copies, which share tf_ too), and the
    // (front, back, length) table of tables(), built on its first call.
    std::shared_ptr<const detail::Preintegration> pre_;
    std::shared_ptr<detail::LazyPreintTable> gl_table_;
};

}  // namespace tr
