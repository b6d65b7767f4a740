#pragma once
// The random numbers and samples of particle-based volume rendering (particle-based paper,
// sections 3.3-4.1): counter-based uniforms (a pure function of the seed and the indices, so a
// picture does not depend on the thread count or the order work is done in), a rotated rank-1
// lattice that stratifies the repetitions of one ray segment, and the depth of a segment's
// particle by the inverse of its opacity's cumulative distribution.

#include <project/transfer_function.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace tr {

// A 64-bit mix of `key` (the splitmix64 finalizer): equal keys give equal values, nearby keys
// unrelated ones.
std::uint64_t mix64(std::uint64_t key);

// A key for the tuple (a, b, c, d): chained mix64.
std::uint64_t hash_key(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0, std::uint64_t d = 0);

// A uniform number in [0, 1) from a key (its top 53 bits).
inline double uniform01(std::uint64_t key) {
    return static_cast<double>(mix64(key) >> 11) * 0x1.0p-53;
}

// The repetitions of one ray segment on one pixel as a randomly shifted rank-1 lattice: in
// repetition r the segment's uniform is u_r = frac(shift + r g / R). Each u_r alone is uniform
// (the shift is), so an estimator using it is unbiased in every repetition; over the R
// repetitions the u_r take every stratum [j/R, (j+1)/R) once. Segments on one ray take
// independent shifts AND independent generators g (random units mod R): the joint points of
// several segments over the repetitions then form a rank-1 lattice in as many dimensions,
// spread over their joint cube (one shared g would put them on a line that never fills it).
class SegmentLattice {
  public:
    // R repetitions, the generator drawn from `key` (a unit mod R, and its inverse).
    SegmentLattice(int repetitions, std::uint64_t key);
    // R repetitions with the given generator g (coprime with R) and its inverse mod R.
    SegmentLattice(int repetitions, std::int64_t generator, std::int64_t inverse)
        : size_(std::max(repetitions, 1)), generator_(generator), inverse_(inverse) {}

    int size() const { return size_; }
    int generator() const { return generator_; }

    // u_r for repetition r.
    double uniform(double shift, int r) const {
        const double u =
            shift +
            static_cast<double>((static_cast<std::int64_t>(r) * generator_) % size_) / size_;
        return u >= 1.0 ? u - 1.0 : u;
    }

    // The repetitions whose u_r is below `p` (in [0, 1]): about p R of them, found without
    // visiting the others. Calls fn(r, u_r) for each, in increasing u.
    template <class Fn>
    void for_each_below(double p, double shift, Fn&& fn) const {
        const double a = shift * size_;
        const double base = std::floor(a);
        const double fraction = a - base;
        const double limit = p * size_ - fraction;  // strata j with fraction + j < p R
        if (!(limit > 0)) return;
        const int count = std::min(size_, static_cast<int>(std::ceil(limit)));
        // (a + r g) mod R = fraction + j  <=>  r = (j - base) g^-1 mod R.
        const std::int64_t start =
            ((size_ - static_cast<std::int64_t>(base) % size_) % size_) * inverse_ % size_;
        for (int j = 0; j < count; ++j) {
            const int r =
                static_cast<int>((start + static_cast<std::int64_t>(j) * inverse_) % size_);
            fn(r, (fraction + j) / size_);
        }
    }

  private:
    int size_;
    std::int64_t generator_;
    std::int64_t inverse_;  // generator_ * inverse_ = 1 mod size_
};

// The units mod R (the numbers in [1, R) coprime with R) and their inverses, to draw many
// SegmentLattices of one size without a gcd each: lattice(key) == SegmentLattice(R, key)'s
// distribution (a uniformly drawn unit), not its value.
class LatticeUnits {
  public:
    explicit LatticeUnits(int repetitions);
    SegmentLattice lattice(std::uint64_t key) const {
        if (units_.empty()) return SegmentLattice(size_, 1, 1);
        const std::size_t i = mix64(key) % units_.size();
        return SegmentLattice(size_, units_[i], inverses_[i]);
    }

  private:
    int size_;
    std::vector<std::int64_t> units_, inverses_;
};

// Where along a segment its particle lies (particle-based paper, 4.1; spec key `depth`).
enum class ParticleDepth {
    kInverseCdf,  // drawn by the inverse of the opacity's CDF along the segment (exact)
    kEntry,       // at the entry point
    kMiddle,      // at the middle
    kExit,        // at the exit point
    kRandom,      // uniform between entry and exit
};

std::string_view particle_depth_name(ParticleDepth depth);  // "inverse-cdf", "entry", ...
std::optional<ParticleDepth> parse_particle_depth(std::string_view name);

// The integral of the extinction over the scalar, Phi(s) = integral of kappa from the first
// opacity point to s (kappa constant beyond the ends, as the spec clamps), exact: on each linear
// piece of the opacity a = 1 - u, the integral of -ln(u) / unit_distance is (u ln u - u) over
// the slope. A segment of length L along which the scalar runs linearly from sf to sb has optical
// depth L (Phi(sb) - Phi(sf)) / (sb - sf).
class ExtinctionIntegral {
  public:
    explicit ExtinctionIntegral(const TransferFunction& tf);

    double at(double s) const;

    // Moving from s_from towards s_to, the first scalar s where |Phi(s) - Phi(s_from)| reaches
    // `amount` (at most |Phi(s_to) - Phi(s_from)|). Cost: a binary search over the opacity
    // points and a few Newton steps of one logarithm each.
    double advance(double s_from, double s_to, double amount) const;

  private:
    double piece_at(std::size_t k, double s) const;  // Phi on piece k (0: below, n: above)
    double solve_in_piece(std::size_t k, double target) const;

    std::vector<double> s_, a_;  // the opacity points
    std::vector<double> phi_;    // Phi at each point
    double unit_distance_;
};

// The distance w in [0, length] from the entry of a segment (scalar linear from s_front to
// s_back over `length`) where its first particle lies, given that it has one: w solves
// alpha(w) = v alpha(length), alpha(w) = 1 - exp(-optical depth over [0, w]), so w follows the
// distribution the spec's optical model gives the first particle. `v` in [0, 1);
// `optical_depth` is the whole segment's. Exact to rounding (ExtinctionIntegral::advance).
double inverse_cdf_depth(const ExtinctionIntegral& phi, double s_front, double s_back,
                         double length, double optical_depth, double v);

// The particle's distance from the entry for each ParticleDepth (`v` as above; kRandom takes
// `v` as its uniform).
double particle_depth(ParticleDepth depth, const ExtinctionIntegral& phi, double s_front,
                      double s_back, double length, double optical_depth, double v);

}  // namespace tr
