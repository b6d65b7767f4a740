#include <core/parallel.h>
#include <project/detail/preintegration.h>
#include <project/segment_shader.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <tuple>

namespace tr {
namespace {

using detail::kExtinctionRefine;
using detail::kExtinctionScalars;
using detail::kMeanDepths;
using detail::kMeanScalars;

constexpr int kExpSize = 256;
// The (front, back, length) table of tables(), for the OpenGL renderer.
constexpr int kPreScalars = 64;
constexpr int kPreLengths = 32;
// kExact's sub-steps: optical depth per step, steps per piece between control points.
constexpr double kMaxDepthStep = 0.02;
constexpr int kMaxSteps = 256;

// 2^(-j/64), j = 0..63.
struct Exp2Table {
    float v[64];
    Exp2Table() {
        for (int j = 0; j < 64; ++j) v[j] = static_cast<float>(std::exp2(-j / 64.0));
    }
};
const Exp2Table kExp2Neg;

// exp(-x) for x >= 0 in single precision without a library call (the default integrator's one
// exponential per fragment): 2^(-k/64) e^-g with k = round(64 x / ln 2), |g| <= ln(2) / 128,
// e^-g ~ 1 - g + g^2 / 2 (error below 3e-8); 1 - exp_neg(x) is within 2e-7 of 1 - exp(-x).
// 0 beyond x = 87.
inline float exp_neg(float x) {
    if (!(x < 87.0f)) return 0.0f;
    const float t = x * 92.3324826f;  // 64 / ln 2
    const int k = static_cast<int>(t + 0.5f);
    const float g = (t - static_cast<float>(k)) * 0.0108304247f;  // ln 2 / 64
    const float p = 1.0f - g + 0.5f * g * g;
    return p * kExp2Neg.v[k & 63] *
           std::bit_cast<float>(static_cast<std::uint32_t>(127 - (k >> 6)) << 23);
}

// Four floats for the trilinear lookup (GCC / Clang vector extension: SSE, NEON, or scalar).
using Float4 = float __attribute__((vector_size(16)));
inline Float4 load4(const glm::vec4* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline Float4 mix4(Float4 a, Float4 b, float t) { return a + (b - a) * t; }

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
    // An edge of a mesh with coordinates beyond 1e154 overflows to inf: the largest double
    // instead, so that the exp texture's coordinates (length / max_length) stay finite (inf /
    // inf made its index NaN, cast to int: a read far outside the table).
    : tf_(tf),
      integrator_(integrator),
      max_length_(std::isfinite(max_length) ? std::max(max_length, 1e-300)
                                            : std::numeric_limits<double>::max()) {
    s_lo_ = tf.s_min();
    s_hi_ = tf.s_max();
    if (!(s_hi_ > s_lo_)) s_hi_ = s_lo_ + 1.0;
    for (const auto& p : tf.color_points()) breakpoints_.push_back(p.s);
    for (const auto& p : tf.opacity_points()) breakpoints_.push_back(p.s);
    std::sort(breakpoints_.begin(), breakpoints_.end());
    breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
    kappa_max_ = 0.0;
    for (const auto& p : tf.opacity_points()) {
        kappa_max_ = std::max(kappa_max_, tf.extinction_from_opacity(p.a));
    }
    if (integrator == Integrator::kExpTexture) {
        exp_u_scale_ = (kExpSize - 1) / max_length_;
        exp_v_scale_ = (kExpSize - 1) / kappa_max_;  // +inf for kappa_max 0 or subnormal
        // u in [0, max_length], v in [0, kappa_max]: texel (i, j) holds 1 - exp(-u_i v_j).
        exp_table_.resize(kExpSize * kExpSize);
        for (int j = 0; j < kExpSize; ++j) {
            // Fractions first: kappa_max * j overflows near the largest double (then inf * 0).
            const double v = kappa_max_ * (static_cast<double>(j) / (kExpSize - 1));
            for (int i = 0; i < kExpSize; ++i) {
                const double u = max_length_ * (static_cast<double>(i) / (kExpSize - 1));
                exp_table_[j * kExpSize + i] = static_cast<float>(1.0 - std::exp(-u * v));
            }
        }
    } else if (integrator == Integrator::kPreintegrated) {
        auto pre = std::make_shared<detail::Preintegration>();
        detail::build_preintegration(tf, breakpoints_, s_lo_, s_hi_, *pre);
        pre_ = std::move(pre);
        gl_table_ = std::make_shared<detail::LazyPreintTable>();
    }
}

std::size_t SegmentShader::direct_cells() const { return pre_ ? pre_->direct_cells : 0; }

std::size_t SegmentShader::table_cells() const {
    return pre_
               ? static_cast<std::size_t>(kMeanScalars - 1) * (kMeanScalars - 1) * (kMeanDepths - 1)
               : 0;
}

SegmentShaderTables SegmentShader::tables() const {
    if (integrator_ == Integrator::kPreintegrated) {
        // The (front, back, length) table, built on first use (the CPU renderer never asks).
        std::call_once(gl_table_->once, [&] {
            std::vector<float>& table = gl_table_->table;
            table.resize(static_cast<std::size_t>(kPreScalars) * kPreScalars * kPreLengths * 4);
            parallel_for(0, kPreScalars, 1, [&](std::size_t f) {
                for (int b = 0; b < kPreScalars; ++b) {
                    const double sf = s_lo_ + (s_hi_ - s_lo_) * f / (kPreScalars - 1);
                    const double sb = s_lo_ + (s_hi_ - s_lo_) * b / (kPreScalars - 1);
                    for (int l = 0; l < kPreLengths; ++l) {
                        const double length = max_length_ * l / (kPreLengths - 1);
                        const ShadedSegment s = preintegrated(sf, sb, length);
                        float* out = &table[((f * kPreScalars + b) * kPreLengths + l) * 4];
                        out[0] = s.color.x, out[1] = s.color.y, out[2] = s.color.z;
                        out[3] = s.alpha;
                    }
                }
            });
        });
    }
    SegmentShaderTables t;
    t.exp_table = exp_table_;
    t.exp_size = exp_table_.empty() ? 0 : kExpSize;
    if (gl_table_) t.preint_table = gl_table_->table;
    t.pre_scalars = t.preint_table.empty() ? 0 : kPreScalars;
    t.pre_lengths = t.preint_table.empty() ? 0 : kPreLengths;
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
            if (s_front >= s_lo_ && s_front <= s_hi_ && s_back >= s_lo_ && s_back <= s_hi_) {
                return preintegrated_inside(s_front, s_back, length);
            }
            return preintegrated(s_front, s_back, length);
        case Integrator::kExact:
            return exact(s_front, s_back, length);
    }
    return {Vec3f(0.0f), 0.0f};
}

ShadedSegment SegmentShader::exact(double s_front, double s_back, double length) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    Vec3 color(0.0);
    double transparency = 1.0;
    // One piece, from u0 to u1 (fractions of the segment), with no control point inside. Once
    // the transparency is below kOpaque, what lies behind adds less than that: stop.
    constexpr double kOpaque = 1e-7;
    auto piece = [&](double u0, double u1) {
        if (!(u1 > u0) || transparency < kOpaque) return;
        const double piece_length = (u1 - u0) * length;
        const double s0 = s_front + (s_back - s_front) * u0;
        const double s1 = s_front + (s_back - s_front) * u1;
        const double k_max = std::max(tf_.extinction(s0), tf_.extinction(s1));
        // (Clamped before the conversion: a long, thick piece would overflow an int. A clear
        // piece of infinite length, 0 * inf, is NaN: 4 steps.)
        const double wanted = std::ceil(k_max * piece_length / kMaxDepthStep);
        const int steps =
            static_cast<int>(std::isnan(wanted) ? 4.0 : std::clamp(wanted, 4.0, double{kMaxSteps}));
        const double h = piece_length / steps;
        for (int i = 0; i < steps; ++i) {
            const double s = s0 + (s1 - s0) * (i + 0.5) / steps;  // midpoint
            // Zero extinction over an infinite step absorbs nothing (0 * inf would be NaN).
            const double depth = tf_.extinction(s) * h;
            const double alpha = depth > 0 ? -std::expm1(-depth) : 0.0;
            color += transparency * alpha * tf_.color(s);
            transparency *= 1.0 - alpha;
            if (transparency < kOpaque) break;
        }
    };
    // Split where the scalar crosses a control point, in the order the ray meets them.
    double u = 0.0;
    if (s_front != s_back) {
        const double lo = std::min(s_front, s_back), hi = std::max(s_front, s_back);
        const auto first = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), lo);
        const auto last = std::lower_bound(first, breakpoints_.end(), hi);
        auto cross = [&](double b) {
            const double next = (b - s_front) / (s_back - s_front);
            piece(u, next);
            u = std::max(u, next);
        };
        if (s_back > s_front) {
            for (auto it = first; it != last; ++it) cross(*it);
        } else {
            for (auto it = last; it != first; --it) cross(*(it - 1));
        }
    }
    piece(u, 1.0);
    return {Vec3f(color), static_cast<float>(1.0 - transparency)};
}

