#include <core/parallel.h>
#include <core/stopwatch.h>
#include <project/pbvr/pbvr_object.h>
#include <project/pbvr/pbvr_sampling.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kCellsPerChunk = 2048;

// The view's geometry the particle density needs.
struct DensityView {
    const CameraFrame* camera;
    bool orthographic;
    Vec3 eye, forward;
    double footprint_scale;  // sub-pixel side = footprint_scale * z (perspective) or itself
    double near;             // perspective: particles nearer than this are dropped
    double min_cos;          // smallest cos(theta) over the picture's rays (perspective)
    int subpixel_level;
};

DensityView make_view(const CameraFrame& camera, int subpixel_level, double scene_size) {
    DensityView view;
    view.camera = &camera;
    view.orthographic = camera.orthographic();
    view.eye = camera.eye();
    view.forward = camera.forward();
    view.subpixel_level = subpixel_level;
    // The width of one sub-pixel: the distance between neighbouring pixel rays.
    const Ray a = camera.ray(0.5 * camera.width(), 0.5 * camera.height());
    const Ray b = camera.ray(0.5 * camera.width(), 0.5 * camera.height() + 1.0);
    if (view.orthographic) {
        view.footprint_scale = glm::length(b.origin - a.origin) / subpixel_level;
        view.min_cos = 1.0;
    } else {
        // Rays at unit depth along `forward`.
        const Vec3 pa = a.direction / glm::dot(a.direction, view.forward);
        const Vec3 pb = b.direction / glm::dot(b.direction, view.forward);
        view.footprint_scale = glm::length(pb - pa) / subpixel_level;
        double min_cos = 1.0;
        for (double x : {0.0, static_cast<double>(camera.width())}) {
            for (double y : {0.0, static_cast<double>(camera.height())}) {
                min_cos = std::min(min_cos, glm::dot(camera.ray(x, y).direction, view.forward));
            }
        }
        view.min_cos = min_cos;
    }
    view.near = 1e-6 * std::max(scene_size, 1e-300);
    return view;
}

// The depth along the view direction (perspective: from the eye).
double depth_of(const DensityView& view, const Vec3& x) {
    return glm::dot(x - view.eye, view.forward);
}

// rho's denominator at x: the sub-pixel footprint times cos(theta).
double footprint(const DensityView& view, const Vec3& x, double z) {
    if (view.orthographic) return view.footprint_scale * view.footprint_scale;
    const double side = view.footprint_scale * z;
    const double cos_theta = z / glm::length(x - view.eye);
    return side * side * cos_theta;
}

// The largest extinction over the scalars between lo and hi (the opacity is piecewise linear:
// its largest value is at an end or a control point between).
double max_extinction(const TransferFunction& tf, double lo, double hi) {
    double a = std::max(tf.opacity(lo), tf.opacity(hi));
    for (const OpacityPoint& p : tf.opacity_points()) {
        if (p.s > lo && p.s < hi) a = std::max(a, p.a);
    }
    return tf.extinction_from_opacity(a);
}

// A point uniform in the tet from three uniforms (sorted spacings of the simplex).
Vec3 uniform_in_tet(const Vec3 corners[4], double u1, double u2, double u3, double weights[4]) {
    double a = u1, b = u2, c = u3;
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    weights[0] = a;
    weights[1] = b - a;
    weights[2] = c - b;
    weights[3] = 1.0 - c;
    return weights[0] * corners[0] + weights[1] * corners[1] + weights[2] * corners[2] +
           weights[3] * corners[3];
}

// One cell's data for generation.
struct Cell {
    Vec3 corners[4];
    double scalars[4];
    double volume;
};

Cell cell_of(const VolumeData& v, CellId t) {
    Cell c;
    const Tet& tet = v.mesh->tet(t);
    for (int k = 0; k < 4; ++k) {
        c.corners[k] = v.mesh->point(tet[k]);
        c.scalars[k] = v.scalar[tet[k]];
    }
    c.volume = std::abs(tet_volume(c.corners[0], c.corners[1], c.corners[2], c.corners[3]));
    return c;
}

