#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/pbvr/pbvr_image.h>
#include <project/tet_fragments.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <vector>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

// Repetitions drawn at a time per tile: the tile's buffer holds one entry per pixel and
// repetition (8 MB for 1024 repetitions of 32 x 32 pixels).
constexpr int kRepetitionsPerPass = 1024;

// A segment of one pixel ray through one cell, as the tile keeps it.
struct Fragment {
    std::uint32_t cell;
    std::uint16_t pixel;  // in the tile: (y - y0) * kFragmentTile + (x - x0)
    std::uint8_t volume;
    float t_in, length, s_in, s_out;
    float optical_depth;
};

// The buffer entry while drawing: the key that decides the nearest (the particle's depth, or
// for one volume the segment's entry: its cells do not overlap, so the nearest segment holds
// the nearest particle) and the fragment's index in the tile.
std::uint64_t pack_key(float key, std::uint32_t fragment) {
    std::uint32_t bits;
    __builtin_memcpy(&bits, &key, sizeof(bits));
    return (static_cast<std::uint64_t>(bits) << 32) | fragment;
}

float key_of(std::uint64_t entry) {
    const auto bits = static_cast<std::uint32_t>(entry >> 32);
    float key;
    __builtin_memcpy(&key, &bits, sizeof(key));
    return key;
}

struct VolumeState {
    const VolumeData* volume;
    ExtinctionIntegral phi;
    TileBins bins;
    std::vector<CellId> cells;
};

}  // namespace

