#pragma once
// What object- and image-space particle-based volume rendering share (particle-based paper,
// section 3): the particle buffer entry (the nearest opaque particle of a sub-pixel or of one
// repetition of a pixel) and the pictures' limits. What they draw is a VolumeScene.
//
// Particles are opaque: the picture of one repetition is, per (sub-)pixel, the colour of the
// nearest particle, or what lies behind the volume (the background or opaque geometry); the
// ensemble average of many repetitions converges to the spec's ray integral.

#include <core/image.h>
#include <project/volume_scene.h>

#include <cstdint>
#include <span>
#include <vector>

namespace tr {

// The work a picture may ask for: repetitions x pixels x sub-pixels above this is refused
// before anything is allocated (2^38: 1024 repetitions of a 4096 x 4096 picture with 4 x 4
// sub-pixels; far beyond any picture worth waiting for on one machine).
inline constexpr double kMaxParticleSamples = 274877906944.0;

// A particle buffer entry: depth in the high 32 bits (a non-negative float's bits order as the
// float does), the colour packed 10-10-10 in the low bits. The smaller entry is the nearer
// particle, ties broken by colour, so the nearest wins whatever order particles arrive in.
inline constexpr std::uint64_t kNoParticle = ~std::uint64_t{0};

inline std::uint64_t pack_particle(float depth, const Vec3& color) {
    std::uint32_t bits;
    static_assert(sizeof(bits) == sizeof(depth));
    __builtin_memcpy(&bits, &depth, sizeof(bits));
    auto channel = [](double c) {
        const double clamped = c < 0 ? 0 : (c > 1 ? 1 : c);
        return static_cast<std::uint32_t>(clamped * 1023.0 + 0.5);
    };
    const std::uint32_t rgb =
        (channel(color.r) << 20) | (channel(color.g) << 10) | channel(color.b);
    return (static_cast<std::uint64_t>(bits) << 32) | rgb;
}

inline Vec3f particle_color(std::uint64_t entry) {
    const auto rgb = static_cast<std::uint32_t>(entry);
    return Vec3f(static_cast<float>((rgb >> 20) & 1023u), static_cast<float>((rgb >> 10) & 1023u),
                 static_cast<float>(rgb & 1023u)) *
           (1.0f / 1023.0f);
}

inline float particle_depth_of(std::uint64_t entry) {
    const auto bits = static_cast<std::uint32_t>(entry >> 32);
    float depth;
    __builtin_memcpy(&depth, &bits, sizeof(depth));
    return depth;
}

}  // namespace tr
