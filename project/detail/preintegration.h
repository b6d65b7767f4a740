#pragma once
// The default integrator's tables (SegmentShader, kPreintegrated): the scalar axis, the mean
// extinction over (front, back) and the mean colour over (front, back, r = tau / (1 + tau)),
// built and their interpolation error measured per cell (project/preintegration.cpp); and the
// mean colour of one segment integrated directly (SegmentColors), which the tables are built from
// and which the shader falls back to in the cells the measurement flags. Internal to project/.

#include <core/math.h>
#include <project/transfer_function.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

namespace tr::detail {

// The mean-colour table: nodes per scalar axis and over r = tau / (1 + tau).
constexpr int kMeanScalars = 64;
constexpr int kMeanDepths = 32;
// The mean-extinction table: kExtinctionRefine cells per mean-colour cell along each axis.
constexpr int kExtinctionRefine = 4;
constexpr int kExtinctionScalars = (kMeanScalars - 1) * kExtinctionRefine + 1;
// Building the table: a piece of a segment is halved until the quadratic that stands for its
// colour is this close to the true colour (at the quarter points), or after kMaxPieceDepth
// halvings.
constexpr double kPieceTolerance = 2e-5;
constexpr int kMaxPieceDepth = 24;

// Moments of the weight theta exp(-theta t) over t in [0, 1]: m[k] = integral of t^k times it,
// given e = exp(-theta). Series for small theta (where the closed forms cancel), relative error
// below 1e-9.
inline void weight_moments(double theta, double e, double m[3]) {
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

// Builds p's axis over [s_lo, s_hi] (the breakpoints: every control point's scalar, sorted and
// unique), its mean-extinction table and its mean-colour table, each cell's interpolation error
// measured and the cells beyond the bounds flagged. Threaded over rows.
void build_preintegration(const TransferFunction& tf, std::span<const double> breakpoints,
                          double s_lo, double s_hi, Preintegration& p);

}  // namespace tr::detail