double density_at(const VolumeData& v, const DensityView& view, const Vec3& x, double s) {
    const double z = depth_of(view, x);
    if (!view.orthographic && z < view.near) return 0.0;
    return v.tf->extinction(s) / footprint(view, x, z);
}

// The 32-point quadrature of rho over a cell: 8 sub-tets by midpoint subdivision, the
// degree-2 four-point rule on each.
double integrate_density(const VolumeData& v, const DensityView& view, const Cell& c) {
    // The 10 nodes: corners 0..3, then edge midpoints (01, 02, 03, 12, 13, 23).
    Vec3 p[10];
    double s[10];
    for (int k = 0; k < 4; ++k) p[k] = c.corners[k], s[k] = c.scalars[k];
    const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (int e = 0; e < 6; ++e) {
        p[4 + e] = 0.5 * (p[edges[e][0]] + p[edges[e][1]]);
        s[4 + e] = 0.5 * (s[edges[e][0]] + s[edges[e][1]]);
    }
    // Corners keep a small tet each; the octahedron in the middle splits along edge 02-13.
    const int subs[8][4] = {{0, 4, 5, 6}, {4, 1, 7, 8}, {5, 7, 2, 9}, {6, 8, 9, 3},
                            {5, 8, 4, 6}, {5, 8, 6, 9}, {5, 8, 9, 7}, {5, 8, 7, 4}};
    const double a = 0.5854101966249685, b = 0.1381966011250105;  // the rule's barycentrics
    double sum = 0;
    for (const auto& sub : subs) {
        for (int q = 0; q < 4; ++q) {
            Vec3 x(0.0);
            double sx = 0;
            for (int k = 0; k < 4; ++k) {
                const double w = k == q ? a : b;
                x += w * p[sub[k]];
                sx += w * s[sub[k]];
            }
            sum += density_at(v, view, x, sx);
        }
    }
    return sum / 32.0 * c.volume;
}

// How many particles: floor(mean) + Bernoulli(frac(mean)).
std::size_t floor_bernoulli(double mean, double u) {
    const double whole = std::floor(mean);
    return static_cast<std::size_t>(whole) + (u < mean - whole ? 1 : 0);
}

// The sub-pixel buffer one repetition's particles are projected into: per sub-pixel the nearest
// particle (depth and colour, one 64-bit word updated atomically: the nearest wins whatever the
// order), then resolved into the pixels' running sums.
class ParticleBuffer {
  public:
    ParticleBuffer(const DensityView& view, const VolumeScene& scene)
        : view_(view),
          scene_(scene),
          sub_width_(view.camera->width() * view.subpixel_level),
          sub_height_(view.camera->height() * view.subpixel_level),
          slots_(static_cast<std::size_t>(sub_width_) * sub_height_),
          behind_(view.camera->width(), view.camera->height(), Vec3f(scene.background)) {
        if (scene.opaque_color) behind_ = *scene.opaque_color;
    }

    void clear() {
        parallel_for(0, slots_.size(), 1 << 16, [&](std::size_t i) {
            slots_[i].store(kNoParticle, std::memory_order_relaxed);
        });
    }

