#include <core/parallel.h>
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

constexpr int kExpSize = 256;
// The (front, back, length) table of tables(), for the OpenGL renderer.
constexpr int kPreScalars = 64;
constexpr int kPreLengths = 32;
// The mean-colour table: nodes per scalar axis and over r = tau / (1 + tau).
constexpr int kMeanScalars = 64;
constexpr int kMeanDepths = 32;
// A table cell whose measured interpolation error (largest channel) exceeds this has its
// segments integrated directly. The error is sampled (centre, face centres, edge midpoints; a 3 x 3
// grid where the cell touches a control point on the diagonal), not bounded: the largest error
// found between samples, over random segments through the tests' transfer functions, is 0.35 of
// a level with this threshold (tests/project/segment_shader_test.cpp), within the half level the
// default integrator promises.
constexpr double kMaxColorError = 0.3 / 255.0;
// The mean-extinction table: kExtinctionRefine cells per mean-colour cell along each axis.
constexpr int kExtinctionRefine = 4;
constexpr int kExtinctionScalars = (kMeanScalars - 1) * kExtinctionRefine + 1;
// A (front, back) cell whose mean extinction, interpolated, is off by more than this relative
// error (measured) takes the closed form instead: it moves the opacity by at most this / e.
constexpr double kMaxExtinctionError = 2e-4;
// Front-scalar cells across which the extinction changes by more than this factor have their
// segments that are not optically thin (r beyond the first cell) integrated directly.
constexpr double kMaxExtinctionRatio = 5.0;
// Building the table: a piece of a segment is halved until the quadratic that stands for its
// colour is this close to the true colour (at the quarter points), or after kMaxPieceDepth
// halvings.
constexpr double kPieceTolerance = 2e-5;
constexpr int kMaxPieceDepth = 24;
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

// Moments of the weight theta exp(-theta t) over t in [0, 1]: m[k] = integral of t^k times it,
// given e = exp(-theta). Series for small theta (where the closed forms cancel), relative error
// below 1e-9.
void weight_moments(double theta, double e, double m[3]) {
    if (theta < 0.1) {
        // m_k = theta * sum_n (-theta)^n / (n! (n + k + 1)).
        const double t = theta;
        m[0] =
            t * (1.0 - t * (1.0 / 2 - t * (1.0 / 6 - t * (1.0 / 24 - t * (1.0 / 120 - t / 720)))));
        m[1] = t * (1.0 / 2 -
                    t * (1.0 / 3 - t * (1.0 / 8 - t * (1.0 / 30 - t * (1.0 / 144 - t / 840)))));
        m[2] = t * (1.0 / 3 -
                    t * (1.0 / 4 - t * (1.0 / 10 - t * (1.0 / 36 - t * (1.0 / 168 - t / 960)))));
        return;
    }
    m[0] = 1.0 - e;
    m[1] = (m[0] - theta * e) / theta;
    m[2] = (2.0 * m[1] - theta * e) / theta;
}

// The mean colour of one segment (scalar from sf to sb) as a function of its optical depth tau:
// cbar(tau) = integral of c(q) tau exp(-tau q) dq / (1 - exp(-tau)), q in [0, 1] the fraction
// of the segment's optical depth in front of a point. The segment is cut into pieces between
// control points, where colour and opacity are linear along it and the optical depth is closed
// form (mean_neg_log); on each piece the colour is taken as a quadratic in q through the piece's
// ends and middle, and pieces are halved until that quadratic is within kPieceTolerance of the
// true colour at the quarter points. Against the quadratic the integral is closed form.
class SegmentColors {
  public:
    struct Piece {
        double dx, dq;  // length along the segment (of 1), optical depth (of 1 once normalized)
        Vec3 a, b, c;   // colour a + b eta + c eta^2, eta in [0, 1] the fraction of dq
    };

