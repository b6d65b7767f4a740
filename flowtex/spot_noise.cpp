#include <core/check.h>
#include <core/parallel.h>
#include <flowtex/detail/spot_random.h>
#include <flowtex/spot_noise.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace tr {
namespace {

using detail::SpotRandom;

std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.6g", v);
    return buf;
}

constexpr int kSeedTries = 10000;

}  // namespace

Result<SpotNoise> SpotNoise::create(const TetMesh& mesh, const PointLocator& locator,
                                    const Field& scalar, const Flow& flow,
                                    const SpotNoiseOptions& options) {
    if (scalar.num_components != 1 || scalar.num_tuples() != mesh.num_points()) {
        return with_about(
            make_error(ErrorCode::kInvalidArgument,
                       "spot noise: '" + scalar.name + "' is not a scalar point array (it has " +
                           std::to_string(scalar.num_components) + " components)"),
            "scalar");
    }
    if (options.count == 0 || options.count > kMaxSpots) {
        return with_about(make_error(ErrorCode::kInvalidArgument,
                                     "spot noise: count must be 1 .. " + std::to_string(kMaxSpots) +
                                         ", not " + std::to_string(options.count)),
                          "count");
    }
    if (!(options.band > 0) || !std::isfinite(options.band) || !(options.dt > 0) ||
        !std::isfinite(options.dt) || options.lifetime_frames < 0) {
        return with_about(
            make_error(ErrorCode::kInvalidArgument,
                       "spot noise: band and dt must be positive and finite, lifetime >= 0"),
            "band");
    }
    const auto [lo, hi] = field_range(scalar, 0);
    if (!std::isfinite(options.iso) || !(options.iso >= lo && options.iso <= hi)) {
        return with_about(make_error(ErrorCode::kInvalidArgument,
                                     "spot noise: iso " + format_number(options.iso) +
                                         " is outside '" + scalar.name + "''s range [" +
                                         format_number(lo) + ", " + format_number(hi) + "]"),
                          "iso");
    }
    SpotNoise noise(mesh, locator, scalar, flow, options);
    if (const auto* mesh_flow = dynamic_cast<const MeshFlow*>(&flow);
        mesh_flow != nullptr && &mesh_flow->locator().mesh() == &mesh) {
        noise.shared_velocity_ = &mesh_flow->velocity();
    }
    const std::size_t num_tets = mesh.num_real_tets();
    noise.gradient_norm_.assign(mesh.num_tets(), 0.0);
    std::vector<std::uint8_t> in_band(num_tets, 0);
    parallel_for(0, num_tets, 4096, [&](std::size_t t) {
        const Tet& tet = mesh.tet(static_cast<CellId>(t));
        const Vec3 p0 = mesh.point(tet[0]);
        const glm::dmat3 edges(mesh.point(tet[1]) - p0, mesh.point(tet[2]) - p0,
                               mesh.point(tet[3]) - p0);
        const double s0 = scalar.get(tet[0]);
        const Vec3 ds(scalar.get(tet[1]) - s0, scalar.get(tet[2]) - s0, scalar.get(tet[3]) - s0);
        // s(p) = s0 + g . (p - p0): edges^T g = ds.
        const Vec3 g = glm::inverse(glm::transpose(edges)) * ds;
        const double norm = glm::length(g);
        if (!(norm > 0) || !std::isfinite(norm)) return;
        noise.gradient_norm_[t] = norm;
        double smin = s0, smax = s0;
        for (int k = 1; k < 4; ++k) {
            smin = std::min(smin, scalar.get(tet[k]));
            smax = std::max(smax, scalar.get(tet[k]));
        }
        const double reach = options.band * norm;
        in_band[t] = smin < options.iso + reach && smax > options.iso - reach;
    });
    double total = 0;
    for (std::size_t t = 0; t < num_tets; ++t) {
        if (!in_band[t]) continue;
        noise.band_tets_.push_back(static_cast<CellId>(t));
        total += mesh.tet_volume(static_cast<CellId>(t));
        noise.band_cdf_.push_back(total);
    }
    if (noise.band_tets_.empty() || !(total > 0)) {
        return with_about(make_error(ErrorCode::kInvalidArgument,
                                     "spot noise: no tet of the mesh meets the band " +
                                         format_number(options.band) + " around '" + scalar.name +
                                         "' = " + format_number(options.iso)),
                          "band");
    }
    for (double& c : noise.band_cdf_) c /= total;

    const std::size_t n = options.count;
    noise.positions_.resize(n);
    noise.velocities_.resize(n);
    noise.hints_.assign(n, kNoCell);
    noise.flow_hints_.assign(n, kNoCell);
    noise.generations_.assign(n, 0);
    noise.ages_.resize(n);
    noise.flags_.assign(n, 1);
    noise.cells_.assign(n, 0);
    const double t0 = options.start_time;
    parallel_for(0, n, 1024, [&](std::size_t i) {
        noise.flags_[i] = noise.seed_spot(i, t0);
        // Staggered ages: about count / lifetime spots reach the lifetime each frame.
        noise.ages_[i] =
            options.lifetime_frames > 0 ? static_cast<int>(i * 7919 % options.lifetime_frames) : 0;
    });
    if (std::find(noise.flags_.begin(), noise.flags_.end(), 0) != noise.flags_.end()) {
        return with_about(make_error(ErrorCode::kInvalidArgument,
                                     "spot noise: the flow is not defined in the band around '" +
                                         scalar.name + "' = " + format_number(options.iso)),
                          "band");
    }
    noise.build_grid();
    return noise;
}