    // Projects a particle at x with colour `color` covering `footprint` sub-pixels (1: its own;
    // more: the sub-pixels whose centres lie in a square of that area around it). False when it
    // is behind the eye, out of the picture or behind opaque geometry.
    bool deposit(const Vec3& x, const Vec3& color, double footprint = 1.0) {
        const Vec3 q = view_.camera->project(x);
        if (view_.orthographic ? q.z < 0 : q.z < view_.near) return false;  // behind the eye
        const double sx = q.x * view_.subpixel_level, sy = q.y * view_.subpixel_level;
        const double half = footprint > 1 ? 0.5 * std::sqrt(footprint) : 0.0;
        if (!(sx + half >= 0 && sy + half >= 0 && sx - half < sub_width_ &&
              sy - half < sub_height_)) {
            return false;
        }
        // The ray parameter of the particle along its pixel's ray, as opaque depths are kept.
        const Ray ray = view_.camera->ray(q.x, q.y);
        const double t = glm::dot(x - ray.origin, ray.direction);
        const std::uint64_t entry = pack_particle(static_cast<float>(t), color);
        if (footprint <= 1) {
            if (!(sx >= 0 && sy >= 0)) return false;
            return offer(static_cast<int>(sx), static_cast<int>(sy), t, entry);
        }
        // Sub-pixel centres (i + 0.5) within [sx - half, sx + half).
        const int x0 = std::max(0, static_cast<int>(std::ceil(sx - half - 0.5)));
        const int x1 = std::min(sub_width_ - 1, static_cast<int>(std::ceil(sx + half - 0.5)) - 1);
        const int y0 = std::max(0, static_cast<int>(std::ceil(sy - half - 0.5)));
        const int y1 = std::min(sub_height_ - 1, static_cast<int>(std::ceil(sy + half - 0.5)) - 1);
        bool any = false;
        for (int iy = y0; iy <= y1; ++iy) {
            for (int ix = x0; ix <= x1; ++ix) any = offer(ix, iy, t, entry) || any;
        }
        return any;
    }

    // Adds each pixel's mean over its sub-pixels (the particle's colour, or what lies behind)
    // to `sum` (3 doubles per pixel) and, when `coverage` is given (one double per pixel), the
    // fraction of its sub-pixels that hold a particle to `coverage`.
    void resolve_into(std::vector<double>& sum, std::vector<double>* coverage = nullptr) const {
        if (coverage) {
            resolve<true>(sum, coverage->data());
        } else {
            resolve<false>(sum, nullptr);
        }
    }

  private:
    template <bool kCoverage>
    void resolve(std::vector<double>& sum, double* coverage) const {
        const int w = view_.camera->width(), h = view_.camera->height();
        const int level = view_.subpixel_level;
        const float inverse_subpixels = 1.0f / static_cast<float>(level * level);
        parallel_for(0, static_cast<std::size_t>(h), 8, [&](std::size_t y) {
            for (int x = 0; x < w; ++x) {
                Vec3f pixel(0.0f);
                [[maybe_unused]] int covered = 0;
                const Vec3f& back = behind_.at(x, static_cast<int>(y));
                for (int j = 0; j < level; ++j) {
                    const std::size_t row = (y * level + j) * static_cast<std::size_t>(sub_width_);
                    for (int i = 0; i < level; ++i) {
                        const std::uint64_t e =
                            slots_[row + static_cast<std::size_t>(x) * level + i].load(
                                std::memory_order_relaxed);
                        pixel += e == kNoParticle ? back : particle_color(e);
                        if constexpr (kCoverage) covered += e != kNoParticle;
                    }
                }
                double* out = &sum[(y * w + x) * 3];
                for (int k = 0; k < 3; ++k) out[k] += pixel[k] * inverse_subpixels;
                if constexpr (kCoverage) {
                    coverage[y * w + x] += static_cast<double>(covered) / (level * level);
                }
            }
        });
    }

    bool offer(int ix, int iy, double t, std::uint64_t entry) {
        if (ix >= sub_width_ || iy >= sub_height_) return false;
        if (scene_.opaque_depth) {
            const int px = ix / view_.subpixel_level, py = iy / view_.subpixel_level;
            const std::size_t pixel = static_cast<std::size_t>(py) * view_.camera->width() + px;
            if (t >= (*scene_.opaque_depth)[pixel]) return false;
        }
        std::atomic<std::uint64_t>& slot =
            slots_[static_cast<std::size_t>(iy) * sub_width_ + static_cast<std::size_t>(ix)];
        std::uint64_t current = slot.load(std::memory_order_relaxed);
        while (entry < current &&
               !slot.compare_exchange_weak(current, entry, std::memory_order_relaxed)) {
        }
        return true;
    }

