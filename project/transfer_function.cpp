#include <project/transfer_function.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tr {
namespace {

template <class Point, class Value, class Get>
Value piecewise_linear(const std::vector<Point>& points, double s, Get get) {
    if (s <= points.front().s) return get(points.front());
    if (s >= points.back().s) return get(points.back());
    auto hi = std::upper_bound(points.begin(), points.end(), s,
                               [](double x, const Point& p) { return x < p.s; });
    auto lo = hi - 1;
    const double span = hi->s - lo->s;
    if (!(span > 0)) return get(*hi);
    const double t = (s - lo->s) / span;
    return get(*lo) + (get(*hi) - get(*lo)) * t;
}

}  // namespace

Result<TransferFunction> TransferFunction::create(std::vector<ColorPoint> color,
                                                  std::vector<OpacityPoint> opacity,
                                                  double unit_distance) {
    if (color.empty()) return make_error(ErrorCode::kInvalidArgument, "no color points");
    if (opacity.empty()) return make_error(ErrorCode::kInvalidArgument, "no opacity points");
    if (!(unit_distance > 0) || !std::isfinite(unit_distance)) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "unit_distance must be a positive number, not " + std::to_string(unit_distance));
    }
    for (std::size_t i = 0; i < color.size(); ++i) {
        const auto& p = color[i];
        const std::string where = "color point " + std::to_string(i);
        if (!std::isfinite(p.s))
            return make_error(ErrorCode::kInvalidArgument, where + ": scalar is not finite");
        if (i > 0 && p.s < color[i - 1].s) {
            return make_error(ErrorCode::kInvalidArgument, where + ": scalars must not decrease");
        }
        for (int c = 0; c < 3; ++c) {
            if (!(p.rgb[c] >= 0 && p.rgb[c] <= 1)) {
                return make_error(ErrorCode::kInvalidArgument, where + ": rgb must be in [0, 1]");
            }
        }
    }
    for (std::size_t i = 0; i < opacity.size(); ++i) {
        const auto& p = opacity[i];
        const std::string where = "opacity point " + std::to_string(i);
        if (!std::isfinite(p.s))
            return make_error(ErrorCode::kInvalidArgument, where + ": scalar is not finite");
        if (i > 0 && p.s < opacity[i - 1].s) {
            return make_error(ErrorCode::kInvalidArgument, where + ": scalars must not decrease");
        }
        if (!(p.a >= 0 && p.a < 1)) {
            return make_error(ErrorCode::kInvalidArgument,
                              where + ": opacity must be in [0, 1), not " + std::to_string(p.a));
        }
    }
    TransferFunction tf;
    tf.color_ = std::move(color);
    tf.opacity_ = std::move(opacity);
    tf.unit_distance_ = unit_distance;
    return tf;
}

Vec3 TransferFunction::color(double s) const {
    return piecewise_linear<ColorPoint, Vec3>(color_, s, [](const ColorPoint& p) { return p.rgb; });
}

double TransferFunction::opacity(double s) const {
    return piecewise_linear<OpacityPoint, double>(opacity_, s,
                                                  [](const OpacityPoint& p) { return p.a; });
}

double TransferFunction::extinction_from_opacity(double a) const {
    return -std::log1p(-a) / unit_distance_;
}

double TransferFunction::s_min() const { return std::min(color_.front().s, opacity_.front().s); }
double TransferFunction::s_max() const { return std::max(color_.back().s, opacity_.back().s); }

}  // namespace tr