Image render_image_pbvr(const VolumeScene& scene, const ImagePbvrOptions& options,
                        ImagePbvrStats* stats, std::vector<float>* alpha_out) {
    const auto start = Clock::now();
    const CameraFrame& camera = *scene.camera;
    const int w = camera.width(), h = camera.height();
    const int repetitions = std::max(1, options.repetitions);
    std::vector<VolumeState> volumes;
    volumes.reserve(scene.volumes.size());
    for (const VolumeData& v : scene.volumes) {
        VolumeState state{&v, ExtinctionIntegral(*v.tf), {}, {}};
        state.cells.resize(v.mesh->num_real_tets());
        std::iota(state.cells.begin(), state.cells.end(), CellId{0});
        state.bins = bin_cells(*v.mesh, state.cells, camera);
        volumes.push_back(std::move(state));
    }
    // One volume's segments never overlap on a ray: the nearest segment with a particle holds
    // the nearest particle, and only the winner's depth need be drawn — or, with a shader, its
    // expected colour taken instead.
    const bool disjoint = volumes.size() == 1;
    const bool mean_colors = disjoint && options.depth == ParticleDepth::kInverseCdf &&
                             scene.volumes[0].shader != nullptr;
    const std::span<const double> max_depth = scene.opaque_depth
                                                  ? std::span<const double>(*scene.opaque_depth)
                                                  : std::span<const double>();
    Image image(w, h, Vec3f(scene.background));
    if (scene.opaque_color) image = *scene.opaque_color;
    const Image behind = image;
    if (alpha_out) alpha_out->assign(static_cast<std::size_t>(w) * h, 0.0f);
    // Repetitions with a particle are counted per pixel for the control variate and, without
    // it, for the opacity asked for (the fraction of repetitions that hide what lies behind).
    const bool count_hits = options.control_variate || alpha_out != nullptr;
    const std::size_t num_tiles = volumes.empty() ? 0 : volumes[0].bins.num_tiles();
    std::atomic<std::size_t> total_fragments{0}, total_particles{0};
    // The lattices' generators for a whole pass and for a shorter last one.
    const int full_pass = std::min(repetitions, kRepetitionsPerPass);
    const LatticeUnits full_units(full_pass);
    const LatticeUnits last_units(
        repetitions % kRepetitionsPerPass == 0 ? 1 : repetitions % kRepetitionsPerPass);

    parallel_for(0, num_tiles, 1, [&](std::size_t tile) {
        TileRays rays;
        tile_rays(volumes[0].bins, tile, camera, rays);
        // The tile's fragments, all volumes (buffers kept per worker between tiles).
        thread_local std::vector<Fragment> fragments;
        fragments.clear();
        for (std::size_t v = 0; v < volumes.size(); ++v) {
            const VolumeState& state = volumes[v];
            const VolumeData& volume = *state.volume;
            for (std::uint32_t index : state.bins.bins[tile]) {
                const CellId t = state.cells[index];
                const CellFragments cell(*volume.mesh, volume.scalar, t, camera);
                for_each_fragment(
                    cell, state.bins.boxes[index], rays, w, max_depth,
                    [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                        const double length = t_out - t_in;
                        // With mean colours the shader gives the opacity (below).
                        const double depth =
                            mean_colors ? 0.0 : length * volume.tf->mean_extinction(s_in, s_out);
                        if (!mean_colors && !(depth > 0)) return;
                        fragments.push_back({t,
                                             static_cast<std::uint16_t>(
                                                 (y - rays.y0) * kFragmentTile + (x - rays.x0)),
                                             static_cast<std::uint8_t>(v), static_cast<float>(t_in),
                                             static_cast<float>(length), static_cast<float>(s_in),
                                             static_cast<float>(s_out), static_cast<float>(depth)});
                    });
            }
        }
        // Each segment's opacity, and with mean colours its mean colour C / alpha from the
        // shader (its opacity exact in the length: TransferFunction::mean_extinction's).
        thread_local std::vector<double> alpha;
        thread_local std::vector<Vec3f> mean_color;
        if (mean_colors) {
            thread_local std::vector<SegmentQuery> queries;
            thread_local std::vector<ShadedSegment> shaded;
            queries.resize(fragments.size());
            shaded.resize(fragments.size());
            for (std::size_t i = 0; i < fragments.size(); ++i) {
                queries[i] = {fragments[i].s_in, fragments[i].s_out, fragments[i].length};
            }
            scene.volumes[0].shader->shade(queries, shaded);
            // Keep the segments with a particle to give.
            std::size_t kept = 0;
            alpha.resize(fragments.size());
            mean_color.resize(fragments.size());
            for (std::size_t i = 0; i < fragments.size(); ++i) {
                if (!(shaded[i].alpha > 0)) continue;
                fragments[kept] = fragments[i];
                alpha[kept] = shaded[i].alpha;
                mean_color[kept] = shaded[i].color / shaded[i].alpha;
                ++kept;
            }
            fragments.resize(kept);
            alpha.resize(kept);
        } else {
            alpha.resize(fragments.size());
            for (std::size_t i = 0; i < fragments.size(); ++i) {
                alpha[i] = -std::expm1(-static_cast<double>(fragments[i].optical_depth));
            }
        }
        total_fragments += fragments.size();
        // The control variate's per-pixel sums (pbvr_image.h): the log of the transparency of
        // all the pixel's segments, and their colours weighted by opacity.
        thread_local std::vector<double> log_transparency, weight;
        thread_local std::vector<Vec3> weighted_color;
        thread_local std::vector<int> hits;
        constexpr std::size_t kTilePixels = kFragmentTile * kFragmentTile;
        if (count_hits) hits.assign(kTilePixels, 0);
        if (options.control_variate) {
            log_transparency.assign(kTilePixels, 0.0);
            weight.assign(kTilePixels, 0.0);
            weighted_color.assign(kTilePixels, Vec3(0.0));
            for (std::size_t i = 0; i < fragments.size(); ++i) {
                const Fragment& f = fragments[i];
                const Vec3 c = mean_colors ? Vec3(mean_color[i])
                                           : volumes[f.volume].volume->tf->color(
                                                 0.5 * (static_cast<double>(f.s_in) + f.s_out));
                log_transparency[f.pixel] += std::log1p(-alpha[i]);
                weight[f.pixel] += alpha[i];
                weighted_color[f.pixel] += alpha[i] * c;
            }
        }
        auto global_pixel = [&](const Fragment& f) {
            const int x = rays.x0 + f.pixel % kFragmentTile, y = rays.y0 + f.pixel / kFragmentTile;
            return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + x;
        };
        // The particle of fragment f at CDF value q: its distance from the eye and colour.
        auto particle = [&](const Fragment& f, double q, double& t, Vec3& color) {
            const VolumeState& state = volumes[f.volume];
            const double along = particle_depth(options.depth, state.phi, f.s_in, f.s_out, f.length,
                                                f.optical_depth, q);
            t = f.t_in + along;
            const double s = f.length > 0 ? f.s_in + (f.s_out - f.s_in) * along / f.length : f.s_in;
            color = state.volume->tf->color(s);
        };

        std::vector<double> sum(kFragmentTile * kFragmentTile * 3, 0.0);
        thread_local std::vector<std::uint64_t> nearest;
        thread_local std::vector<double> shifts;
        thread_local std::vector<std::uint64_t> generators;  // stratified: g; else a stream's key
        std::size_t particles = 0;
        for (int pass = 0, done = 0; done < repetitions; ++pass) {
            const int count = std::min(kRepetitionsPerPass, repetitions - done);
            done += count;
            const LatticeUnits& units = count == full_pass ? full_units : last_units;
            nearest.assign(static_cast<std::size_t>(kFragmentTile) * kFragmentTile * count,
                           kNoParticle);
            // Each fragment's numbers in this pass: a random shift and lattice (stratified) or a
            // stream of independent uniforms.
            shifts.resize(fragments.size());
            generators.resize(fragments.size());
            auto uniform_of = [&](std::uint32_t i, int r) {
                if (options.stratified) {
                    const double u =
                        shifts[i] + static_cast<double>(
                                        (static_cast<std::int64_t>(r) * generators[i]) % count) /
                                        count;
                    return u >= 1.0 ? u - 1.0 : u;
                }
                return uniform01(hash_key(generators[i], static_cast<std::uint64_t>(r)));
            };
            for (std::uint32_t i = 0; i < fragments.size(); ++i) {
                const Fragment& f = fragments[i];
                const double a = alpha[i];
                const std::uint64_t key = hash_key(
                    options.seed, static_cast<std::uint64_t>(pass),
                    (static_cast<std::uint64_t>(f.volume) << 32) | f.cell, global_pixel(f));
                std::uint64_t* slots = &nearest[static_cast<std::size_t>(f.pixel) * count];
                // Repetition r has a particle in f when its uniform u < alpha; its depth is
                // the CDF's inverse at q = u / alpha.
                auto visit = [&](int r, double u) {
                    ++particles;
                    std::uint64_t& slot = slots[r];
                    if (slot != kNoParticle && key_of(slot) <= f.t_in) return;  // can't be nearer
                    if (disjoint) {
                        slot = pack_key(f.t_in, i);
                        return;
                    }
                    double t;
                    Vec3 color;
                    particle(f, std::min(u / a, 1.0 - 1e-16), t, color);
                    const auto depth = static_cast<float>(t);
                    if (slot == kNoParticle || depth < key_of(slot)) slot = pack_key(depth, i);
                };
                if (options.stratified) {
                    const SegmentLattice lattice = units.lattice(key);
                    shifts[i] = uniform01(key);
                    generators[i] = static_cast<std::uint64_t>(lattice.generator());
                    lattice.for_each_below(a, shifts[i], visit);
                } else {
                    generators[i] = key;
                    for (int r = 0; r < count; ++r) {
                        const double u = uniform_of(i, r);
                        if (u < a) visit(r, u);
                    }
                }
            }
            // Each pixel: the winners' colours (or what lies behind) summed over the pass.
            for (int y = rays.y0; y <= rays.y1; ++y) {
                for (int x = rays.x0; x <= rays.x1; ++x) {
                    const std::size_t local =
                        static_cast<std::size_t>(y - rays.y0) * kFragmentTile + (x - rays.x0);
                    const Vec3 back(behind.at(x, y));
                    Vec3 total(0.0);
                    for (int r = 0; r < count; ++r) {
                        const std::uint64_t e = nearest[local * count + r];
                        if (e == kNoParticle) {
                            total += back;
                            continue;
                        }
                        if (count_hits) ++hits[local];
                        const std::uint32_t i = static_cast<std::uint32_t>(e);
                        if (mean_colors) {
                            total += Vec3(mean_color[i]);
                            continue;
                        }
                        // The winner's particle, drawn again from the same number.
                        double t;
                        Vec3 color;
                        particle(fragments[i], std::min(uniform_of(i, r) / alpha[i], 1.0 - 1e-16),
                                 t, color);
                        total += color;
                    }
                    for (int k = 0; k < 3; ++k) sum[local * 3 + k] += total[k];
                }
            }
        }
        total_particles += particles;
        for (int y = rays.y0; y <= rays.y1; ++y) {
            for (int x = rays.x0; x <= rays.x1; ++x) {
                const std::size_t local =
                    static_cast<std::size_t>(y - rays.y0) * kFragmentTile + (x - rays.x0);
                Vec3 mean(sum[local * 3], sum[local * 3 + 1], sum[local * 3 + 2]);
                mean /= static_cast<double>(repetitions);
                // The fraction of repetitions with a particle: what lies behind shows in the
                // others, so the picture is (colours) + (1 - hit fraction) behind.
                double opacity = count_hits ? static_cast<double>(hits[local]) / repetitions : 0;
                if (options.control_variate && weight[local] > 0) {
                    // The fraction of repetitions with a particle has a known expectation,
                    // 1 - (the transparency of all the segments): its deviation times the
                    // expected colour change it brings (approximated by the segments' colours
                    // weighted by opacity, less what lies behind) is taken out.
                    const double expected_hits = -std::expm1(log_transparency[local]);
                    const double deviation =
                        static_cast<double>(hits[local]) / repetitions - expected_hits;
                    const Vec3 beta = weighted_color[local] / weight[local] - Vec3(behind.at(x, y));
                    mean -= deviation * beta;
                    // What lies behind now weighs (1 - hit fraction) + deviation = T exactly.
                    opacity = expected_hits;
                }
                image.at(x, y) = Vec3f(mean);
                if (alpha_out) {
                    (*alpha_out)[static_cast<std::size_t>(y) * w + x] = static_cast<float>(opacity);
                }
            }
        }
    });
    if (stats) {
        stats->fragments = total_fragments.load();
        stats->particles = total_particles.load();
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