    const DensityView& view_;
    const VolumeScene& scene_;
    int sub_width_, sub_height_;
    std::vector<std::atomic<std::uint64_t>> slots_;
    Image behind_;
};

// Generates one cell's particles of one repetition.
struct Generator {
    const VolumeData& volume;
    std::size_t volume_index;
    const DensityView& view;
    const ObjectPbvrOptions& options;
    const std::vector<float>& bound;  // per cell: the expected candidates (kExact) or particles

    // Calls emit(x, s) for each particle (position, scalar); counts[0] += candidates drawn,
    // counts[1] += particles.
    template <class Emit>
    void generate(CellId t, int repetition, std::size_t counts[2], Emit&& emit) const {
        const float mean = bound[t];
        if (!(mean > 0)) return;
        const Cell c = cell_of(volume, t);
        const std::uint64_t key =
            hash_key(options.seed, static_cast<std::uint64_t>(repetition), volume_index, t);
        std::uint64_t next = 0;
        auto uniform = [&] { return uniform01(hash_key(key, next++)); };
        double w[4];
        auto sample = [&](double& s) {
            const Vec3 x = uniform_in_tet(c.corners, uniform(), uniform(), uniform(), w);
            s = w[0] * c.scalars[0] + w[1] * c.scalars[1] + w[2] * c.scalars[2] +
                w[3] * c.scalars[3];
            return x;
        };
        switch (options.sampling) {
            case ParticleSampling::kExact: {
                // Poisson(mean) candidates as the arrivals of a unit-rate process in [0, mean].
                const double rho_max = mean / c.volume;
                for (double arrival = -std::log1p(-uniform()); arrival < mean;
                     arrival -= std::log1p(-uniform())) {
                    ++counts[0];
                    double s;
                    const Vec3 x = sample(s);
                    if (uniform() * rho_max >= density_at(volume, view, x, s)) continue;
                    ++counts[1];
                    emit(x, s);
                }
                return;
            }
            case ParticleSampling::kUniform: {
                const std::size_t n = floor_bernoulli(mean, uniform());
                for (std::size_t i = 0; i < n; ++i) {
                    double s;
                    const Vec3 x = sample(s);
                    ++counts[1];
                    emit(x, s);
                }
                return;
            }
            case ParticleSampling::kMetropolis: {
                const std::size_t n = floor_bernoulli(mean, uniform());
                if (n == 0) return;
                // An independence chain: proposals uniform in the cell, accepted with the
                // ratio of densities; a short burn-in from a uniform start.
                double s;
                Vec3 x = sample(s);
                double rho = density_at(volume, view, x, s);
                constexpr int kBurnIn = 8;
                for (std::size_t i = 0; i < n + kBurnIn; ++i) {
                    double s_new;
                    const Vec3 y = sample(s_new);
                    const double rho_new = density_at(volume, view, y, s_new);
                    if (rho_new >= rho || uniform() * rho < rho_new) {
                        x = y, s = s_new, rho = rho_new;
                    }
                    if (i < kBurnIn) continue;
                    ++counts[1];
                    emit(x, s);
                }
                return;
            }
        }
    }
};