ShadedSegment SegmentShader::exp_texture(double s_front, double s_back, double length) const {
    // Halves added (two extinctions near the largest double would sum to inf).
    const double v = 0.5 * tf_.extinction(s_front) + 0.5 * tf_.extinction(s_back);
    return exp_texture_at(length, v, 0.5 * (s_front + s_back), s_front, s_back);
}

ShadedSegment SegmentShader::exp_texture_at(double length, double mean_extinction, double s_mean,
                                            double s_front, double s_back) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    // An infinite largest extinction (a unit distance of 1e-320 makes -ln(1 - a) / d
    // overflow): the texture's row v / kappa_max would be inf / inf; integrated directly.
    // (A kappa_max of 0 or too small for its reciprocal leaves exp_v_scale_ infinite.)
    if (length > max_length_ || !std::isfinite(kappa_max_) || !std::isfinite(exp_v_scale_) ||
        !std::isfinite(mean_extinction))
        return exact(s_front, s_back, length);
    // The row at most the last: v <= kappa_max up to rounding.
    const double x = std::min(length * exp_u_scale_, double{kExpSize - 1});
    const double y = std::clamp(mean_extinction * exp_v_scale_, 0.0, double{kExpSize - 1});
    const int i = std::min(static_cast<int>(x), kExpSize - 2);
    const int j = std::min(static_cast<int>(y), kExpSize - 2);
    const double fx = x - i, fy = y - j;
    const float* t = &exp_table_[j * kExpSize + i];
    const double alpha = (1 - fy) * ((1 - fx) * t[0] + fx * t[1]) +
                         fy * ((1 - fx) * t[kExpSize] + fx * t[kExpSize + 1]);
    const Vec3 c = tf_.color(s_mean);
    return {Vec3f(c * alpha), static_cast<float>(alpha)};
}

