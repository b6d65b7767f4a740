#include <core/parallel.h>
#include <project/detail/preintegration.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tr::detail {
namespace {

// A table cell whose measured interpolation error (largest channel) exceeds this has its
// segments integrated directly. The error is sampled (centre, face centres, edge midpoints; a 3 x 3
// grid where the cell touches a control point on the diagonal), not bounded: the largest error
// found between samples, over random segments through the tests' transfer functions, is 0.35 of
// a level with this threshold (tests/project/segment_shader_test.cpp), within the half level the
// default integrator promises.
constexpr double kMaxColorError = 0.3 / 255.0;
// A (front, back) cell whose mean extinction, interpolated, is off by more than this relative
// error (measured) takes the closed form instead: it moves the opacity by at most this / e.
constexpr double kMaxExtinctionError = 2e-4;
// Front-scalar cells across which the extinction changes by more than this factor have their
// segments that are not optically thin (r beyond the first cell) integrated directly.
constexpr double kMaxExtinctionRatio = 5.0;

// Fills p.mean_extinction and p.extinction_closed_form (p.axis built).
void build_mean_extinction(const TransferFunction& tf, Preintegration& p) {
    constexpr int n = kExtinctionScalars;
    // Scalars at every half step of the table's axis (kExtinctionRefine steps per colour node).
    std::vector<double> half(2 * n - 1);
    for (int h = 0; h < 2 * n - 1; ++h) half[h] = p.axis.node(h / (2.0 * kExtinctionRefine));
    p.mean_extinction.assign(static_cast<std::size_t>(n) * n, 0.0f);
    p.extinction_closed_form.assign(static_cast<std::size_t>(n - 1) * (n - 1), 0);
    parallel_for(0, n, 1, [&](std::size_t row) {
        const int i = static_cast<int>(row);
        for (int j = 0; j < n; ++j) {
            p.mean_extinction[static_cast<std::size_t>(i) * n + j] =
                static_cast<float>(tf.mean_extinction(half[2 * i], half[2 * j]));
        }
    });
    // Each cell's relative interpolation error, at its centre and edge midpoints. The opacity's
    // error from a relative error d of the optical depth is at most d * tau * exp(-tau) <= d / e,
    // the mean colour's (through r) at most d / 4 times its change across r: a cell is
    // interpolated where d <= kMaxExtinctionError, otherwise the closed form is used.
    parallel_for(0, n - 1, 1, [&](std::size_t row) {
        const int i = static_cast<int>(row);
        auto node = [&](int a, int b) {
            return static_cast<double>(p.mean_extinction[static_cast<std::size_t>(a) * n + b]);
        };
        for (int j = 0; j < n - 1; ++j) {
            double worst = 0.0;
            const int halves[5][2] = {{1, 1}, {1, 0}, {1, 2}, {0, 1}, {2, 1}};
            for (const auto& f : halves) {
                const double truth = tf.mean_extinction(half[2 * i + f[0]], half[2 * j + f[1]]);
                const double u = 0.5 * f[0], v = 0.5 * f[1];
                const double interpolated = (1 - u) * ((1 - v) * node(i, j) + v * node(i, j + 1)) +
                                            u * ((1 - v) * node(i + 1, j) + v * node(i + 1, j + 1));
                const double error = std::abs(interpolated - truth);
                worst = std::max(worst, truth > 0 ? error / truth : error > 0 ? 1.0 : 0.0);
            }
            p.extinction_closed_form[static_cast<std::size_t>(i) * (n - 1) + j] =
                !(worst <= kMaxExtinctionError);
        }
    });
}

// Fills p.mean_color and p.direct_cells (p.axis built).
void build_mean_color(const TransferFunction& tf, std::span<const double> breakpoints,
                      Preintegration& p) {
    constexpr int n = kMeanScalars, nr = kMeanDepths;
    constexpr int halves = 2 * nr - 1;  // r at every node and every midpoint between nodes
    // Mean colours at the nodes' (front, back) pairs and at the cells' centre pairs, each at
    // every half step of r; whether each pair's segment absorbs at all.
    std::vector<Vec3f> at_nodes(static_cast<std::size_t>(n) * n * halves);
    std::vector<Vec3f> at_centres(static_cast<std::size_t>(n - 1) * (n - 1) * halves);
    std::vector<std::uint8_t> node_absorbs(static_cast<std::size_t>(n) * n);
    std::vector<std::uint8_t> centre_absorbs(static_cast<std::size_t>(n - 1) * (n - 1));
    auto scalar = [&](double i) { return p.axis.node(i); };
    parallel_for(0, 2 * n - 1, 1, [&](std::size_t row) {
        // Even rows: node rows i = row / 2; odd rows: centre rows i + 1/2.
        const bool centre = row % 2 == 1;
        const int i = static_cast<int>(row / 2);
        std::vector<SegmentColors::Piece> storage;
        const int count = centre ? n - 1 : n;
        for (int j = 0; j < count; ++j) {
            const double sf = scalar(i + (centre ? 0.5 : 0.0));
            const double sb = scalar(j + (centre ? 0.5 : 0.0));
            const SegmentColors colors(tf, breakpoints, sf, sb, storage);
            const std::size_t pair = static_cast<std::size_t>(i) * count + j;
            (centre ? centre_absorbs : node_absorbs)[pair] = colors.absorbs();
            Vec3f* out = &(centre ? at_centres : at_nodes)[pair * halves];
            for (int h = 0; h < halves; ++h) out[h] = Vec3f(colors.mean_color(h / (halves - 1.0)));
        }
    });
    p.mean_color.assign(static_cast<std::size_t>(n) * n * nr, glm::vec4(0.0f));
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < nr; ++k) {
                const Vec3f& c = at_nodes[(static_cast<std::size_t>(i) * n + j) * halves + 2 * k];
                p.mean_color[(static_cast<std::size_t>(i) * n + j) * nr + k] = glm::vec4(c, 0.0f);
            }
        }
    }
    // Front-scalar cells across which the extinction changes by more than kMaxExtinctionRatio:
    // there the mean colour of a segment more than thin (r beyond the first cell) follows the
    // extinction just behind the front, which interpolation between the cell's ends misses.
    std::vector<std::uint8_t> steep(n - 1, 0);
    for (int i = 0; i + 1 < n; ++i) {
        const double s0 = p.axis.node(i), s1 = p.axis.node(i + 1), nudge = 1e-9 * (s1 - s0);
        double k_min = std::numeric_limits<double>::infinity(), k_max = 0.0;
        auto take = [&](double k) { k_min = std::min(k_min, k), k_max = std::max(k_max, k); };
        take(tf.extinction(s0 + nudge));
        take(tf.extinction(s1 - nudge));
        for (const OpacityPoint& p : tf.opacity_points()) {
            if (p.s > s0 && p.s < s1) take(tf.extinction_from_opacity(p.a));
        }
        steep[i] = k_max > kMaxExtinctionRatio * k_min;
    }
    // Each cell's interpolation error, sampled where trilinear interpolation strays most from
    // a smooth function: the centre, the centres of the two faces across r, the midpoints of
    // the four edges along r.
    std::vector<std::uint8_t> direct(static_cast<std::size_t>(n - 1) * (n - 1) * (nr - 1), 0);
    parallel_for(0, n - 1, 1, [&](std::size_t row) {
        const int i = static_cast<int>(row);
        std::vector<SegmentColors::Piece> storage;
        auto node = [&](int a, int b, int h) {
            return at_nodes[(static_cast<std::size_t>(a) * n + b) * halves + h];
        };
        auto error = [](const Vec3f& a, const Vec3f& b) {
            const Vec3f d = glm::abs(a - b);
            return std::max({d.x, d.y, d.z});
        };
        for (int j = 0; j < n - 1; ++j) {
            const std::size_t centre_pair = static_cast<std::size_t>(i) * (n - 1) + j;
            const bool a00 = node_absorbs[static_cast<std::size_t>(i) * n + j];
            const bool a01 = node_absorbs[static_cast<std::size_t>(i) * n + j + 1];
            const bool a10 = node_absorbs[static_cast<std::size_t>(i + 1) * n + j];
            const bool a11 = node_absorbs[static_cast<std::size_t>(i + 1) * n + j + 1];
            // A corner whose segment (front != back) does not absorb holds the plain mean
            // colour, which need not be the limit of its neighbours' mean colours: if any other
            // corner or the centre absorbs, the cell's segments are integrated directly. (A corner
            // on the diagonal is a point, whose colour is the limit.)
            const bool any = a00 || a01 || a10 || a11 || centre_absorbs[centre_pair];
            const bool mixed = any && ((!a00 && i != j) || (!a01 && i != j + 1) ||
                                       (!a10 && i + 1 != j) || (!a11 && i != j));
            const Vec3f* c = &at_centres[centre_pair * halves];
            // A cell whose corner on the diagonal is a control point holds segments crossing it
            // at any fraction of their length, which the mean colour does not follow smoothly:
            // sampled on a 3 x 3 grid of (front, back) pairs at every half step of r.
            std::vector<float> corner_error(nr - 1, 0.0f);
            if ((i + 1 == j && p.axis.is_knot(j)) || (j + 1 == i && p.axis.is_knot(i))) {
                for (int a = 1; a <= 3; ++a) {
                    for (int b = 1; b <= 3; ++b) {
                        const double u = a / 4.0, v = b / 4.0;
                        const SegmentColors colors(tf, breakpoints, scalar(i + u), scalar(j + v),
                                                   storage);
                        for (int h = 0; h < halves; ++h) {
                            const int k = std::min(h / 2, nr - 2);
                            const float w = (h - 2 * k) / 2.0f;
                            auto layer = [&](int hh) {
                                return (1 - static_cast<float>(u)) *
                                           ((1 - static_cast<float>(v)) * node(i, j, hh) +
                                            static_cast<float>(v) * node(i, j + 1, hh)) +
                                       static_cast<float>(u) *
                                           ((1 - static_cast<float>(v)) * node(i + 1, j, hh) +
                                            static_cast<float>(v) * node(i + 1, j + 1, hh));
                            };
                            const Vec3f interpolated =
                                (1 - w) * layer(2 * k) + w * layer(2 * k + 2);
                            const float e =
                                error(Vec3f(colors.mean_color(h / (halves - 1.0))), interpolated);
                            corner_error[k] = std::max(corner_error[k], e);
                            if (h % 2 == 0 && k > 0 && h == 2 * k) {
                                corner_error[k - 1] = std::max(corner_error[k - 1], e);
                            }
                        }
                    }
                }
            }
            for (int k = 0; k < nr - 1; ++k) {
                const int h0 = 2 * k, h1 = 2 * k + 2;
                auto face = [&](int h) {
                    return 0.25f * (node(i, j, h) + node(i + 1, j, h) + node(i, j + 1, h) +
                                    node(i + 1, j + 1, h));
                };
                float e =
                    std::max({error(c[h0 + 1], 0.5f * (face(h0) + face(h1))),
                              error(c[h0], face(h0)), error(c[h1], face(h1)), corner_error[k]});
                for (int a = i; a <= i + 1; ++a) {
                    for (int b = j; b <= j + 1; ++b) {
                        e = std::max(
                            e, error(node(a, b, h0 + 1), 0.5f * (node(a, b, h0) + node(a, b, h1))));
                    }
                }
                direct[centre_pair * (nr - 1) + k] =
                    mixed || e > kMaxColorError || (k > 0 && steep[i]);
            }
        }
    });
    p.direct_cells = 0;
    for (int i = 0; i < n - 1; ++i) {
        for (int j = 0; j < n - 1; ++j) {
            for (int k = 0; k < nr - 1; ++k) {
                if (!direct[(static_cast<std::size_t>(i) * (n - 1) + j) * (nr - 1) + k]) continue;
                p.mean_color[(static_cast<std::size_t>(i) * n + j) * nr + k].w = 1.0f;
                ++p.direct_cells;
            }
        }
    }
}

}  // namespace