// Per cell the number the generation draws from: the expected candidates of the thinning
// (kExact: the cell's volume times the largest density over it), the density at the centroid
// times the volume (kUniform) or the density's integral (kMetropolis). Zero for cells wholly
// out of view or transparent.
std::vector<float> cell_bounds(const VolumeData& v, const DensityView& view,
                               const ParticleSampling sampling) {
    std::vector<float> bound(v.mesh->num_real_tets(), 0.0f);
    const CameraFrame& camera = *view.camera;
    parallel_for(0, bound.size(), 1024, [&](std::size_t i) {
        const CellId t = static_cast<CellId>(i);
        const Cell c = cell_of(v, t);
        double lo = c.scalars[0], hi = lo, z_lo = std::numeric_limits<double>::infinity(),
               z_hi = -z_lo;
        double x0 = z_lo, x1 = -z_lo, y0 = z_lo, y1 = -z_lo;
        for (int k = 0; k < 4; ++k) {
            lo = std::min(lo, c.scalars[k]), hi = std::max(hi, c.scalars[k]);
            const Vec3 q = camera.project(c.corners[k]);
            z_lo = std::min(z_lo, q.z), z_hi = std::max(z_hi, q.z);
            x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
            y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
        }
        if (!view.orthographic) {
            if (z_hi < view.near) return;  // wholly behind the eye
            z_lo = std::max(z_lo, view.near);
        }
        // Wholly outside the picture (only decidable when every corner is in front).
        if (view.orthographic || z_lo > view.near) {
            if (x1 < 0 || y1 < 0 || x0 > camera.width() || y0 > camera.height()) return;
        }
        const double kappa_max = max_extinction(*v.tf, lo, hi);
        if (!(kappa_max > 0)) return;
        double mean = 0;
        switch (sampling) {
            case ParticleSampling::kExact: {
                const double area = view.orthographic
                                        ? view.footprint_scale * view.footprint_scale
                                        : std::pow(view.footprint_scale * z_lo, 2) * view.min_cos;
                mean = c.volume * kappa_max / area;
                break;
            }
            case ParticleSampling::kUniform: {
                const Vec3 centroid =
                    0.25 * (c.corners[0] + c.corners[1] + c.corners[2] + c.corners[3]);
                const double s = 0.25 * (c.scalars[0] + c.scalars[1] + c.scalars[2] + c.scalars[3]);
                mean = c.volume * density_at(v, view, centroid, s);
                break;
            }
            case ParticleSampling::kMetropolis:
                mean = integrate_density(v, view, c);
                break;
        }
        bound[i] = static_cast<float>(std::min(mean, 1e30));
    });
    return bound;
}

double scene_size(const VolumeScene& scene) {
    Bounds3 b;
    for (const VolumeData& v : scene.volumes) {
        const Bounds3 vb = v.mesh->bounds();
        if (!vb.empty()) b.extend(vb.lo), b.extend(vb.hi);
    }
    return b.diagonal();
}

}  // namespace

std::string_view particle_sampling_name(ParticleSampling sampling) {
    switch (sampling) {
        case ParticleSampling::kExact:
            return "exact";
        case ParticleSampling::kUniform:
            return "uniform";
        case ParticleSampling::kMetropolis:
            return "metropolis";
    }
    return "?";
}

std::optional<ParticleSampling> parse_particle_sampling(std::string_view name) {
    for (ParticleSampling s :
         {ParticleSampling::kExact, ParticleSampling::kUniform, ParticleSampling::kMetropolis}) {
        if (particle_sampling_name(s) == name) return s;
    }
    return std::nullopt;
}

double expected_particles(const VolumeData& volume, CellId t, const CameraFrame& camera,
                          int subpixel_level) {
    const DensityView view = make_view(camera, subpixel_level, volume.mesh->bounds().diagonal());
    return integrate_density(volume, view, cell_of(volume, t));
}

ObjectPbvrPlan plan_object_pbvr(const VolumeScene& scene, const ObjectPbvrOptions& options) {
    const DensityView view =
        make_view(*scene.camera, std::max(1, options.subpixel_level), scene_size(scene));
    ObjectPbvrPlan plan;
    for (const VolumeData& v : scene.volumes) {
        plan.bounds.push_back(cell_bounds(v, view, options.sampling));
        for (float b : plan.bounds.back()) plan.candidates += b;
    }
    return plan;
}

double expected_candidates(const VolumeScene& scene, const ObjectPbvrOptions& options) {
    return plan_object_pbvr(scene, options).candidates;
}