std::optional<double> SpotNoise::distance_to_surface(const Vec3& p, CellId& hint) const {
    const auto location = locator_->locate(p, hint);
    if (!location) return std::nullopt;
    hint = location->tet;
    return distance_at(*location);
}

double SpotNoise::distance_at(const Location& location) const {
    const Tet& tet = mesh_->tet(location.tet);
    double s = 0;
    for (int k = 0; k < 4; ++k) s += location.barycentric[k] * scalar_->get(tet[k]);
    const double g = gradient_norm_[location.tet];
    const double diff = std::abs(s - options_.iso);
    if (!(g > 0)) return diff == 0 ? 0.0 : std::numeric_limits<double>::infinity();
    return diff / g;
}

SpotNoise::BandSample SpotNoise::sample_band_tet(SpotRandom& random, CellId cell) const {
    if (cell == kNoCell) {
        const double u = random.uniform();
        const std::size_t k = static_cast<std::size_t>(
            std::lower_bound(band_cdf_.begin(), band_cdf_.end(), u) - band_cdf_.begin());
        cell = band_tets_[std::min(k, band_tets_.size() - 1)];
    }
    // Uniform in the tet: barycentric weights from Dirichlet(1, 1, 1, 1).
    std::array<double, 4> b;
    double sum = 0;
    for (double& w : b) {
        w = -std::log(random.uniform());
        sum += w;
    }
    const Tet& tet = mesh_->tet(cell);
    BandSample out;
    out.tet = cell;
    double s = 0;
    for (int c = 0; c < 4; ++c) {
        out.point += (b[c] / sum) * mesh_->point(tet[c]);
        s += (b[c] / sum) * scalar_->get(tet[c]);
    }
    out.in_band = std::abs(s - options_.iso) < options_.band * gradient_norm_[cell];
    return out;
}