void ScalarAxis::build(const TransferFunction& tf, std::span<const double> breakpoints, double s_lo,
                       double s_hi, int nodes) {
    const int cells = nodes - 1;
    knots_.clear();
    for (double b : breakpoints) {
        if (b > s_lo && b < s_hi) knots_.push_back(b);
    }
    const bool aligned = static_cast<int>(knots_.size()) + 1 <= cells / 3;
    if (!aligned) knots_.clear();  // too many control points: uniform
    knots_.insert(knots_.begin(), s_lo);
    knots_.push_back(s_hi);
    // Where the opacity falls to zero at a control point (or to a small fraction of the far
    // end's), segments starting there have a mean colour that changes sharply with the front
    // scalar: extra knots at 1/256, 1/64 and 1/16 of the way to the next control point make the
    // cells there narrow (their extinction changes by a bounded factor, except in the first).
    if (aligned) {
        std::vector<double> extra;
        for (std::size_t k = 0; k + 1 < knots_.size(); ++k) {
            const double a = knots_[k], b = knots_[k + 1];
            // The opacity's line on [a, b], from two interior points (an end may be a step).
            const double oa = tf.opacity(a + 0.25 * (b - a)), ob = tf.opacity(a + 0.75 * (b - a));
            const double ka =
                tf.extinction_from_opacity(std::clamp(1.5 * oa - 0.5 * ob, 0.0, 1.0 - 1e-12));
            const double kb =
                tf.extinction_from_opacity(std::clamp(1.5 * ob - 0.5 * oa, 0.0, 1.0 - 1e-12));
            for (const auto& [from, to, k_from, k_to] :
                 {std::tuple{a, b, ka, kb}, std::tuple{b, a, kb, ka}}) {
                if (!(k_from * 64.0 < k_to)) continue;
                for (double f : {1.0 / 256, 1.0 / 64, 1.0 / 16}) {
                    extra.push_back(from + (to - from) * f);
                }
            }
        }
        if (static_cast<int>(knots_.size() + extra.size()) + 1 <= cells) {
            knots_.insert(knots_.end(), extra.begin(), extra.end());
            std::sort(knots_.begin(), knots_.end());
        }
    }
    // Cells per interval: in proportion to its length, at least one each (largest share first).
    const std::size_t m = knots_.size() - 1;
    std::vector<int> count(m, 1);
    for (int given = static_cast<int>(m); given < cells; ++given) {
        std::size_t best = 0;
        for (std::size_t k = 1; k < m; ++k) {
            if ((knots_[k + 1] - knots_[k]) / count[k] >
                (knots_[best + 1] - knots_[best]) / count[best]) {
                best = k;
            }
        }
        ++count[best];
    }
    nodes_.assign(m + 1, 0.0);
    for (std::size_t k = 0; k < m; ++k) nodes_[k + 1] = nodes_[k] + count[k];
    // Uniform bins, several per cell, each with the interval its start lies in and the next.
    const std::size_t num_bins = 8 * static_cast<std::size_t>(cells);
    s_lo_ = s_lo;
    bin_scale_ = static_cast<float>(num_bins / (s_hi - s_lo));
    bins_.assign(num_bins, Bin{});
    last_bin_ = num_bins - 1;
    constexpr float kNone = std::numeric_limits<float>::infinity();
    auto rel = [&](std::size_t k) { return static_cast<float>(knots_[k] - s_lo); };
    auto scale = [&](std::size_t k) {
        return static_cast<float>(count[k] / (knots_[k + 1] - knots_[k]));
    };
    std::size_t k = 0;
    for (std::size_t b = 0; b < num_bins; ++b) {
        while (k + 1 < m && static_cast<float>(b) / bin_scale_ >= rel(k + 1)) ++k;
        Bin& bin = bins_[b];
        bin = {kNone, rel(k), static_cast<float>(nodes_[k]), scale(k), kNone, 0.0f, 0.0f, 0.0f};
        if (k + 1 < m) {
            bin.next = rel(k + 1);
            bin.node1 = static_cast<float>(nodes_[k + 1]);
            bin.scale1 = scale(k + 1);
            if (k + 2 < m) bin.next2 = rel(k + 2);
        }
    }
}