Image render_object_pbvr(const VolumeScene& scene, const ObjectPbvrOptions& options,
                         ObjectPbvrStats* stats, const ObjectPbvrPlan* plan,
                         std::vector<float>* alpha) {
    const CameraFrame& camera = *scene.camera;
    const int w = camera.width(), h = camera.height();
    const int level = std::max(1, options.subpixel_level);
    const int repetitions = std::max(1, options.repetitions);
    const DensityView view = make_view(camera, level, scene_size(scene));
    ParticleBuffer buffer(view, scene);
    const ObjectPbvrPlan own = plan ? ObjectPbvrPlan{} : plan_object_pbvr(scene, options);
    const std::vector<std::vector<float>>& bounds = plan ? plan->bounds : own.bounds;
    std::vector<double> sum(static_cast<std::size_t>(w) * h * 3, 0.0);
    // With alpha asked for: per pixel the sub-pixels holding a particle, summed over repetitions
    // as fractions (what lies behind shows in the others).
    std::vector<double> coverage(alpha ? static_cast<std::size_t>(w) * h : 0, 0.0);
    std::atomic<std::size_t> candidates{0}, particles{0}, projected{0};
    double generate_ms = 0, resolve_ms = 0;
    for (int r = 0; r < repetitions; ++r) {
        auto start = Clock::now();
        buffer.clear();
        for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
            const VolumeData& volume = scene.volumes[v];
            const Generator gen{volume, v, view, options, bounds[v]};
            parallel_for_chunks(
                0, volume.mesh->num_real_tets(), kCellsPerChunk, [&](std::size_t b, std::size_t e) {
                    std::size_t counts[2] = {0, 0}, reached = 0;
                    for (std::size_t t = b; t < e; ++t) {
                        gen.generate(static_cast<CellId>(t), r, counts,
                                     [&](const Vec3& x, double s) {
                                         reached += buffer.deposit(x, volume.tf->color(s));
                                     });
                    }
                    candidates += counts[0];
                    particles += counts[1];
                    projected += reached;
                });
        }
        generate_ms += ms_since(start);
        start = Clock::now();
        buffer.resolve_into(sum, alpha ? &coverage : nullptr);
        resolve_ms += ms_since(start);
    }
    Image image(w, h);
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
        image.pixels[p] = Vec3f(static_cast<float>(sum[3 * p] / repetitions),
                                static_cast<float>(sum[3 * p + 1] / repetitions),
                                static_cast<float>(sum[3 * p + 2] / repetitions));
    }
    if (alpha) {
        alpha->resize(coverage.size());
        for (std::size_t p = 0; p < coverage.size(); ++p) {
            (*alpha)[p] = static_cast<float>(coverage[p] / repetitions);
        }
    }
    if (stats) {
        stats->candidates = candidates.load();
        stats->particles = particles.load();
        stats->projected = projected.load();
        stats->generate_ms = generate_ms;
        stats->resolve_ms = resolve_ms;
    }
    return image;
}

ObjectParticleSet ObjectParticleSet::generate(const VolumeScene& scene,
                                              const ObjectPbvrOptions& options,
                                              const ObjectPbvrPlan* plan) {
    ObjectParticleSet set;
    set.options_ = options;
    set.options_.repetitions = std::max(1, options.repetitions);
    set.options_.subpixel_level = std::max(1, options.subpixel_level);
    set.frame_ = *scene.camera;
    set.repetitions_.resize(static_cast<std::size_t>(set.options_.repetitions));
    for (const VolumeData& v : scene.volumes) {
        set.functions_.push_back({*v.tf});
        set.cell_function_.emplace_back(v.mesh->num_real_tets(), std::uint16_t{0});
    }
    set.generate_cells(scene, nullptr, plan);
    return set;
}