bool SpotNoise::seed_spot(std::size_t i, double t, int grid_cell) {
    SpotRandom random(options_.seed, i, generations_[i]);
    for (int attempt = 0; attempt < kSeedTries; ++attempt) {
        CellId cell = kNoCell;
        if (grid_cell >= 0 && box_sampling_[grid_cell]) {
            // A uniform point of the cube, located from one of its tets.
            const int gx = grid_cell % grid_n_, gy = grid_cell / grid_n_ % grid_n_,
                      gz = grid_cell / grid_n_ / grid_n_;
            const Vec3 p =
                grid_lo_ + cell_size_ * Vec3(gx + random.uniform(), gy + random.uniform(),
                                             gz + random.uniform());
            CellId hint = cell_tets_[cell_start_[grid_cell]];
            const auto d = distance_to_surface(p, hint);
            if (!d || !(*d < options_.band)) continue;
            CellId flow_hint = hint;
            const auto v = flow_->at(p, t, flow_hint);
            if (!v) continue;
            positions_[i] = p;
            velocities_[i] = *v;
            hints_[i] = hint;
            flow_hints_[i] = flow_hint;
            return true;
        }
        if (grid_cell >= 0) {
            const double u = random.uniform();
            const auto b = cell_cdf_.begin() + cell_start_[grid_cell];
            const auto e = cell_cdf_.begin() + cell_start_[grid_cell + 1];
            const std::size_t k = static_cast<std::size_t>(std::lower_bound(b, e, u) - b);
            cell = cell_tets_[cell_start_[grid_cell] +
                              std::min<std::size_t>(k, static_cast<std::size_t>(e - b) - 1)];
        }
        const BandSample sample = sample_band_tet(random, cell);
        if (!sample.in_band) continue;
        const Vec3 p = sample.point;
        if (grid_cell >= 0 && cell_of(p) != grid_cell) continue;
        const CellId hint = sample.tet;
        CellId flow_hint = hint;
        const auto v = flow_->at(p, t, flow_hint);
        if (!v) continue;
        positions_[i] = p;
        velocities_[i] = *v;
        hints_[i] = hint;
        flow_hints_[i] = flow_hint;
        return true;
    }
    return false;
}

double SpotNoise::mean_speed() const {
    double sum = 0;
    for (const Vec3& v : velocities_) sum += glm::length(v);
    return velocities_.empty() ? 0.0 : sum / velocities_.size();
}

void SpotNoise::retime(double dt, int lifetime_frames) {
    TR_CHECK(dt > 0 && lifetime_frames >= 0);
    options_.dt = dt;
    options_.lifetime_frames = lifetime_frames;
    for (std::size_t i = 0; i < ages_.size(); ++i) {
        ages_[i] = lifetime_frames > 0 ? static_cast<int>(i * 7919 % lifetime_frames) : 0;
    }
}