ShadedSegment SegmentShader::preintegrated(double s_front, double s_back, double length) const {
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    const bool front_in = s_front >= s_lo_ && s_front <= s_hi_;
    const bool back_in = s_back >= s_lo_ && s_back <= s_hi_;
    if (front_in && back_in) return preintegrated_inside(s_front, s_back, length);
    // Beyond the control points colour and extinction are constant: cut the segment where it
    // leaves [s_lo, s_hi] and composite its parts, the outer ones uniform slabs.
    double cuts[4] = {0.0, 1.0, 1.0, 1.0};
    int num_cuts = 1;
    for (double s : {s_lo_, s_hi_}) {
        const double u = (s - s_front) / (s_back - s_front);
        if (u > 0 && u < 1) cuts[num_cuts++] = u;
    }
    if (num_cuts == 3 && cuts[2] < cuts[1]) std::swap(cuts[1], cuts[2]);
    cuts[num_cuts++] = 1.0;
    Vec3f color(0.0f);
    float transparency = 1.0f;
    for (int p = 0; p + 1 < num_cuts; ++p) {
        const double u0 = cuts[p], u1 = cuts[p + 1];
        if (!(u1 > u0)) continue;
        const double part_length = (u1 - u0) * length;
        const double s0 = s_front + (s_back - s_front) * u0;
        const double s1 = s_front + (s_back - s_front) * u1;
        const double mid = 0.5 * (s0 + s1);
        ShadedSegment part;
        if (mid < s_lo_ || mid > s_hi_) {
            const double alpha = -std::expm1(-tf_.extinction(mid) * part_length);
            part = {Vec3f(tf_.color(mid) * alpha), static_cast<float>(alpha)};
        } else {
            part = preintegrated_inside(std::clamp(s0, s_lo_, s_hi_), std::clamp(s1, s_lo_, s_hi_),
                                        part_length);
        }
        color += transparency * part.color;
        transparency *= 1.0f - part.alpha;
    }
    return {color, 1.0f - transparency};
}