void ObjectParticleSet::generate_cells(const VolumeScene& scene,
                                       const std::vector<std::vector<char>>* only,
                                       const ObjectPbvrPlan* plan) {
    const DensityView view = make_view(*frame_, options_.subpixel_level, scene_size(scene));
    ObjectPbvrOptions options = options_;
    // The first generation draws what render_object_pbvr draws; regenerations new numbers.
    if (generation_ > 0) options.seed = hash_key(options_.seed, generation_);
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        const VolumeData& volume = scene.volumes[v];
        // The plan's bounds are the first generation's (its options); later ones draw anew.
        const std::vector<float> bound = plan && generation_ == 0
                                             ? plan->bounds[v]
                                             : cell_bounds(volume, view, options.sampling);
        const Generator gen{volume, v, view, options, bound};
        const std::size_t cells = volume.mesh->num_real_tets();
        const std::size_t chunks = (cells + kCellsPerChunk - 1) / kCellsPerChunk;
        for (int r = 0; r < options.repetitions; ++r) {
            // Fixed chunks, appended in order: the same particles in the same order whatever
            // the thread count.
            std::vector<std::vector<Kept>> parts(chunks);
            parallel_for(0, chunks, 1, [&](std::size_t chunk) {
                std::size_t counts[2] = {0, 0};
                const std::size_t end = std::min(cells, (chunk + 1) * kCellsPerChunk);
                for (std::size_t t = chunk * kCellsPerChunk; t < end; ++t) {
                    if (only && !(*only)[v][t]) continue;
                    gen.generate(static_cast<CellId>(t), r, counts, [&](const Vec3& x, double s) {
                        parts[chunk].push_back({static_cast<float>(x.x), static_cast<float>(x.y),
                                                static_cast<float>(x.z), static_cast<float>(s),
                                                static_cast<float>(volume.tf->extinction(s)),
                                                static_cast<std::uint32_t>(t),
                                                static_cast<std::uint32_t>(v)});
                    });
                }
            });
            std::vector<Kept>& kept = repetitions_[static_cast<std::size_t>(r)];
            for (const std::vector<Kept>& part : parts)
                kept.insert(kept.end(), part.begin(), part.end());
        }
    }
}

bool ObjectParticleSet::reusable_for(const CameraFrame& camera) const {
    if (!frame_) return false;
    const CameraFrame& f = *frame_;
    if (camera.width() != f.width() || camera.height() != f.height()) return false;
    const bool same_view = camera.eye() == f.eye() && camera.forward() == f.forward() &&
                           camera.up() == f.up() && camera.orthographic() == f.orthographic();
    if (same_view) return true;
    if (!camera.orthographic() || !f.orthographic()) return false;
    // The same sub-pixel size: the distance between neighbouring pixel rays.
    auto pixel_size = [](const CameraFrame& c) {
        return glm::length(c.ray(0.5, 1.5).origin - c.ray(0.5, 0.5).origin);
    };
    return std::abs(pixel_size(camera) - pixel_size(f)) <= 1e-12 * pixel_size(f);
}

