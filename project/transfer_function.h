#pragma once
// The transfer function of a scene (../shared/spec/scene.md): glow colour and opacity, each
// piecewise linear in the scalar, clamped outside the control points; extinction
// kappa(s) = -ln(1 - a(s)) / unit_distance.

#include <core/math.h>
#include <core/result.h>

#include <array>
#include <vector>

namespace tr {

struct ColorPoint {
    double s;
    Vec3 rgb;  // each in [0, 1]
};
struct OpacityPoint {
    double s;
    double a;  // in [0, 1)
};

// The mean of -ln(u) over u in [v, w] (either order; v, w > 0), in closed form
// (u ln u - u is an antiderivative of ln u) written to keep full precision as w -> v, where it
// is -ln(v): the mean extinction, times unit_distance, of a piece along which the opacity
// a = 1 - u is linear. Cost: a log and a log1p.
double mean_neg_log(double v, double w);

class TransferFunction {
  public:
    // Validates: at least one point each, s non-decreasing, rgb in [0, 1], a in [0, 1),
    // unit_distance > 0 and finite. Errors say which point is wrong.
    static Result<TransferFunction> create(std::vector<ColorPoint> color,
                                           std::vector<OpacityPoint> opacity, double unit_distance);

    Vec3 color(double s) const;
    double opacity(double s) const;  // a(s), the opacity of a slab of thickness unit_distance
    double extinction(double s) const { return extinction_from_opacity(opacity(s)); }
    double extinction_from_opacity(double a) const;
    // The mean of kappa over the scalar interval between s0 and s1 (either order), in closed
    // form: the integral of -ln(1 - a) over each linear piece of a is u ln u - u with u = 1 - a,
    // written as a divided difference (log1p) so that it stays accurate as s1 -> s0, where it
    // is kappa(s0). A segment of length L along which the scalar runs linearly from s0 to s1
    // has optical depth L * mean_extinction(s0, s1), exactly. Cost: O(log n) plus the pieces
    // crossed (a cumulative sum covers whole pieces), two logarithms per end piece.
    double mean_extinction(double s0, double s1) const;

    // Whether the opacity is zero at every scalar between s0 and s1 (either order; false when
    // either is NaN): a segment whose scalar stays there absorbs and emits nothing. Cost:
    // O(log n) plus the control points inside.
    bool clear_between(double s0, double s1) const;

    const std::vector<ColorPoint>& color_points() const { return color_; }
    const std::vector<OpacityPoint>& opacity_points() const { return opacity_; }
    double unit_distance() const { return unit_distance_; }
    // Smallest and largest control-point scalar over both functions.
    double s_min() const;
    double s_max() const;

  private:
    std::vector<ColorPoint> color_;
    std::vector<OpacityPoint> opacity_;
    double unit_distance_ = 1.0;
    // integral_[i]: the integral of -ln(1 - a) * unit_distance over [opacity_[0].s,
    // opacity_[i].s] (set by create).
    std::vector<double> integral_;
};

// A log colour scale written as a transfer function of the scalar itself (scene.md has no log
// key, so a scene written with it renders the same in every reader of the spec): `over_log10`,
// whose control points are in log10 of the scalar, becomes one whose control points sit at
// 10^x for every control point x of `over_log10` and for `samples` values of x spread evenly
// between its first and last, each with over_log10's colour and opacity there, and the same
// unit distance. Between them it is linear in the scalar, so it follows the log map to within
// a small share of a step (measured in tests/project/transfer_function_test.cpp); values below
// 10^first take the first point's colour and opacity, as any transfer function clamps.
// Errors (kInvalidArgument): control points beyond 10^+-300, samples < 2.
Result<TransferFunction> log_scaled(const TransferFunction& over_log10, int samples = 129);

}  // namespace tr