// The mean extinction of a segment with both scalars in [s_lo_, s_hi_] at table coordinates
// (x, y): bilinear from a table kExtinctionRefine times finer than the mean colour's, or the
// closed form where the cell says so.
[[gnu::always_inline]] inline float SegmentShader::table_extinction(double s_front, double s_back,
                                                                    float x, float y) const {
    constexpr int m = kExtinctionScalars;
    const detail::Preintegration& pre = *pre_;
    const float xe = x * kExtinctionRefine, ye = y * kExtinctionRefine;
    const int ie = std::min(static_cast<int>(xe), m - 2);
    const int je = std::min(static_cast<int>(ye), m - 2);
    if (pre.extinction_closed_form[static_cast<std::size_t>(ie) * (m - 1) + je]) [[unlikely]] {
        return closed_form_extinction(s_front, s_back);
    }
    const float ex = xe - static_cast<float>(ie), ey = ye - static_cast<float>(je);
    const float* e = &pre.mean_extinction[static_cast<std::size_t>(ie) * m + je];
    const float e0 = e[0] + (e[1] - e[0]) * ey, e1 = e[m] + (e[m + 1] - e[m]) * ey;
    return e0 + (e1 - e0) * ex;
}

[[gnu::noinline]] float SegmentShader::closed_form_extinction(double s_front, double s_back) const {
    return static_cast<float>(tf_.mean_extinction(s_front, s_back));
}

// kPreintegrated for scalars in [s_lo_, s_hi_]: opacity 1 - exp(-tau) from the mean
// extinction, mean colour trilinear in (front, back, r). Single precision.
[[gnu::always_inline]] inline ShadedSegment SegmentShader::preintegrated_inside(
    double s_front, double s_back, double length) const {
    const float x = pre_->axis.coordinate(s_front), y = pre_->axis.coordinate(s_back);
    const float tau = static_cast<float>(length) * table_extinction(s_front, s_back, x, y);
    return preintegrated_finish(s_front, s_back, length, tau, x, y);
}

[[gnu::noinline]] ShadedSegment SegmentShader::direct(double s_front, double s_back,
                                                      double length) const {
    const double tau = length * tf_.mean_extinction(s_front, s_back);
    if (!(tau > 0)) return {Vec3f(0.0f), 0.0f};
    thread_local std::vector<detail::SegmentColors::Piece> storage;
    const detail::SegmentColors colors(tf_, breakpoints_, s_front, s_back, storage);
    const double alpha = -std::expm1(-tau);
    const double r = tau < std::numeric_limits<double>::infinity() ? tau / (1.0 + tau) : 1.0;
    return {Vec3f(colors.mean_color(r) * alpha), static_cast<float>(alpha)};
}