Image ObjectParticleSet::render(const VolumeScene& scene, ObjectPbvrStats* stats) const {
    const CameraFrame& camera = *scene.camera;
    const int w = camera.width(), h = camera.height();
    const DensityView view = make_view(camera, options_.subpixel_level, scene_size(scene));
    ParticleBuffer buffer(view, scene);
    std::vector<double> sum(static_cast<std::size_t>(w) * h * 3, 0.0);
    std::atomic<std::size_t> drawn{0};
    const auto start = Clock::now();
    for (std::size_t r = 0; r < repetitions_.size(); ++r) {
        const std::vector<Kept>& kept = repetitions_[r];
        buffer.clear();
        parallel_for_chunks(0, kept.size(), 1 << 14, [&](std::size_t b, std::size_t e) {
            std::size_t reached = 0;
            for (std::size_t i = b; i < e; ++i) {
                const Kept& p = kept[i];
                const TransferFunction& tf = *scene.volumes[p.volume].tf;
                const double kappa = tf.extinction(p.scalar);
                if (!(kappa > 0) || !(p.kappa0 > 0)) continue;
                double f = kappa / p.kappa0;
                if (std::abs(f - 1) < 1e-6) f = 1;  // the function it was made for (kappa0 float)
                if (f < 1) {
                    // Kept with probability f: a number of the particle's own (its position).
                    std::uint32_t bits[3];
                    __builtin_memcpy(bits, &p.x, sizeof(bits));
                    if (uniform01(hash_key(bits[0], bits[1], bits[2], r)) >= f) continue;
                }
                const Vec3 x(p.x, p.y, p.z);
                reached += buffer.deposit(x, tf.color(p.scalar), std::max(f, 1.0));
            }
            drawn += reached;
        });
        buffer.resolve_into(sum);
    }
    const double repetitions = static_cast<double>(std::max<std::size_t>(repetitions_.size(), 1));
    Image image(w, h);
    for (std::size_t p = 0; p < image.pixels.size(); ++p) {
        image.pixels[p] = Vec3f(static_cast<float>(sum[3 * p] / repetitions),
                                static_cast<float>(sum[3 * p + 1] / repetitions),
                                static_cast<float>(sum[3 * p + 2] / repetitions));
    }
    if (stats) {
        stats->particles = size();
        stats->projected = drawn.load();
        stats->generate_ms = 0;
        stats->resolve_ms = ms_since(start);
    }
    return image;
}

std::size_t ObjectParticleSet::retarget(const VolumeScene& scene) {
    std::vector<std::vector<char>> redo(scene.volumes.size());
    std::size_t cells_redone = 0;
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        const VolumeData& volume = scene.volumes[v];
        const TransferFunction& now = *volume.tf;
        redo[v].assign(volume.mesh->num_real_tets(), 0);
        parallel_for(0, redo[v].size(), 1024, [&](std::size_t t) {
            const TransferFunction& then = functions_[v][cell_function_[v][t]];
            const Tet& tet = volume.mesh->tet(static_cast<CellId>(t));
            double lo = volume.scalar[tet[0]], hi = lo;
            for (PointId p : tet) {
                lo = std::min<double>(lo, volume.scalar[p]);
                hi = std::max<double>(hi, volume.scalar[p]);
            }
            // The scalars where the ratio of extinctions is checked: the ends, every control
            // point of either function between them, and the midpoints.
            std::vector<double> at = {lo, hi};
            for (const TransferFunction* tf : {&now, &then}) {
                for (const OpacityPoint& p : tf->opacity_points()) {
                    if (p.s > lo && p.s < hi) at.push_back(p.s);
                }
            }
            std::sort(at.begin(), at.end());
            const std::size_t n = at.size();
            for (std::size_t i = 0; i + 1 < n; ++i) at.push_back(0.5 * (at[i] + at[i + 1]));
            for (double s : at) {
                const double k_now = now.extinction(s), k_then = then.extinction(s);
                if (k_now > 0 && !(k_then > 0 && k_now <= kMaxGrowth * k_then)) {
                    redo[v][t] = 1;
                    return;
                }
            }
        });
        // The regenerated cells now follow `now`.
        functions_[v].push_back(now);
        const auto index = static_cast<std::uint16_t>(functions_[v].size() - 1);
        for (std::size_t t = 0; t < redo[v].size(); ++t) {
            if (!redo[v][t]) continue;
            cell_function_[v][t] = index;
            ++cells_redone;
        }
    }
    if (cells_redone == 0) return 0;
    for (std::vector<Kept>& kept : repetitions_) {
        std::erase_if(kept, [&](const Kept& p) { return redo[p.volume][p.cell] != 0; });
    }
    ++generation_;
    generate_cells(scene, &redo);
    return cells_redone;
}

std::size_t ObjectParticleSet::size() const {
    std::size_t n = 0;
    for (const std::vector<Kept>& kept : repetitions_) n += kept.size();
    return n;
}

}  // namespace tr
