#include <project/pbvr/pbvr_sampling.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tr {

std::uint64_t mix64(std::uint64_t key) {
    key += 0x9e3779b97f4a7c15ull;
    key = (key ^ (key >> 30)) * 0xbf58476d1ce4e5b9ull;
    key = (key ^ (key >> 27)) * 0x94d049bb133111ebull;
    return key ^ (key >> 31);
}

std::uint64_t hash_key(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
    return mix64(mix64(mix64(mix64(a) ^ b) ^ c) ^ d);
}

namespace {

// x^-1 mod m for x coprime with m (extended Euclid).
std::int64_t inverse_mod(std::int64_t x, std::int64_t m) {
    std::int64_t a = x, b = m, u = 1, v = 0;
    while (b != 0) {
        const std::int64_t q = a / b;
        a -= q * b, std::swap(a, b);
        u -= q * v, std::swap(u, v);
    }
    return ((u % m) + m) % m;
}

}  // namespace

SegmentLattice::SegmentLattice(int repetitions, std::uint64_t key)
    : size_(std::max(repetitions, 1)), generator_(1), inverse_(1) {
    if (size_ <= 2) return;
    // A random unit: the first number coprime with R from a random start.
    std::int64_t g =
        1 + static_cast<std::int64_t>(mix64(key) % static_cast<std::uint64_t>(size_ - 1));
    while (std::gcd(g, static_cast<std::int64_t>(size_)) != 1) g = g % (size_ - 1) + 1;
    generator_ = g;
    inverse_ = inverse_mod(g, size_);
}

LatticeUnits::LatticeUnits(int repetitions) : size_(std::max(repetitions, 1)) {
    if (size_ <= 2) return;  // g = 1 (SegmentLattice's own choice for these)
    for (std::int64_t g = 1; g < size_; ++g) {
        if (std::gcd(g, static_cast<std::int64_t>(size_)) != 1) continue;
        units_.push_back(g);
        inverses_.push_back(inverse_mod(g, size_));
    }
}

std::string_view particle_depth_name(ParticleDepth depth) {
    switch (depth) {
        case ParticleDepth::kInverseCdf:
            return "inverse-cdf";
        case ParticleDepth::kEntry:
            return "entry";
        case ParticleDepth::kMiddle:
            return "middle";
        case ParticleDepth::kExit:
            return "exit";
        case ParticleDepth::kRandom:
            return "random";
    }
    return "?";
}

std::optional<ParticleDepth> parse_particle_depth(std::string_view name) {
    for (ParticleDepth d : {ParticleDepth::kInverseCdf, ParticleDepth::kEntry,
                            ParticleDepth::kMiddle, ParticleDepth::kExit, ParticleDepth::kRandom}) {
        if (particle_depth_name(d) == name) return d;
    }
    return std::nullopt;
}

ExtinctionIntegral::ExtinctionIntegral(const TransferFunction& tf)
    : unit_distance_(tf.unit_distance()) {
    for (const OpacityPoint& p : tf.opacity_points()) {
        s_.push_back(p.s);
        a_.push_back(p.a);
    }
    phi_.assign(s_.size(), 0.0);
    for (std::size_t i = 1; i < s_.size(); ++i) {
        phi_[i] = phi_[i - 1] +
                  (s_[i] - s_[i - 1]) * mean_neg_log(1 - a_[i - 1], 1 - a_[i]) / unit_distance_;
    }
}

double ExtinctionIntegral::piece_at(std::size_t k, double s) const {
    const std::size_t n = s_.size();
    if (k == 0) return (s - s_[0]) * -std::log1p(-a_[0]) / unit_distance_;
    if (k >= n) return phi_[n - 1] + (s - s_[n - 1]) * -std::log1p(-a_[n - 1]) / unit_distance_;
    const double t = (s - s_[k - 1]) / (s_[k] - s_[k - 1]);
    const double u = 1 - (a_[k - 1] + (a_[k] - a_[k - 1]) * t);
    return phi_[k - 1] + (s - s_[k - 1]) * mean_neg_log(1 - a_[k - 1], u) / unit_distance_;
}

double ExtinctionIntegral::at(double s) const {
    // Piece k: [s_[k-1], s_[k]); 0 below the first point, n above the last.
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin());
    return piece_at(k, s);
}

