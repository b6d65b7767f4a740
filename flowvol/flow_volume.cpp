#include <core/parallel.h>
#include <flowvol/flow_volume.h>
#include <mesh/point_data.h>
#include <mesh/tetrahedralize.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <queue>
#include <string>
#include <unordered_map>

namespace tr {
namespace {

using glm::dvec2;

struct FrontParticle {
    Particle particle;
    dvec2 uv{0.0};            // where on the seed polygon it started, in [0, 1]^2
    std::int64_t point = -1;  // its point in the layer mesh on the current front
};

struct FrontTriangle {
    std::array<std::uint32_t, 3> v{};  // counter-clockwise seen along the polygon's normal
    // The first layer cell of its lineage and that cell's seed area (compressible flow).
    std::int64_t origin_cell = -1;
    double origin_area = 0;
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t{a} << 32) | b;
}

class FlowVolumeGrower {
  public:
    FlowVolumeGrower(const TetMesh& domain, const FaceAdjacency& adjacency,
                     const VelocityField& velocity, const FlowVolumeOptions& options)
        : tracer_(domain, adjacency, velocity), options_(options) {}

    const ParticleTracer& tracer() const { return tracer_; }

    // Lays the seed grid on the polygon spanned by axes u, v about the seed's centre.
    void seed(const DyeSeed& seed, const Vec3& u, const Vec3& v, double start_time) {
        seed_ = seed;
        u_ = u;
        v_ = v;
        t0_ = start_time;
        const int n = seed.resolution;
        const auto index = [n](int i, int j) {
            return static_cast<std::uint32_t>(j * (n + 1) + i);
        };
        for (int j = 0; j <= n; ++j) {
            for (int i = 0; i <= n; ++i) {
                FrontParticle p;
                p.uv = dvec2(static_cast<double>(i) / n, static_cast<double>(j) / n);
                p.particle.position = seed_point(p.uv);
                CellId hint = kNoCell;
                const auto where = tracer_.locator().locate(p.particle.position, hint);
                p.particle.active = where.has_value();
                if (where) p.particle.tet = where->tet;
                p.point = add_point(p.particle.position);
                particles_.push_back(p);
            }
        }
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                triangles_.push_back({{index(i, j), index(i + 1, j), index(i + 1, j + 1)}});
                triangles_.push_back({{index(i, j), index(i + 1, j + 1), index(i, j + 1)}});
            }
        }
        drop_dead_triangles();
    }

    // Grows one layer: advect, split stretched edges, add the prisms.
    void grow_layer(int step) {
        advance(step);
        if (options_.split_threshold > 0) subdivide(step);
        add_prisms(step);
        drop_dead_triangles();
        cells_after_layer_.push_back(layers_.num_cells());
    }

    Result<FlowVolume> finish();

  private:
    Vec3 seed_point(const dvec2& uv) const {
        return seed_.center + (uv.x - 0.5) * seed_.width * u_ + (uv.y - 0.5) * seed_.height * v_;
    }
    double time_of(int step) const { return t0_ + step * options_.dt; }

    std::int64_t add_point(const Vec3& p) {
        layers_.points.push_back(p);
        return static_cast<std::int64_t>(layers_.points.size() - 1);
    }

    double seed_area(const FrontTriangle& t) const {
        const dvec2 a = particles_[t.v[1]].uv - particles_[t.v[0]].uv;
        const dvec2 b = particles_[t.v[2]].uv - particles_[t.v[0]].uv;
        return 0.5 * std::abs(a.x * b.y - a.y * b.x);
    }

    bool growing(const FrontTriangle& t) const {
        return advanced_[t.v[0]] && advanced_[t.v[1]] && advanced_[t.v[2]];
    }

    // RK4 for every moving particle from time_of(step) to time_of(step + 1).
    void advance(int step) {
        const std::size_t n = particles_.size();
        std::vector<std::uint8_t> was_active(n);
        for (std::size_t k = 0; k < n; ++k) was_active[k] = particles_[k].particle.active;
        std::vector<StepResult> results(n, StepResult::kLeftDomain);
        parallel_for(0, n, 256, [&](std::size_t k) {
            if (was_active[k]) {
                results[k] = tracer_.step(particles_[k].particle, time_of(step), options_.dt);
            }
        });
        previous_point_.assign(n, -1);
        advanced_.assign(n, 0);
        for (std::size_t k = 0; k < n; ++k) {
            if (!was_active[k]) continue;
            FrontParticle& p = particles_[k];
            previous_point_[k] = p.point;
            // A particle cut at the boundary still closes this layer; stalled or invalid ones
            // do not move.
            if (results[k] == StepResult::kMoved || results[k] == StepResult::kLeftDomain) {
                advanced_[k] = 1;
                p.point = add_point(p.particle.position);
            }
            if (results[k] != StepResult::kMoved) ++particles_stopped_;
        }
    }

    // A particle traced from the seed polygon at uv to time_of(steps), or nothing when it
    // starts outside the domain or stops on the way.
    std::optional<Particle> trace_from_seed(const dvec2& uv, int steps) const {
        Particle p;
        p.position = seed_point(uv);
        CellId hint = kNoCell;
        const auto where = tracer_.locator().locate(p.position, hint);
        if (!where) return std::nullopt;
        p.tet = where->tet;
        for (int s = 0; s < steps; ++s) {
            if (tracer_.step(p, time_of(s), options_.dt) != StepResult::kMoved) return std::nullopt;
        }
        return p;
    }

    // Splits growing triangles' edges longer than the threshold, longest first, until none is
    // left or none can be split. Edges at a particle that just stopped are left alone: their
    // triangles end with this layer.
    void subdivide(int step) {
        const double limit = options_.split_threshold * seed_.spacing();
        // A triangle is halved only while its halves keep at least the seed area of a seed
        // triangle refined max_refinement times along each side: a bound on the particles.
        const double finest = static_cast<double>(seed_.resolution) * options_.max_refinement;
        const double smallest_half = 0.5 / (finest * finest);
        edges_.clear();
        std::priority_queue<std::pair<double, std::uint64_t>> long_edges;
        const auto consider = [&](std::uint32_t a, std::uint32_t b) {
            if (!particles_[a].particle.active || !particles_[b].particle.active) return;
            const double length =
                glm::distance(particles_[a].particle.position, particles_[b].particle.position);
            if (length > limit) long_edges.push({length, edge_key(a, b)});
        };
        for (std::size_t t = 0; t < triangles_.size(); ++t) {
            if (!growing(triangles_[t])) continue;
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = triangles_[t].v[e], b = triangles_[t].v[(e + 1) % 3];
                if (attach(edge_key(a, b), t)) consider(a, b);
            }
        }
        while (!long_edges.empty()) {
            const std::uint64_t key = long_edges.top().second;
            long_edges.pop();
            const auto found = edges_.find(key);
            if (found == edges_.end()) continue;  // split already
            const std::array<std::int64_t, 2> tris = found->second;
            const auto a = static_cast<std::uint32_t>(key >> 32);
            const auto b = static_cast<std::uint32_t>(key & 0xffffffffu);
            const dvec2 uv = 0.5 * (particles_[a].uv + particles_[b].uv);
            bool fine_enough = false;
            for (std::int64_t t : tris) {
                fine_enough = fine_enough || (t >= 0 && 0.5 * seed_area(triangles_[t]) <
                                                            smallest_half * (1 - 1e-9));
            }
            std::optional<Particle> traced;
            if (particles_.size() < options_.max_particles && !fine_enough) {
                traced = trace_from_seed(uv, step + 1);
            }
            if (!traced) {
                ++unresolved_edges_;
                continue;
            }
            FrontParticle m;
            m.particle = *traced;
            m.uv = uv;
            m.point = add_point(traced->position);
            const Vec3 below =
                0.5 * (layers_.points[previous_point_[a]] + layers_.points[previous_point_[b]]);
            previous_point_.push_back(add_point(below));
            advanced_.push_back(1);
            particles_.push_back(m);
            ++particles_inserted_;
            const auto middle = static_cast<std::uint32_t>(particles_.size() - 1);
            edges_.erase(key);
            for (std::int64_t t : tris) {
                if (t < 0) continue;
                const std::uint32_t apex = halve(static_cast<std::size_t>(t), a, b, middle);
                consider(middle, apex);
            }
            consider(a, middle);
            consider(middle, b);
        }
    }

    // Records that triangle t has edge `key`; true when the edge is new.
    bool attach(std::uint64_t key, std::size_t t) {
        auto [it, inserted] = edges_.try_emplace(key, std::array<std::int64_t, 2>{-1, -1});
        it->second[inserted ? 0 : 1] = static_cast<std::int64_t>(t);
        return inserted;
    }

    void reattach(std::uint64_t key, std::size_t from, std::size_t to) {
        for (std::int64_t& t : edges_.at(key)) {
            if (t == static_cast<std::int64_t>(from)) t = static_cast<std::int64_t>(to);
        }
    }

    // Replaces triangle t, which has edge {a, b}, by its two halves through `middle`, keeping
    // the edge map current. Returns the apex (the vertex opposite the edge).
    std::uint32_t halve(std::size_t t, std::uint32_t a, std::uint32_t b, std::uint32_t middle) {
        FrontTriangle& tri = triangles_[t];
        int e = 0;
        while (edge_key(tri.v[e], tri.v[(e + 1) % 3]) != edge_key(a, b)) ++e;
        const std::uint32_t first = tri.v[e], second = tri.v[(e + 1) % 3];
        const std::uint32_t apex = tri.v[(e + 2) % 3];
        FrontTriangle other = tri;
        tri.v = {first, middle, apex};
        other.v = {middle, second, apex};
        const std::size_t t2 = triangles_.size();
        triangles_.push_back(other);
        reattach(edge_key(second, apex), t, t2);
        attach(edge_key(first, middle), t);
        attach(edge_key(middle, second), t2);
        attach(edge_key(middle, apex), t);
        attach(edge_key(middle, apex), t2);
        return apex;
    }

    // One prism per growing triangle between its previous and its new front.
    void add_prisms(int step) {
        for (FrontTriangle& t : triangles_) {
            if (!growing(t)) continue;
            const auto [a, b, c] = t.v;
            // VTK wedge: face (0, 1, 2) faces away from (3, 4, 5).
            layers_.add_cell(CellType::kWedge,
                             {previous_point_[a], previous_point_[c], previous_point_[b],
                              particles_[a].point, particles_[c].point, particles_[b].point});
            const auto cell = static_cast<std::int64_t>(layers_.num_cells() - 1);
            const double area = seed_area(t);
            if (t.origin_cell < 0) {
                t.origin_cell = cell;
                t.origin_area = area;
            }
            age_.push_back((step + 0.5) * options_.dt);
            cell_origin_.push_back(t.origin_cell);
            cell_area_fraction_.push_back(t.origin_area > 0 ? area / t.origin_area : 1.0);
        }
    }

    void drop_dead_triangles() {
        std::erase_if(triangles_, [this](const FrontTriangle& t) {
            return !particles_[t.v[0]].particle.active || !particles_[t.v[1]].particle.active ||
                   !particles_[t.v[2]].particle.active;
        });
    }

    ParticleTracer tracer_;
    FlowVolumeOptions options_;
    DyeSeed seed_;
    Vec3 u_{1, 0, 0}, v_{0, 1, 0};
    double t0_ = 0;

    std::vector<FrontParticle> particles_;
    std::vector<FrontTriangle> triangles_;
    // This step: each particle's point on the previous front, and whether it moved.
    std::vector<std::int64_t> previous_point_;
    std::vector<std::uint8_t> advanced_;
    // Edges of the growing triangles during subdivision: the (one or two) triangles on each.
    std::unordered_map<std::uint64_t, std::array<std::int64_t, 2>> edges_;

    UnstructuredMesh layers_;
    std::vector<double> age_;
    std::vector<std::int64_t> cell_origin_;
    std::vector<double> cell_area_fraction_;
    std::vector<std::size_t> cells_after_layer_;
    std::size_t particles_stopped_ = 0;
    std::size_t particles_inserted_ = 0;
    std::size_t unresolved_edges_ = 0;
};