void SpotNoise::advance() {
    const double t0 = time(), dt = options_.dt;
    const int lifetime = options_.lifetime_frames;
    parallel_for(0, positions_.size(), 512, [&](std::size_t i) {
        flags_[i] = 0;
        if (lifetime > 0 && ++ages_[i] >= lifetime) {
            flags_[i] = 1;
            return;
        }
        CellId flow_hint = flow_hints_[i];
        // velocities_[i] is v(positions_[i], t0): the last step's (or the seeding's) lookup.
        const auto next = rk4_step_from(*flow_, positions_[i], velocities_[i], t0, dt, Vec3(0.0),
                                        flow_hint, false);
        std::optional<Vec3> v;
        std::optional<double> d;
        CellId hint = hints_[i];
        if (next && shared_velocity_ != nullptr) {
            // One location gives the end point's velocity and its distance to the surface (the
            // same location the flow's lookup and the band test each found before).
            if (const auto location = locator_->locate(*next, flow_hint)) {
                flow_hint = hint = location->tet;
                v = shared_velocity_->at(*location, t0 + dt);
                d = distance_at(*location);
            }
        } else if (next) {
            v = flow_->at(*next, t0 + dt, flow_hint);
            if (v) d = distance_to_surface(*next, hint);
        }
        if (d && *d < options_.band) {
            positions_[i] = *next;
            velocities_[i] = *v;
            hints_[i] = hint;
            flow_hints_[i] = flow_hint;
            cells_[i] = cell_of(*next);  // here, in parallel, for the deficits below
        } else {
            flags_[i] = 1;
        }
    });
    // The cubes' deficits, and the spots to reseed shared among them in proportion.
    std::vector<double> deficit = target_;
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < positions_.size(); ++i) {
        if (flags_[i]) {
            out.push_back(static_cast<std::uint32_t>(i));
        } else {
            deficit[static_cast<std::size_t>(cells_[i])] -= 1.0;
        }
    }
    // Water-filling: the level L >= 0 with sum max(d - L, 0) = reseeds (bisection); each
    // cube gets floor(max(d - L, 0)), the rest spread evenly over the cubes with d > L.
    reseed_cells_.assign(out.size(), -1);
    const double r = static_cast<double>(out.size());
    // Only cubes with a target can have a deficit above 0 (the others' is 0 less their spots):
    // the sums and the eligible cubes run over those, in cube order, as over all.
    auto above = [&](double level) {
        double sum = 0;
        for (const std::uint32_t c : target_cells_) sum += std::max(deficit[c] - level, 0.0);
        return sum;
    };
    double lo = 0, hi = 1;
    for (const std::uint32_t c : target_cells_) hi = std::max(hi, deficit[c]);
    if (above(0) > r) {
        for (int iteration = 0; iteration < 40; ++iteration) {
            const double mid = 0.5 * (lo + hi);
            (above(mid) > r ? lo : hi) = mid;
        }
    }
    const double level = hi > 1 && above(0) > r ? hi : 0.0;
    std::size_t j = 0;
    std::vector<int> eligible;
    for (const std::uint32_t c : target_cells_) {
        if (!(deficit[c] > level)) continue;
        eligible.push_back(static_cast<int>(c));
        const auto n = static_cast<std::size_t>(deficit[c] - level);
        for (std::size_t k = 0; k < n && j < out.size(); ++k) {
            reseed_cells_[j++] = static_cast<int>(c);
        }
    }
    if (j < out.size() && !eligible.empty()) {
        SpotRandom random(options_.seed, ~std::uint64_t{0}, static_cast<std::uint64_t>(frame_));
        const std::size_t rest = out.size() - j;
        const double stride = static_cast<double>(eligible.size()) / static_cast<double>(rest);
        const double offset = random.uniform() * stride;
        for (std::size_t k = 0; k < rest; ++k) {
            const auto e = static_cast<std::size_t>(offset + stride * static_cast<double>(k));
            reseed_cells_[j++] = eligible[std::min(e, eligible.size() - 1)];
        }
    }
    parallel_for(0, out.size(), 64, [&](std::size_t j) {
        const std::size_t i = out[j];
        ++generations_[i];
        ages_[i] = 0;
        // A cube whose band is too thin for the tries: anywhere in the band. Should no try
        // succeed at all (the band's flow vanished in an unsteady field), the spot stays.
        if (!seed_spot(i, t0 + dt, reseed_cells_[j])) seed_spot(i, t0 + dt);
    });
    reseeded_ = out.size();
    ++frame_;
}

int SpotNoise::cell_of(const Vec3& p) const {
    auto axis = [&](double v, double lo) {
        return std::clamp(static_cast<int>(std::floor((v - lo) / cell_size_)), 0, grid_n_ - 1);
    };
    return (axis(p.z, grid_lo_.z) * grid_n_ + axis(p.y, grid_lo_.y)) * grid_n_ +
           axis(p.x, grid_lo_.x);
}