double ScalarAxis::node(double i) const {
    std::size_t k = 0;
    while (k + 2 < knots_.size() && i >= nodes_[k + 1]) ++k;
    const double t = std::min((i - nodes_[k]) / (nodes_[k + 1] - nodes_[k]), 1.0);
    return t >= 1.0 ? knots_[k + 1] : knots_[k] + (knots_[k + 1] - knots_[k]) * t;
}

bool ScalarAxis::is_knot(int node) const {
    return std::binary_search(nodes_.begin(), nodes_.end(), static_cast<double>(node));
}

float ScalarAxis::coordinate_beyond(double s) const {
    if (!(s < knots_.back())) return static_cast<float>(nodes_.back());
    const std::size_t k = static_cast<std::size_t>(
        std::upper_bound(knots_.begin(), knots_.end(), s) - knots_.begin() - 1);
    return static_cast<float>(nodes_[k] + (s - knots_[k]) / (knots_[k + 1] - knots_[k]) *
                                              (nodes_[k + 1] - nodes_[k]));
}

void build_preintegration(const TransferFunction& tf, std::span<const double> breakpoints,
                          double s_lo, double s_hi, Preintegration& p) {
    p.axis.build(tf, breakpoints, s_lo, s_hi, kMeanScalars);
    build_mean_extinction(tf, p);
    build_mean_color(tf, breakpoints, p);
}

}  // namespace tr::detail
