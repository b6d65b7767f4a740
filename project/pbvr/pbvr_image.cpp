#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/pbvr/pbvr_image.h>
#include <project/tet_fragments.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <span>
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

constexpr std::size_t kTilePixels = kFragmentTile * kFragmentTile;

// What every tile reads: the volumes, the camera, the options and what they decide.
struct ImagePlan {
    const VolumeScene& scene;
    const ImagePbvrOptions& options;
    const CameraFrame& camera;
    const std::vector<VolumeState>& volumes;
    int repetitions;
    // One volume's segments never overlap on a ray: the nearest segment with a particle holds
    // the nearest particle, and only the winner's depth need be drawn — or, with a shader, its
    // expected colour taken instead.
    bool disjoint;
    bool mean_colors;
    // Repetitions with a particle are counted per pixel for the control variate and, without
    // it, for the opacity asked for (the fraction of repetitions that hide what lies behind).
    bool count_hits;
    std::span<const double> max_depth;
    const Image& behind;
    // The lattices' generators for a whole pass and for a shorter last one.
    int full_pass;
    const LatticeUnits& full_units;
    const LatticeUnits& last_units;
};

// A tile's working buffers, kept per worker between tiles.
struct TileBuffers {
    std::vector<Fragment> fragments;
    std::vector<double> alpha;
    std::vector<Vec3f> mean_color;
    std::vector<SegmentQuery> queries;
    std::vector<ShadedSegment> shaded;
    // The control variate's per-pixel sums (pbvr_image.h): the log of the transparency of all
    // the pixel's segments, and their colours weighted by opacity.
    std::vector<double> log_transparency, weight;
    std::vector<Vec3> weighted_color;
    std::vector<int> hits;
    std::vector<std::uint64_t> nearest;
    std::vector<double> shifts;
    std::vector<std::uint64_t> generators;  // stratified: g; else a stream's key
};

// The tile's fragments, all volumes.
void gather_fragments(const ImagePlan& plan, std::size_t tile, const TileRays& rays,
                      std::vector<Fragment>& fragments) {
    fragments.clear();
    const int w = plan.camera.width();
    for (std::size_t v = 0; v < plan.volumes.size(); ++v) {
        const VolumeState& state = plan.volumes[v];
        const VolumeData& volume = *state.volume;
        for (std::uint32_t index : state.bins.bins[tile]) {
            const CellId t = state.cells[index];
            const CellFragments cell(*volume.mesh, volume.scalar, t, plan.camera);
            for_each_fragment(
                cell, state.bins.boxes[index], rays, w, plan.max_depth,
                [&](int x, int y, double t_in, double t_out, double s_in, double s_out) {
                    const double length = t_out - t_in;
                    // With mean colours the shader gives the opacity (segment_opacities).
                    const double depth =
                        plan.mean_colors ? 0.0 : length * volume.tf->mean_extinction(s_in, s_out);
                    if (!plan.mean_colors && !(depth > 0)) return;
                    fragments.push_back(
                        {t,
                         static_cast<std::uint16_t>((y - rays.y0) * kFragmentTile + (x - rays.x0)),
                         static_cast<std::uint8_t>(v), static_cast<float>(t_in),
                         static_cast<float>(length), static_cast<float>(s_in),
                         static_cast<float>(s_out), static_cast<float>(depth)});
                });
        }
    }
}

