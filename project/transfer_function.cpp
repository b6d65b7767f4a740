#include <project/transfer_function.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tr {
namespace {

template <class Point, class Value, class Get>
Value piecewise_linear(const std::vector<Point>& points, double s, Get get) {
    // A NaN scalar (a renderer's interpolation in a degenerate cell) takes the first point's
    // value: upper_bound would return the end, and *hi read past the points.
    if (!(s > points.front().s)) return get(points.front());
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

// -(F(w) - F(v)) / (w - v) with F(u) = u ln u - u, written with d = (w - v) / v as
// -(ln v + (1 + d) log1p(d) / d - 1).
double mean_neg_log(double v, double w) {
    const double d = (w - v) / v;
    if (std::abs(d) < 1e-9) return -(std::log(v) + 0.5 * d);
    return -(std::log(v) + (1.0 + d) * std::log1p(d) / d - 1.0);
}

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
    tf.integral_.assign(tf.opacity_.size(), 0.0);
    for (std::size_t i = 1; i < tf.opacity_.size(); ++i) {
        const OpacityPoint& a = tf.opacity_[i - 1];
        const OpacityPoint& b = tf.opacity_[i];
        tf.integral_[i] = tf.integral_[i - 1] + (b.s - a.s) * mean_neg_log(1.0 - a.a, 1.0 - b.a);
    }
    return tf;
}

Vec3 TransferFunction::color(double s) const {
    return piecewise_linear<ColorPoint, Vec3>(color_, s, [](const ColorPoint& p) { return p.rgb; });
}

double TransferFunction::opacity(double s) const {
    return piecewise_linear<OpacityPoint, double>(opacity_, s,
                                                  [](const OpacityPoint& p) { return p.a; });
}

bool TransferFunction::clear_between(double s0, double s1) const {
    if (std::isnan(s0) || std::isnan(s1)) return false;
    if (s0 > s1) std::swap(s0, s1);
    if (opacity(s0) != 0 || opacity(s1) != 0) return false;
    // The control points inside (and on the ends: a step there has its other side at s0, s1).
    const auto first = std::lower_bound(opacity_.begin(), opacity_.end(), s0,
                                        [](const OpacityPoint& q, double x) { return q.s < x; });
    for (auto it = first; it != opacity_.end() && it->s <= s1; ++it) {
        if (it->a != 0) return false;
    }
    return true;
}

double TransferFunction::extinction_from_opacity(double a) const {
    return -std::log1p(-a) / unit_distance_;
}

double TransferFunction::mean_extinction(double s0, double s1) const {
    if (s0 > s1) std::swap(s0, s1);
    const std::vector<OpacityPoint>& p = opacity_;
    const std::size_t n = p.size();
    // Piece k is [p[k-1].s, p[k].s] for 0 < k < n; piece 0 is below p[0].s, piece n above
    // p[n-1].s (opacity constant there). piece_of(s): the first k with s < p[k].s (n if none).
    auto piece_of = [&](double s) {
        return static_cast<std::size_t>(
            std::upper_bound(p.begin(), p.end(), s,
                             [](double x, const OpacityPoint& q) { return x < q.s; }) -
            p.begin());
    };
    // The opacity at s in piece k, from that piece's own line (so a step, two points at one s,
    // is taken from the side the piece lies on).
    auto u_at = [&](std::size_t k, double s) {
        if (k == 0) return 1.0 - p.front().a;
        if (k == n) return 1.0 - p.back().a;
        const OpacityPoint& a = p[k - 1];
        const OpacityPoint& b = p[k];
        const double t = (s - a.s) / (b.s - a.s);
        return 1.0 - (a.a + (b.a - a.a) * t);
    };
    // Integral of -ln u over [x0, x1] inside piece k.
    auto part = [&](std::size_t k, double x0, double x1) {
        if (!(x1 > x0)) return 0.0;
        return (x1 - x0) * mean_neg_log(u_at(k, x0), u_at(k, x1));
    };
    const std::size_t k0 = piece_of(s0), k1 = piece_of(s1);
    if (k0 == k1 || !(s1 > s0)) return mean_neg_log(u_at(k0, s0), u_at(k0, s1)) / unit_distance_;
    // From s0 to the end of its piece, the whole pieces between, then to s1.
    double sum = part(k0, s0, p[k0].s) + part(k1, p[k1 - 1].s, s1);
    sum += integral_[k1 - 1] - integral_[k0];
    return sum / (s1 - s0) / unit_distance_;
}

double TransferFunction::s_min() const { return std::min(color_.front().s, opacity_.front().s); }
double TransferFunction::s_max() const { return std::max(color_.back().s, opacity_.back().s); }

Result<TransferFunction> log_scaled(const TransferFunction& over_log10, int samples) {
    const double a = over_log10.s_min(), b = over_log10.s_max();
    if (!(a >= -300.0 && b <= 300.0)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "a log scale takes control points in [-300, 300] (log10 of the scalar)");
    }
    if (samples < 2) {
        return make_error(ErrorCode::kInvalidArgument, "a log scale takes at least 2 samples");
    }
    std::vector<double> xs;
    for (int i = 0; i < samples; ++i) xs.push_back(a + (b - a) * i / (samples - 1));
    for (const ColorPoint& p : over_log10.color_points()) xs.push_back(p.s);
    for (const OpacityPoint& p : over_log10.opacity_points()) xs.push_back(p.s);
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    std::vector<ColorPoint> color;
    std::vector<OpacityPoint> opacity;
    for (double x : xs) {
        const double s = std::pow(10.0, x);
        color.push_back({s, over_log10.color(x)});
        opacity.push_back({s, over_log10.opacity(x)});
    }
    return TransferFunction::create(std::move(color), std::move(opacity),
                                    over_log10.unit_distance());
}

}  // namespace tr