    // `storage` holds the pieces (reused between segments: no allocation once it has grown).
    SegmentColors(const TransferFunction& tf, std::span<const double> breakpoints, double sf,
                  double sb, std::vector<Piece>& storage)
        : pieces_(storage) {
        pieces_.clear();
        // Pieces between the control points the scalar crosses, in the order the ray meets them.
        double x0 = 0.0;
        auto base = [&](double x1) {
            if (!(x1 > x0)) return;
            // Colour and opacity are linear in x between control points: take their lines
            // from two interior points (the ends may sit on a step).
            const double xa = x0 + 0.25 * (x1 - x0), xb = x0 + 0.75 * (x1 - x0);
            const Vec3 ca = tf.color(sf + (sb - sf) * xa), cb = tf.color(sf + (sb - sf) * xb);
            const double aa = tf.opacity(sf + (sb - sf) * xa);
            const double ab = tf.opacity(sf + (sb - sf) * xb);
            Line line;
            line.c0 = ca - 0.5 * (cb - ca);
            line.dc = 2.0 * (cb - ca);
            line.u0 = 1.0 - (aa - 0.5 * (ab - aa));
            line.du = -2.0 * (ab - aa);
            line.length = x1 - x0;
            refine(line, 0.0, 1.0, 0);
            x0 = x1;
        };
        if (sf != sb) {
            const double lo = std::min(sf, sb), hi = std::max(sf, sb);
            const auto first = std::upper_bound(breakpoints.begin(), breakpoints.end(), lo);
            const auto last = std::lower_bound(first, breakpoints.end(), hi);
            if (sb > sf) {
                for (auto it = first; it != last; ++it) base((*it - sf) / (sb - sf));
            } else {
                for (auto it = last; it != first; --it) base((*(it - 1) - sf) / (sb - sf));
            }
        }
        base(1.0);
        for (const Piece& p : pieces_) total_ += p.dq;
        if (total_ > 0) {
            for (Piece& p : pieces_) p.dq /= total_;
        }
    }

    // Whether the segment absorbs anywhere (otherwise the mean colour means nothing).
    bool absorbs() const { return total_ > 0; }

    // cbar at r = tau / (1 + tau) in [0, 1]. Without absorption: the plain mean colour.
    Vec3 mean_color(double r) const {
        Vec3 sum(0.0);
        if (!absorbs()) {
            double length = 0.0;
            for (const Piece& p : pieces_) {
                sum += (p.a + 0.5 * p.b + p.c / 3.0) * p.dx;
                length += p.dx;
            }
            return sum / length;
        }
        if (r >= 1.0) {  // infinitely thick: the colour where the absorption starts
            for (const Piece& p : pieces_) {
                if (p.dq > 0) return p.a;
            }
        }
        if (r <= 0.0) {  // optically thin: weights uniform in q
            for (const Piece& p : pieces_) sum += (p.a + 0.5 * p.b + p.c / 3.0) * p.dq;
            return sum;
        }
        const double tau = r / (1.0 - r);
        double transmittance = 1.0;
        for (const Piece& p : pieces_) {
            const double theta = tau * p.dq;
            const double e = std::exp(-theta);
            double m[3];
            weight_moments(theta, e, m);
            sum += transmittance * (p.a * m[0] + p.b * m[1] + p.c * m[2]);
            transmittance *= e;
            if (transmittance < 1e-15) break;
        }
        return sum / -std::expm1(-tau);
    }

  private:
    // Colour c0 + dc t and u = 1 - opacity = u0 + du t for t in [0, 1] across a piece between
    // control points, `length` of the segment's (of 1).
    struct Line {
        Vec3 c0, dc;
        double u0, du;
        double length;
        Vec3 color(double t) const { return c0 + dc * t; }
        double u(double t) const { return u0 + du * t; }
        // Optical depth from t0 to t1, in units of unit_distance times the segment's length.
        double depth(double t0, double t1) const {
            return length * (t1 - t0) * mean_neg_log(u(t0), u(t1));
        }
    };
    void refine(const Line& line, double t0, double t1, int depth) {
        const double tm = 0.5 * (t0 + t1);
        const double dq = line.depth(t0, t1);
        const Vec3 c0 = line.color(t0), cm = line.color(tm), c1 = line.color(t1);
        Piece p{line.length * (t1 - t0), dq, c0, c1 - c0, Vec3(0.0)};
        if (dq > 0) {
            // Quadratic in eta through (0, c0), (em, cm), (1, c1).
            const double em = line.depth(t0, tm) / dq;
            if (em > 0 && em < 1) {
                // c(eta) = c0 + b eta + c eta^2 with b + c = c1 - c0, b em + c em^2 = cm - c0.
                p.c = ((cm - c0) - (c1 - c0) * em) / (em * em - em);
                p.b = (c1 - c0) - p.c;
            }
            if (depth < kMaxPieceDepth) {
                // Check at the quarter points.
                double worst = 0.0;
                for (double f : {0.25, 0.75}) {
                    const double t = t0 + f * (t1 - t0);
                    const double e = line.depth(t0, t) / dq;
                    const Vec3 d = glm::abs(p.a + (p.b + p.c * e) * e - line.color(t));
                    worst = std::max({worst, d.x, d.y, d.z});
                }
                if (!(worst <= kPieceTolerance)) {
                    refine(line, t0, tm, depth + 1);
                    refine(line, tm, t1, depth + 1);
                    return;
                }
            }
        }
        pieces_.push_back(p);
    }

