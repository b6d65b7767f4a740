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
};

}  // namespace tr