double ExtinctionIntegral::solve_in_piece(std::size_t k, double target) const {
    const std::size_t n = s_.size();
    if (k == 0 || k >= n) {  // kappa constant: Phi linear
        const std::size_t end = k == 0 ? 0 : n - 1;
        const double kappa = -std::log1p(-a_[end]) / unit_distance_;
        return s_[end] + (target - phi_[end]) / kappa;
    }
    const double s0 = s_[k - 1], s1 = s_[k];
    const double a0 = a_[k - 1], a1 = a_[k];
    if (s1 == s0) return s0;  // a step: no width to move through
    if (a0 == a1) {
        const double kappa = -std::log1p(-a0) / unit_distance_;
        return s0 + (target - phi_[k - 1]) / kappa;
    }
    // Phi(s) - phi_[k-1] = (G(u(s)) - G(u0)) * (s1 - s0) / ((a1 - a0) unit_distance) with
    // G(u) = u ln u - u, u = 1 - a linear in s: solve G(u) = c for u between u0 and u1 by Newton
    // (G' = ln u), safeguarded by bisection.
    const double u0 = 1 - a0, u1 = 1 - a1;
    auto g = [](double u) { return u * std::log(u) - u; };
    const double c = g(u0) + (target - phi_[k - 1]) * (a1 - a0) * unit_distance_ / (s1 - s0);
    double lo = std::min(u0, u1), hi = std::max(u0, u1);
    // G decreases in u: g(lo) >= c >= g(hi).
    double u =
        lo + (hi - lo) * std::clamp((target - phi_[k - 1]) / (phi_[k] - phi_[k - 1]), 0.0, 1.0);
    for (int iteration = 0; iteration < 60; ++iteration) {
        const double f = g(u) - c;
        if (f == 0) break;
        (f > 0 ? lo : hi) = u;
        const double derivative = std::log(u);
        double next = derivative < 0 ? u - f / derivative : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - u) <= 1e-15 * u) {
            u = next;
            break;
        }
        u = next;
    }
    return s0 + (s1 - s0) * ((1 - u) - a0) / (a1 - a0);
}

double ExtinctionIntegral::advance(double s_from, double s_to, double amount) const {
    if (!(amount > 0) || s_from == s_to) return s_from;
    const double start = at(s_from);
    if (s_to > s_from) {
        const double target = start + amount;
        // The piece where Phi first reaches the target: Phi at the points is non-decreasing.
        const std::size_t k = static_cast<std::size_t>(
            std::lower_bound(phi_.begin(), phi_.end(), target) - phi_.begin());
        const double s = solve_in_piece(
            std::max(k, static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s_from) -
                                                 s_.begin())),
            target);
        return std::clamp(s, s_from, s_to);
    }
    const double target = start - amount;
    // Moving down: the last point whose Phi is at most the target starts the piece.
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(phi_.begin(), phi_.end(), target) - phi_.begin());
    const std::size_t from_piece =
        static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s_from) - s_.begin());
    const double s = solve_in_piece(std::min(k, from_piece), target);
    return std::clamp(s, s_to, s_from);
}

double inverse_cdf_depth(const ExtinctionIntegral& phi, double s_front, double s_back,
                         double length, double optical_depth, double v) {
    if (!(length > 0) || !(optical_depth > 0)) return 0.0;
    // The optical depth the particle lies at: alpha(w) = v alpha(length).
    const double target = -std::log1p(v * std::expm1(-optical_depth));
    const double ds = s_back - s_front;
    if (std::abs(ds) <= 1e-12 * std::max(std::abs(s_front), std::abs(s_back))) {
        return std::clamp(length * target / optical_depth, 0.0, length);
    }
    // Along the segment Phi changes by optical_depth |ds| / length; the particle is where it
    // has changed by target |ds| / length.
    const double s = phi.advance(s_front, s_back, target * std::abs(ds) / length);
    return std::clamp(length * (s - s_front) / ds, 0.0, length);
}

double particle_depth(ParticleDepth depth, const ExtinctionIntegral& phi, double s_front,
                      double s_back, double length, double optical_depth, double v) {
    switch (depth) {
        case ParticleDepth::kInverseCdf:
            return inverse_cdf_depth(phi, s_front, s_back, length, optical_depth, v);
        case ParticleDepth::kEntry:
            return 0.0;
        case ParticleDepth::kMiddle:
            return 0.5 * length;
        case ParticleDepth::kExit:
            return length;
        case ParticleDepth::kRandom:
            return v * length;
    }
    return 0.0;
}

}  // namespace tr
