#include <flowvol/flow_volume.h>
#include <mesh/point_data.h>
#include <mesh/tetrahedralize.h>

#include <cmath>
#include <string>

namespace tr {

Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const Field& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options, const ProgressFn& progress) {
    if (velocity.num_components != 3 || velocity.num_tuples() != domain.num_points()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "velocity '" + velocity.name + "' must have 3 components per point");
    }
    if (seed.resolution < 1 || seed.resolution > 4096 || !(seed.width > 0) || !(seed.height > 0) ||
        options.steps < 1 || !(options.dt > 0) ||
        !std::isfinite(seed.width * seed.height * options.dt)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "seed sizes, resolution (1..4096), steps and dt must be positive");
    }
    const ParticleTracer tracer(domain, adjacency, velocity);
    CellId hint = kNoCell;
    const auto at_centre = tracer.velocity_at(seed.center, hint);
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

    const int n = seed.resolution;
    const int side = n + 1;
    std::vector<Particle> front(static_cast<std::size_t>(side) * side);
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            Particle& p = front[j * side + i];
            p.position = seed.center + (static_cast<double>(i) / n - 0.5) * seed.width * u +
                         (static_cast<double>(j) / n - 0.5) * seed.height * v;
            CellId h = kNoCell;
            const auto where = tracer.locator().locate(p.position, h);
            p.active = where.has_value();
            if (where) p.tet = where->tet;
        }
    }

    // Layers as hexahedra over the seed grid, tetrahedralized together at the end.
    UnstructuredMesh layers;
    std::vector<double> age;
    std::vector<std::int64_t> column;  // seed quad of each cell
    FlowVolume result;
    std::vector<std::size_t> cells_after_layer;
    auto add_point = [&](const Vec3& p) {
        layers.points.push_back(p);
        return static_cast<std::int64_t>(layers.points.size() - 1);
    };
    std::vector<std::int64_t> previous_ids(front.size());
    for (std::size_t k = 0; k < front.size(); ++k) previous_ids[k] = add_point(front[k].position);
    std::vector<std::uint8_t> alive(front.size());
    for (std::size_t k = 0; k < front.size(); ++k) alive[k] = front[k].active;
    for (int step = 0; step < options.steps; ++step) {
        std::vector<std::uint8_t> was_alive = alive;
        for (std::size_t k = 0; k < front.size(); ++k) {
            if (!front[k].active) continue;
            const StepResult r = tracer.step(front[k], options.dt);
            if (r != StepResult::kMoved) {
                ++result.particles_stopped;
                // A particle cut at the boundary still closes this layer; stalled or invalid
                // ones do not move.
                if (r != StepResult::kLeftDomain) alive[k] = 0;
            }
        }
        std::vector<std::int64_t> ids(front.size());
        for (std::size_t k = 0; k < front.size(); ++k) ids[k] = add_point(front[k].position);
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const std::size_t c[4] = {static_cast<std::size_t>(j * side + i),
                                          static_cast<std::size_t>(j * side + i + 1),
                                          static_cast<std::size_t>((j + 1) * side + i + 1),
                                          static_cast<std::size_t>((j + 1) * side + i)};
                bool ok = true;
                for (std::size_t q : c) ok = ok && was_alive[q] && alive[q];
                if (!ok) continue;
                layers.add_cell(CellType::kHexahedron,
                                {previous_ids[c[0]], previous_ids[c[1]], previous_ids[c[2]],
                                 previous_ids[c[3]], ids[c[0]], ids[c[1]], ids[c[2]], ids[c[3]]});
                age.push_back((step + 0.5) * options.dt);
                column.push_back(j * n + i);
            }
        }
        // Particles that left the domain this step are done after closing their layer.
        for (std::size_t k = 0; k < front.size(); ++k) {
            if (!front[k].active) alive[k] = 0;
        }
        previous_ids = ids;
        cells_after_layer.push_back(layers.num_cells());
        report_progress(progress, "growing", static_cast<double>(step + 1) / options.steps);
    }
    if (layers.num_cells() == 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the dye polygon does not lie in the flow (no layer could grow)");
    }
    layers.cell_fields.push_back(make_double_field("age", 1, age));
    TetrahedralizeOptions tet_options;
    tet_options.merge_points = false;  // fronts share their points already
    TR_TRY(result.mesh, tetrahedralize(layers, tet_options));

    // Concentration: 1, or (compressible) the column's first cell volume over each cell's.
    std::vector<double> cell_volume(layers.num_cells(), 0.0);
    for (CellId t = 0; t < result.mesh.num_tets(); ++t) {
        cell_volume[result.mesh.source_cell(t)] += result.mesh.tet_volume(t);
    }
    std::vector<double> first_volume(static_cast<std::size_t>(n) * n, 0.0);
    for (std::size_t c = 0; c < layers.num_cells(); ++c) {
        if (first_volume[column[c]] == 0.0) first_volume[column[c]] = cell_volume[c];
    }
    std::vector<double> concentration(result.mesh.num_tets(), 1.0);
    if (options.compressible) {
        for (CellId t = 0; t < result.mesh.num_tets(); ++t) {
            const std::size_t c = result.mesh.source_cell(t);
            if (cell_volume[c] > 0) concentration[t] = first_volume[column[c]] / cell_volume[c];
        }
    }
    TR_TRY_STATUS(result.mesh.add_cell_field(make_double_field("concentration", 1, concentration)));
    const Field point_concentration =
        cell_to_point(result.mesh, *find_field(result.mesh.cell_fields(), "concentration"));
    TR_TRY_STATUS(result.mesh.add_point_field(point_concentration));
    // Tets per layer: cells after each layer, mapped through the split.
    std::size_t cursor = 0;
    for (std::size_t cells : cells_after_layer) {
        while (cursor < result.mesh.num_tets() && result.mesh.source_cell(cursor) < cells) {
            ++cursor;
        }
        result.layer_tets.push_back(cursor);
    }
    return result;
}

}  // namespace tr