// Each segment's opacity, and with mean colours its mean colour C / alpha from the shader (its
// opacity exact in the length: TransferFunction::mean_extinction's); with mean colours only the
// segments with a particle to give are kept.
void segment_opacities(const ImagePlan& plan, TileBuffers& buffers) {
    std::vector<Fragment>& fragments = buffers.fragments;
    std::vector<double>& alpha = buffers.alpha;
    if (!plan.mean_colors) {
        alpha.resize(fragments.size());
        for (std::size_t i = 0; i < fragments.size(); ++i) {
            alpha[i] = -std::expm1(-static_cast<double>(fragments[i].optical_depth));
        }
        return;
    }
    buffers.queries.resize(fragments.size());
    buffers.shaded.resize(fragments.size());
    for (std::size_t i = 0; i < fragments.size(); ++i) {
        buffers.queries[i] = {fragments[i].s_in, fragments[i].s_out, fragments[i].length};
    }
    plan.scene.volumes[0].shader->shade(buffers.queries, buffers.shaded);
    std::size_t kept = 0;
    alpha.resize(fragments.size());
    buffers.mean_color.resize(fragments.size());
    for (std::size_t i = 0; i < fragments.size(); ++i) {
        const ShadedSegment& shaded = buffers.shaded[i];
        if (!(shaded.alpha > 0)) continue;
        fragments[kept] = fragments[i];
        alpha[kept] = shaded.alpha;
        buffers.mean_color[kept] = shaded.color / shaded.alpha;
        ++kept;
    }
    fragments.resize(kept);
    alpha.resize(kept);
}

// The hit counters, and the control variate's sums over each pixel's segments.
void control_variate_sums(const ImagePlan& plan, TileBuffers& buffers) {
    if (plan.count_hits) buffers.hits.assign(kTilePixels, 0);
    if (!plan.options.control_variate) return;
    buffers.log_transparency.assign(kTilePixels, 0.0);
    buffers.weight.assign(kTilePixels, 0.0);
    buffers.weighted_color.assign(kTilePixels, Vec3(0.0));
    for (std::size_t i = 0; i < buffers.fragments.size(); ++i) {
        const Fragment& f = buffers.fragments[i];
        const double alpha = buffers.alpha[i];
        const Vec3 c = plan.mean_colors ? Vec3(buffers.mean_color[i])
                                        : plan.volumes[f.volume].volume->tf->color(
                                              0.5 * (static_cast<double>(f.s_in) + f.s_out));
        buffers.log_transparency[f.pixel] += std::log1p(-alpha);
        buffers.weight[f.pixel] += alpha;
        buffers.weighted_color[f.pixel] += alpha * c;
    }
}

// One pass of `count` repetitions over a tile: every fragment's particles drawn into the
// nearest-particle buffer, then each pixel's winners' colours summed.
class TilePass {
  public:
    TilePass(const ImagePlan& plan, const TileRays& rays, TileBuffers& buffers, int count)
        : plan_(plan), rays_(rays), buffers_(buffers), count_(count) {}

    // Draws every fragment's particles of pass `pass`; returns how many were drawn.
    std::size_t draw(int pass, const LatticeUnits& units) {
        std::vector<Fragment>& fragments = buffers_.fragments;
        buffers_.nearest.assign(kTilePixels * count_, kNoParticle);
        // Each fragment's numbers in this pass: a random shift and lattice (stratified) or a
        // stream of independent uniforms.
        buffers_.shifts.resize(fragments.size());
        buffers_.generators.resize(fragments.size());
        std::size_t particles = 0;
        for (std::uint32_t i = 0; i < fragments.size(); ++i) {
            const Fragment& f = fragments[i];
            const double a = buffers_.alpha[i];
            const std::uint64_t key =
                hash_key(plan_.options.seed, static_cast<std::uint64_t>(pass),
                         (static_cast<std::uint64_t>(f.volume) << 32) | f.cell, global_pixel(f));
            std::uint64_t* slots = &buffers_.nearest[static_cast<std::size_t>(f.pixel) * count_];
            // Repetition r has a particle in f when its uniform u < alpha; its depth is the
            // CDF's inverse at q = u / alpha.
            auto visit = [&](int r, double u) {
                ++particles;
                std::uint64_t& slot = slots[r];
                if (slot != kNoParticle && key_of(slot) <= f.t_in) return;  // can't be nearer
                if (plan_.disjoint) {
                    slot = pack_key(f.t_in, i);
                    return;
                }
                double t;
                Vec3 color;
                particle(f, std::min(u / a, 1.0 - 1e-16), t, color);
                const auto depth = static_cast<float>(t);
                if (slot == kNoParticle || depth < key_of(slot)) slot = pack_key(depth, i);
            };
            if (plan_.options.stratified) {
                const SegmentLattice lattice = units.lattice(key);
                buffers_.shifts[i] = uniform01(key);
                buffers_.generators[i] = static_cast<std::uint64_t>(lattice.generator());
                lattice.for_each_below(a, buffers_.shifts[i], visit);
            } else {
                buffers_.generators[i] = key;
                for (int r = 0; r < count_; ++r) {
                    const double u = uniform_of(i, r);
                    if (u < a) visit(r, u);
                }
            }
        }
        return particles;
    }

