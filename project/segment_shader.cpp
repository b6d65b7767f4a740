#include <core/parallel.h>
#include <project/segment_shader.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

constexpr int kExpSize = 256;
constexpr int kPreScalars = 64;
constexpr int kPreLengths = 32;
// Sub-step limits of the direct integration: optical depth and scalar change per step.
constexpr double kMaxDepthStep = 0.02;
constexpr int kMaxSteps = 256;

}  // namespace

std::string_view integrator_name(Integrator integrator) {
    switch (integrator) {
        case Integrator::kExpTexture:
            return "exp-texture";
        case Integrator::kPreintegrated:
            return "preintegrated";
        case Integrator::kExact:
            return "exact";
    }
    return "?";
}

std::optional<Integrator> parse_integrator(std::string_view name) {
    for (Integrator i : {Integrator::kExpTexture, Integrator::kPreintegrated, Integrator::kExact}) {
        if (integrator_name(i) == name) return i;
    }
    return std::nullopt;
}

SegmentShader::SegmentShader(const TransferFunction& tf, Integrator integrator, double max_length)
    : tf_(tf), integrator_(integrator), max_length_(std::max(max_length, 1e-300)) {
    s_lo_ = tf.s_min();
    s_hi_ = tf.s_max();
    if (!(s_hi_ > s_lo_)) s_hi_ = s_lo_ + 1.0;
    scalar_scale_ = (kPreScalars - 1) / (s_hi_ - s_lo_);
    length_scale_ = (kPreLengths - 1) / max_length_;
    for (const auto& p : tf.color_points()) breakpoints_.push_back(p.s);
    for (const auto& p : tf.opacity_points()) breakpoints_.push_back(p.s);
    std::sort(breakpoints_.begin(), breakpoints_.end());
    breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
    kappa_max_ = 0.0;
    for (const auto& p : tf.opacity_points()) {
        kappa_max_ = std::max(kappa_max_, tf.extinction_from_opacity(p.a));
    }
    if (integrator == Integrator::kExpTexture) {
        // u in [0, max_length], v in [0, kappa_max]: texel (i, j) holds 1 - exp(-u_i v_j).
        exp_table_.resize(kExpSize * kExpSize);
        for (int j = 0; j < kExpSize; ++j) {
            const double v = kappa_max_ * j / (kExpSize - 1);
            for (int i = 0; i < kExpSize; ++i) {
                const double u = max_length_ * i / (kExpSize - 1);
                exp_table_[j * kExpSize + i] = static_cast<float>(1.0 - std::exp(-u * v));
            }
        }
    } else if (integrator == Integrator::kPreintegrated) {
        preint_table_.resize(static_cast<std::size_t>(kPreScalars) * kPreScalars * kPreLengths * 4);
        parallel_for(0, kPreScalars, 1, [&](std::size_t f) {
            for (int b = 0; b < kPreScalars; ++b) {
                const double sf = s_lo_ + (s_hi_ - s_lo_) * f / (kPreScalars - 1);
                const double sb = s_lo_ + (s_hi_ - s_lo_) * b / (kPreScalars - 1);
                for (int l = 0; l < kPreLengths; ++l) {
                    const double length = max_length_ * l / (kPreLengths - 1);
                    const ShadedSegment s = exact(sf, sb, length);
                    float* out = &preint_table_[((f * kPreScalars + b) * kPreLengths + l) * 4];
                    out[0] = s.color.x, out[1] = s.color.y, out[2] = s.color.z, out[3] = s.alpha;
                }
            }
        });
    }
}

SegmentShaderTables SegmentShader::tables() const {
    SegmentShaderTables t;
    t.exp_table = exp_table_;
    t.exp_size = exp_table_.empty() ? 0 : kExpSize;
    t.preint_table = preint_table_;
    t.pre_scalars = preint_table_.empty() ? 0 : kPreScalars;
    t.pre_lengths = preint_table_.empty() ? 0 : kPreLengths;
    t.s_lo = s_lo_;
    t.s_hi = s_hi_;
    t.max_length = max_length_;
    t.kappa_max = kappa_max_;
    return t;
}

ShadedSegment SegmentShader::shade(double s_front, double s_back, double length) const {
    switch (integrator_) {
        case Integrator::kExpTexture:
            return exp_texture(s_front, s_back, length);
        case Integrator::kPreintegrated:
            return preintegrated(s_front, s_back, length);
        case Integrator::kExact:
            return exact(s_front, s_back, length);
    }
    return {Vec3f(0.0f), 0.0f};
}