inline ShadedSegment SegmentShader::preintegrated_finish(double s_front, double s_back,
                                                         double length, float tau, float x,
                                                         float y) const {
    constexpr int n = kMeanScalars;
    if (!(tau > 0)) return {Vec3f(0.0f), 0.0f};
    const float alpha = 1.0f - exp_neg(tau);
    // r = tau / (1 + tau), 1 for an infinite depth (a segment longer than a float, 3.4e38:
    // inf / inf was NaN, cast to int, a read outside the table).
    const float r = tau < std::numeric_limits<float>::infinity() ? tau / (1.0f + tau) : 1.0f;
    const float z = r * static_cast<float>(kMeanDepths - 1);
    const int i = std::min(static_cast<int>(x), n - 2);
    const int j = std::min(static_cast<int>(y), n - 2);
    const int k = std::min(static_cast<int>(z), kMeanDepths - 2);
    const glm::vec4* t =
        pre_->mean_color.data() + (static_cast<std::size_t>(i) * n + j) * kMeanDepths + k;
    if (t->w != 0.0f) [[unlikely]] {
        return direct(s_front, s_back, length);
    }
    const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
    const float fz = z - static_cast<float>(k);
    constexpr std::size_t kDy = kMeanDepths;
    constexpr std::size_t kDx = static_cast<std::size_t>(n) * kMeanDepths;
    const Float4 c00 = mix4(load4(t), load4(t + 1), fz);
    const Float4 c01 = mix4(load4(t + kDy), load4(t + kDy + 1), fz);
    const Float4 c10 = mix4(load4(t + kDx), load4(t + kDx + 1), fz);
    const Float4 c11 = mix4(load4(t + kDx + kDy), load4(t + kDx + kDy + 1), fz);
    const Float4 c = mix4(mix4(c00, c01, fy), mix4(c10, c11, fy), fx) * alpha;
    return {Vec3f(c[0], c[1], c[2]), alpha};
}

void SegmentShader::shade(std::span<const SegmentQuery> queries,
                          std::span<ShadedSegment> out) const {
    if (integrator_ != Integrator::kPreintegrated) {
        for (std::size_t i = 0; i < queries.size(); ++i) {
            out[i] = shade(queries[i].s_front, queries[i].s_back, queries[i].length);
        }
        return;
    }
    // In two passes over chunks, so that the processor overlaps more segments (the dependent
    // lookups are long): optical depth and table coordinates, then opacity and mean colour.
    constexpr std::size_t kChunk = 64;
    struct Stage {
        float x, y, tau;
        bool inside;  // both scalars in [s_lo_, s_hi_]; otherwise preintegrated() shades it
    };
    Stage stage[kChunk];
    for (std::size_t begin = 0; begin < queries.size(); begin += kChunk) {
        const std::size_t end = std::min(begin + kChunk, queries.size());
        for (std::size_t i = begin; i < end; ++i) {
            const SegmentQuery& q = queries[i];
            Stage& st = stage[i - begin];
            st.inside =
                q.s_front >= s_lo_ && q.s_front <= s_hi_ && q.s_back >= s_lo_ && q.s_back <= s_hi_;
            if (!st.inside) continue;
            st.x = pre_->axis.coordinate(q.s_front), st.y = pre_->axis.coordinate(q.s_back);
            st.tau =
                static_cast<float>(q.length) * table_extinction(q.s_front, q.s_back, st.x, st.y);
        }
        for (std::size_t i = begin; i < end; ++i) {
            const SegmentQuery& q = queries[i];
            const Stage& st = stage[i - begin];
            out[i] = st.inside
                         ? preintegrated_finish(q.s_front, q.s_back, q.length, st.tau, st.x, st.y)
                         : preintegrated(q.s_front, q.s_back, q.length);
        }
    }
}

}  // namespace tr