    // Each pixel: the winners' colours (or what lies behind) summed over the pass into `sum`
    // (three per tile pixel).
    void sum_colors(std::vector<double>& sum) const {
        for (int y = rays_.y0; y <= rays_.y1; ++y) {
            for (int x = rays_.x0; x <= rays_.x1; ++x) {
                const std::size_t local =
                    static_cast<std::size_t>(y - rays_.y0) * kFragmentTile + (x - rays_.x0);
                const Vec3 back(plan_.behind.at(x, y));
                Vec3 total(0.0);
                for (int r = 0; r < count_; ++r) {
                    const std::uint64_t e = buffers_.nearest[local * count_ + r];
                    if (e == kNoParticle) {
                        total += back;
                        continue;
                    }
                    if (plan_.count_hits) ++buffers_.hits[local];
                    const std::uint32_t i = static_cast<std::uint32_t>(e);
                    if (plan_.mean_colors) {
                        total += Vec3(buffers_.mean_color[i]);
                        continue;
                    }
                    // The winner's particle, drawn again from the same number.
                    double t;
                    Vec3 color;
                    particle(buffers_.fragments[i],
                             std::min(uniform_of(i, r) / buffers_.alpha[i], 1.0 - 1e-16), t, color);
                    total += color;
                }
                for (int k = 0; k < 3; ++k) sum[local * 3 + k] += total[k];
            }
        }
    }

  private:
    std::size_t global_pixel(const Fragment& f) const {
        const int x = rays_.x0 + f.pixel % kFragmentTile, y = rays_.y0 + f.pixel / kFragmentTile;
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(plan_.camera.width()) + x;
    }

    // Fragment i's uniform number of repetition r.
    double uniform_of(std::uint32_t i, int r) const {
        if (plan_.options.stratified) {
            const double u = buffers_.shifts[i] +
                             static_cast<double>(
                                 (static_cast<std::int64_t>(r) * buffers_.generators[i]) % count_) /
                                 count_;
            return u >= 1.0 ? u - 1.0 : u;
        }
        return uniform01(hash_key(buffers_.generators[i], static_cast<std::uint64_t>(r)));
    }

    // The particle of fragment f at CDF value q: its distance from the eye and colour.
    void particle(const Fragment& f, double q, double& t, Vec3& color) const {
        const VolumeState& state = plan_.volumes[f.volume];
        const double along = particle_depth(plan_.options.depth, state.phi, f.s_in, f.s_out,
                                            f.length, f.optical_depth, q);
        t = f.t_in + along;
        const double s = f.length > 0 ? f.s_in + (f.s_out - f.s_in) * along / f.length : f.s_in;
        color = state.volume->tf->color(s);
    }

    const ImagePlan& plan_;
    const TileRays& rays_;
    TileBuffers& buffers_;
    int count_;
};