    std::vector<Piece>& pieces_;
    double total_ = 0.0;
};

}  // namespace

namespace detail {

// The tables' scalar axis: nodes spread over the control points' range with every control
// point on a node (where there are fewer intervals between control points than a third of the
// cells; uniform otherwise), so that no cell straddles a kink of the transfer function.
class ScalarAxis {
  public:
    void build(const TransferFunction& tf, std::span<const double> breakpoints, double s_lo,
               double s_hi, int nodes);
    double node(double i) const;   // scalar at (fractional) node coordinate i
    bool is_knot(int node) const;  // whether a control point sits on this node
    // Node coordinate of s in [s_lo, s_hi], in single precision: one load and a multiply-add,
    // a search only where a bin holds more than one knot.
    float coordinate(double s) const {
        const float d = static_cast<float>(s - s_lo_);
        const Bin& b =
            bins_[std::min(static_cast<std::size_t>(std::max(d, 0.0f) * bin_scale_), last_bin_)];
        if (d < b.next) return b.node0 + (d - b.s0) * b.scale;
        if (d < b.next2) return b.node1 + (d - b.next) * b.scale1;
        return coordinate_beyond(s);
    }

  private:
    // A uniform bin: the interval its start lies in (its lower knot and the node coordinate
    // there, nodes per unit scalar) and the interval after it (from `next`), scalars relative to
    // s_lo. next2: the knot after that (+infinity for none).
    struct Bin {
        float next, s0, node0, scale;
        float next2, node1, scale1, unused;
    };
    float coordinate_beyond(double s) const;  // a bin holding two knots or more: a search

    std::vector<double> knots_;  // interval ends, increasing
    std::vector<double> nodes_;  // node coordinate at each knot
    std::vector<Bin> bins_;
    double s_lo_ = 0;
    float bin_scale_ = 0;       // bins per unit scalar
    std::size_t last_bin_ = 0;  // bins_.size() - 1
};

// kPreintegrated's tables, immutable once built (shared by copies of a SegmentShader).
struct Preintegration {
    ScalarAxis axis;  // both tables' front and back axes
    // (front, back) -> TransferFunction::mean_extinction at kExtinctionScalars^2 nodes, bilinear;
    // per cell 1 where that is not accurate enough (measured): the closed form is used there.
    std::vector<float> mean_extinction;
    std::vector<std::uint8_t> extinction_closed_form;
    // (front, back, r) -> mean colour rgb at kMeanScalars^2 x kMeanDepths nodes; in w 1 where
    // the cell whose lowest corner is this node is not accurate enough (measured): its segments
    // are integrated directly.
    std::vector<glm::vec4> mean_color;
    std::size_t direct_cells = 0;
};

// The (front, back, length) table of tables(), built on its first call.
struct LazyPreintTable {
    std::once_flag once;
    std::vector<float> table;
};

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

}  // namespace detail

namespace {

// Fills p.mean_extinction and p.extinction_closed_form (p.axis built).
void build_mean_extinction(const TransferFunction& tf, detail::Preintegration& p) {
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
                      detail::Preintegration& p) {
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
        pre->axis.build(tf, breakpoints_, s_lo_, s_hi_, kMeanScalars);
        build_mean_extinction(tf, *pre);
        build_mean_color(tf, breakpoints_, *pre);
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
    if (!(length > 0)) return {Vec3f(0.0f), 0.0f};
    // An infinite largest extinction (a unit distance of 1e-320 makes -ln(1 - a) / d
    // overflow): the texture's row v / kappa_max would be inf / inf; integrated directly.
    if (length > max_length_ || !(kappa_max_ > 0) || !std::isfinite(kappa_max_))
        return exact(s_front, s_back, length);
    // Halves added (two extinctions near the largest double would sum to inf), and the row
    // at most the last: v <= kappa_max up to rounding.
    const double v = 0.5 * tf_.extinction(s_front) + 0.5 * tf_.extinction(s_back);
    const double x = length / max_length_ * (kExpSize - 1);
    const double y = std::min(v / kappa_max_, 1.0) * (kExpSize - 1);
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
    thread_local std::vector<SegmentColors::Piece> storage;
    const SegmentColors colors(tf_, breakpoints_, s_front, s_back, storage);
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