Result<FlowVolume> FlowVolumeGrower::finish() {
    if (layers_.num_cells() == 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the dye polygon does not lie in the flow (no layer could grow)");
    }
    FlowVolume result;
    result.particles_stopped = particles_stopped_;
    result.particles_inserted = particles_inserted_;
    result.unresolved_edges = unresolved_edges_;
    for (const FrontParticle& p : particles_) result.front.points.push_back(p.particle.position);
    for (const FrontTriangle& t : triangles_) result.front.triangles.push_back(t.v);

    layers_.cell_fields.push_back(make_double_field("age", 1, age_));
    TetrahedralizeOptions tet_options;
    tet_options.merge_points = false;  // fronts share their points already
    TR_TRY(result.mesh, tetrahedralize(layers_, tet_options));

    // Concentration: 1, or (compressible) the ancestor's volume share over the cell's volume.
    std::vector<double> cell_volume(layers_.num_cells(), 0.0);
    for (CellId t = 0; t < result.mesh.num_tets(); ++t) {
        cell_volume[result.mesh.source_cell(t)] += result.mesh.tet_volume(t);
    }
    std::vector<double> concentration(result.mesh.num_tets(), 1.0);
    if (options_.compressible) {
        for (CellId t = 0; t < result.mesh.num_tets(); ++t) {
            const std::size_t c = result.mesh.source_cell(t);
            const double origin = cell_volume[static_cast<std::size_t>(cell_origin_[c])];
            if (cell_volume[c] > 0) {
                concentration[t] = origin * cell_area_fraction_[c] / cell_volume[c];
            }
        }
    }
    TR_TRY_STATUS(result.mesh.add_cell_field(make_double_field("concentration", 1, concentration)));
    const Field point_concentration =
        cell_to_point(result.mesh, *find_field(result.mesh.cell_fields(), "concentration"));
    TR_TRY_STATUS(result.mesh.add_point_field(point_concentration));
    // Tets per layer: cells after each layer, mapped through the split.
    std::size_t cursor = 0;
    for (std::size_t cells : cells_after_layer_) {
        while (cursor < result.mesh.num_tets() && result.mesh.source_cell(cursor) < cells) {
            ++cursor;
        }
        result.layer_tets.push_back(cursor);
    }
    return result;
}

}  // namespace

Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const VelocityField& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options, const ProgressFn& progress) {
    if (seed.resolution < 1 || seed.resolution > 4096 || !(seed.width > 0) || !(seed.height > 0) ||
        options.steps < 1 || !(options.dt > 0) ||
        !std::isfinite(seed.width * seed.height * options.dt)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "seed sizes, resolution (1..4096), steps and dt must be positive");
    }
    if (!(options.split_threshold == 0 ||
          (options.split_threshold >= 1.5 && std::isfinite(options.split_threshold)))) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the split threshold must be 0 (off) or at least 1.5 seed spacings");
    }
    if (options.max_refinement < 1) {
        return make_error(ErrorCode::kInvalidArgument, "max_refinement must be at least 1");
    }
    const double unsplit_tets = 6.0 * seed.resolution * seed.resolution * options.steps;
    if (unsplit_tets > options.max_tets) {
        char text[240];
        std::snprintf(text, sizeof text,
                      "a seed resolution of %d and %d steps make %.3g tets before any split, "
                      "more than the %.3g allowed (about %.0f GB); lower --seed-res or --steps",
                      seed.resolution, options.steps, unsplit_tets, options.max_tets,
                      unsplit_tets * 60e-9);
        return make_error(ErrorCode::kInvalidArgument, text);
    }
    const double t0 = options.start_time.value_or(velocity.first_time());
    if (!std::isfinite(t0)) {
        return make_error(ErrorCode::kInvalidArgument, "the start time must be finite");
    }
    if (!velocity.is_steady()) {
        const double end = t0 + options.steps * options.dt;
        const double slack = 1e-9 * (velocity.last_time() - velocity.first_time());
        if (t0 < velocity.first_time() - slack || end > velocity.last_time() + slack) {
            return make_error(ErrorCode::kInvalidArgument,
                              "the flow volume runs from time " + std::to_string(t0) + " to " +
                                  std::to_string(end) + ", outside the velocity's times " +
                                  std::to_string(velocity.first_time()) + " .. " +
                                  std::to_string(velocity.last_time()));
        }
    }
    FlowVolumeGrower grower(domain, adjacency, velocity, options);
    CellId hint = kNoCell;
    const auto at_centre = grower.tracer().velocity_at(seed.center, t0, hint);
    if (!at_centre) {
        return make_error(ErrorCode::kInvalidArgument, "the seed's centre is outside the mesh");
    }
    Vec3 normal = seed.normal.value_or(*at_centre);
    if (!std::isfinite(glm::length(normal)) || glm::length(normal) == 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          "no flow direction at the seed's centre (zero or invalid velocity): "
                          "give the polygon's normal");
    }
    normal = glm::normalize(normal);
    const Vec3 other = std::abs(normal.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    const Vec3 u = glm::normalize(glm::cross(other, normal));
    const Vec3 v = glm::cross(normal, u);
    int grown = 0;
    try {
        grower.seed(seed, u, v, t0);
        for (int step = 0; step < options.steps; ++step) {
            grower.grow_layer(step);
            grown = step + 1;
            report_progress(progress, "growing", static_cast<double>(step + 1) / options.steps);
        }
        return grower.finish();
    } catch (const std::bad_alloc&) {
        // Refinement can still outgrow the memory the bound above allows for: say where.
        return make_error(ErrorCode::kInvalidArgument,
                          "out of memory growing the flow volume after " + std::to_string(grown) +
                              " of " + std::to_string(options.steps) +
                              " layers; lower --seed-res, --steps or raise --split-threshold");
    }
}

Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const Field& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options, const ProgressFn& progress) {
    TR_TRY(const VelocityField field, VelocityField::steady(domain, velocity));
    return grow_flow_volume(domain, adjacency, field, seed, options, progress);
}

}  // namespace tr