// The tile's pixels: the mean over the repetitions (with the control variate's correction) and
// the opacity asked for.
void resolve_tile(const ImagePlan& plan, const TileRays& rays, const TileBuffers& buffers,
                  const std::vector<double>& sum, Image& image, std::vector<float>* alpha_out) {
    const int repetitions = plan.repetitions;
    for (int y = rays.y0; y <= rays.y1; ++y) {
        for (int x = rays.x0; x <= rays.x1; ++x) {
            const std::size_t local =
                static_cast<std::size_t>(y - rays.y0) * kFragmentTile + (x - rays.x0);
            Vec3 mean(sum[local * 3], sum[local * 3 + 1], sum[local * 3 + 2]);
            mean /= static_cast<double>(repetitions);
            // The fraction of repetitions with a particle: what lies behind shows in the
            // others, so the picture is (colours) + (1 - hit fraction) behind.
            double opacity =
                plan.count_hits ? static_cast<double>(buffers.hits[local]) / repetitions : 0;
            if (plan.options.control_variate && buffers.weight[local] > 0) {
                // The fraction of repetitions with a particle has a known expectation,
                // 1 - (the transparency of all the segments): its deviation times the expected
                // colour change it brings (approximated by the segments' colours weighted by
                // opacity, less what lies behind) is taken out.
                const double expected_hits = -std::expm1(buffers.log_transparency[local]);
                const double deviation =
                    static_cast<double>(buffers.hits[local]) / repetitions - expected_hits;
                const Vec3 beta = buffers.weighted_color[local] / buffers.weight[local] -
                                  Vec3(plan.behind.at(x, y));
                mean -= deviation * beta;
                // What lies behind now weighs (1 - hit fraction) + deviation = T exactly.
                opacity = expected_hits;
            }
            image.at(x, y) = Vec3f(mean);
            if (alpha_out) {
                (*alpha_out)[static_cast<std::size_t>(y) * plan.camera.width() + x] =
                    static_cast<float>(opacity);
            }
        }
    }
}

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
    Image image(w, h, Vec3f(scene.background));
    if (scene.opaque_color) image = *scene.opaque_color;
    const Image behind = image;
    if (alpha_out) alpha_out->assign(static_cast<std::size_t>(w) * h, 0.0f);
    const bool disjoint = volumes.size() == 1;
    const int full_pass = std::min(repetitions, kRepetitionsPerPass);
    const LatticeUnits full_units(full_pass);
    const LatticeUnits last_units(
        repetitions % kRepetitionsPerPass == 0 ? 1 : repetitions % kRepetitionsPerPass);
    const ImagePlan plan{
        .scene = scene,
        .options = options,
        .camera = camera,
        .volumes = volumes,
        .repetitions = repetitions,
        .disjoint = disjoint,
        .mean_colors = disjoint && options.depth == ParticleDepth::kInverseCdf &&
                       scene.volumes[0].shader != nullptr,
        .count_hits = options.control_variate || alpha_out != nullptr,
        .max_depth = scene.opaque_depth ? std::span<const double>(*scene.opaque_depth)
                                        : std::span<const double>(),
        .behind = behind,
        .full_pass = full_pass,
        .full_units = full_units,
        .last_units = last_units,
    };

    const std::size_t num_tiles = volumes.empty() ? 0 : volumes[0].bins.num_tiles();
    std::atomic<std::size_t> total_fragments{0}, total_particles{0};
    parallel_for(0, num_tiles, 1, [&](std::size_t tile) {
        TileRays rays;
        tile_rays(volumes[0].bins, tile, camera, rays);
        thread_local TileBuffers buffers;
        gather_fragments(plan, tile, rays, buffers.fragments);
        segment_opacities(plan, buffers);
        total_fragments += buffers.fragments.size();
        control_variate_sums(plan, buffers);
        std::vector<double> sum(kTilePixels * 3, 0.0);
        std::size_t particles = 0;
        for (int pass = 0, done = 0; done < repetitions; ++pass) {
            const int count = std::min(kRepetitionsPerPass, repetitions - done);
            done += count;
            TilePass tile_pass(plan, rays, buffers, count);
            particles += tile_pass.draw(pass, count == full_pass ? full_units : last_units);
            tile_pass.sum_colors(sum);
        }
        total_particles += particles;
        resolve_tile(plan, rays, buffers, sum, image, alpha_out);
    });
    if (stats) {
        stats->fragments = total_fragments.load();
        stats->particles = total_particles.load();
        stats->raster_ms = ms_since(start);
    }
    return image;
}

}  // namespace tr