void SpotNoise::build_grid() {
    auto tet_box = [&](CellId t) {
        Bounds3 box{Vec3(1e300), Vec3(-1e300)};
        for (const PointId v : mesh_->tet(t)) {
            box.lo = glm::min(box.lo, mesh_->point(v));
            box.hi = glm::max(box.hi, mesh_->point(v));
        }
        return box;
    };
    Bounds3 box{Vec3(1e300), Vec3(-1e300)};
    for (const CellId t : band_tets_) {
        const Bounds3 b = tet_box(t);
        box.lo = glm::min(box.lo, b.lo);
        box.hi = glm::max(box.hi, b.hi);
    }
    // About 64 spots a cube, the band taken as a surface across n^2 cubes.
    grid_n_ = std::clamp(
        static_cast<int>(std::lround(std::sqrt(static_cast<double>(positions_.size()) / 64.0))), 1,
        64);
    const Vec3 size = box.hi - box.lo;
    cell_size_ = std::max({size.x, size.y, size.z}) / grid_n_ * (1 + 1e-9);
    if (!(cell_size_ > 0)) cell_size_ = 1;
    grid_lo_ = box.lo;
    const std::size_t cells = static_cast<std::size_t>(grid_n_) * grid_n_ * grid_n_;
    std::vector<std::vector<CellId>> lists(cells);
    for (const CellId t : band_tets_) {
        const Bounds3 b = tet_box(t);
        const int lo = cell_of(b.lo), hi = cell_of(b.hi);
        const int ax = lo % grid_n_, ay = lo / grid_n_ % grid_n_, az = lo / grid_n_ / grid_n_;
        const int bx = hi % grid_n_, by = hi / grid_n_ % grid_n_, bz = hi / grid_n_ / grid_n_;
        for (int z = az; z <= bz; ++z) {
            for (int y = ay; y <= by; ++y) {
                for (int x = ax; x <= bx; ++x) {
                    lists[(static_cast<std::size_t>(z) * grid_n_ + y) * grid_n_ + x].push_back(t);
                }
            }
        }
    }
    cell_start_.assign(cells + 1, 0);
    box_sampling_.assign(cells, 0);
    cell_tets_.clear();
    cell_cdf_.clear();
    for (std::size_t c = 0; c < cells; ++c) {
        double sum = 0;
        const std::size_t first = cell_cdf_.size();
        for (const CellId t : lists[c]) {
            cell_tets_.push_back(t);
            sum += mesh_->tet_volume(t);
            cell_cdf_.push_back(sum);
        }
        for (std::size_t k = first; k < cell_cdf_.size(); ++k) cell_cdf_[k] /= sum;
        // Points drawn from the cube itself when its tets are much bigger than it (a try
        // locates the point, about twice a tet draw's cost).
        box_sampling_[c] = sum > 2 * cell_size_ * cell_size_ * cell_size_;
        cell_start_[c + 1] = static_cast<std::uint32_t>(cell_tets_.size());
    }
    // The band's volume per cube, by uniform samples in chunks of their own generators
    // (summed in chunk order: the same for any thread count).
    const std::size_t samples = std::clamp<std::size_t>(16 * positions_.size(), 1 << 18, 1 << 22);
    // 16 chunks whatever the count: their hit counts take 16 x cubes x 4 bytes.
    constexpr std::size_t chunks = 16;
    const std::size_t chunk_samples = samples / chunks;
    std::vector<std::vector<std::uint32_t>> hits(chunks);
    parallel_for(0, chunks, 1, [&](std::size_t k) {
        SpotRandom random(options_.seed ^ 0x7a11, k, ~std::uint64_t{0});
        std::vector<std::uint32_t>& h = hits[k];
        h.assign(cells, 0);
        for (std::size_t s = 0; s < chunk_samples; ++s) {
            const auto sample = sample_band_tet(random);
            if (sample.in_band) ++h[cell_of(sample.point)];
        }
    });
    std::vector<double> volume(cells, 0.0);
    double total = 0;
    for (const auto& h : hits) {
        for (std::size_t c = 0; c < cells; ++c) volume[c] += h[c];
    }
    for (const double v : volume) total += v;
    target_.assign(cells, 0.0);
    if (total > 0) {
        for (std::size_t c = 0; c < cells; ++c) {
            target_[c] = volume[c] / total * static_cast<double>(positions_.size());
        }
    }
    target_cells_.clear();
    for (std::size_t c = 0; c < cells; ++c) {
        if (target_[c] > 0) target_cells_.push_back(static_cast<std::uint32_t>(c));
    }
}

}  // namespace tr