ShadedSegment SegmentShader::exact(double s_front, double s_back, double length) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    // Pieces between the control points the scalar crosses.
    double cuts[64];
    int num_cuts = 0;
    cuts[num_cuts++] = 0.0;
    if (s_front != s_back) {
        const double lo = std::min(s_front, s_back), hi = std::max(s_front, s_back);
        auto first = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), lo);
        for (auto it = first; it != breakpoints_.end() && *it < hi && num_cuts < 62; ++it) {
            cuts[num_cuts++] = (*it - s_front) / (s_back - s_front);
        }
        std::sort(cuts, cuts + num_cuts);
    }
    cuts[num_cuts++] = 1.0;
    Vec3 color(0.0);
    double transparency = 1.0;
    for (int p = 0; p + 1 < num_cuts; ++p) {
        const double u0 = cuts[p], u1 = cuts[p + 1];
        if (!(u1 > u0)) continue;
        const double piece = (u1 - u0) * length;
        const double s0 = s_front + (s_back - s_front) * u0;
        const double s1 = s_front + (s_back - s_front) * u1;
        const double k_max = std::max(tf_.extinction(s0), tf_.extinction(s1));
        const int steps =
            std::clamp(static_cast<int>(std::ceil(k_max * piece / kMaxDepthStep)), 4, kMaxSteps);
        const double h = piece / steps;
        for (int i = 0; i < steps; ++i) {
            const double s = s0 + (s1 - s0) * (i + 0.5) / steps;  // midpoint
            const double alpha = -std::expm1(-tf_.extinction(s) * h);
            color += transparency * alpha * tf_.color(s);
            transparency *= 1.0 - alpha;
        }
    }
    return {Vec3f(color), static_cast<float>(1.0 - transparency)};
}

ShadedSegment SegmentShader::exp_texture(double s_front, double s_back, double length) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    if (length > max_length_ || kappa_max_ <= 0) return exact(s_front, s_back, length);
    const double v = 0.5 * (tf_.extinction(s_front) + tf_.extinction(s_back));
    const double x = length / max_length_ * (kExpSize - 1);
    const double y = v / kappa_max_ * (kExpSize - 1);
    const int i = std::min(static_cast<int>(x), kExpSize - 2);
    const int j = std::min(static_cast<int>(y), kExpSize - 2);
    const double fx = x - i, fy = y - j;
    const float* t = &exp_table_[j * kExpSize + i];
    const double alpha = (1 - fy) * ((1 - fx) * t[0] + fx * t[1]) +
                         fy * ((1 - fx) * t[kExpSize] + fx * t[kExpSize + 1]);
    const Vec3 c = tf_.color(0.5 * (s_front + s_back));
    return {Vec3f(c * alpha), static_cast<float>(alpha)};
}

ShadedSegment SegmentShader::preintegrated(double s_front, double s_back, double length) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    if (length > max_length_) return exact(s_front, s_back, length);
    // Trilinear in (front, back, length), in single precision: the table holds floats.
    const float top = static_cast<float>(kPreScalars - 1);
    const float x = std::clamp(static_cast<float>((s_front - s_lo_) * scalar_scale_), 0.0f, top);
    const float y = std::clamp(static_cast<float>((s_back - s_lo_) * scalar_scale_), 0.0f, top);
    const float z = static_cast<float>(length * length_scale_);
    const int i = std::min(static_cast<int>(x), kPreScalars - 2);
    const int j = std::min(static_cast<int>(y), kPreScalars - 2);
    const int k = std::min(static_cast<int>(z), kPreLengths - 2);
    const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
    const float fz = z - static_cast<float>(k);
    const glm::vec4* t = reinterpret_cast<const glm::vec4*>(preint_table_.data()) +
                         (static_cast<std::size_t>(i) * kPreScalars + j) * kPreLengths + k;
    constexpr std::size_t kDy = kPreLengths;
    constexpr std::size_t kDx = static_cast<std::size_t>(kPreScalars) * kPreLengths;
    const glm::vec4 c00 = glm::mix(t[0], t[1], fz);
    const glm::vec4 c01 = glm::mix(t[kDy], t[kDy + 1], fz);
    const glm::vec4 c10 = glm::mix(t[kDx], t[kDx + 1], fz);
    const glm::vec4 c11 = glm::mix(t[kDx + kDy], t[kDx + kDy + 1], fz);
    const glm::vec4 out = glm::mix(glm::mix(c00, c01, fy), glm::mix(c10, c11, fy), fx);
    return {Vec3f(out), out.w};
}

}  // namespace tr
