#pragma once
// A counter-based generator for spot noise: the same (seed, spot, generation) gives the same
// numbers whatever the thread count.

#include <cstdint>

namespace tr::detail {

inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

class SpotRandom {
  public:
    SpotRandom(std::uint64_t seed, std::uint64_t index, std::uint64_t generation)
        : state_(mix64(seed ^ mix64(index * 0x100000001b3ull + mix64(generation)))) {}
    // Uniform in (0, 1).
    double uniform() {
        state_ = mix64(state_);
        return (static_cast<double>(state_ >> 11) + 0.5) * 0x1.0p-53;
    }

  private:
    std::uint64_t state_;
};

}  // namespace tr::detail
