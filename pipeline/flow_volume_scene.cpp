#include <pipeline/flow_volume_scene.h>

#include <cmath>
#include <exception>
#include <utility>

namespace tr {

std::vector<std::string> vector_arrays(const TetMesh& mesh) {
    std::vector<std::string> names;
    for (const Field& f : mesh.point_fields()) {
        if (f.num_components == 3) names.push_back(f.name);
    }
    return names;
}

FlowVolumeSpec default_flow_spec(const FlowDomain& domain) {
    const TetMesh& mesh = domain.mesh();
    FlowVolumeSpec spec;
    if (!domain.vector_arrays.empty()) spec.vectors = domain.vector_arrays.front();
    const Bounds3 bounds = mesh.bounds();
    const double diagonal = bounds.diagonal() > 0 ? bounds.diagonal() : 1.0;
    spec.seed_center = 0.5 * (bounds.lo + bounds.hi);
    spec.seed_width = spec.seed_height = diagonal / 8;
    spec.seed_resolution = 16;
    spec.steps = 50;
    double speed = 0;
    std::size_t counted = 0;
    if (const Field* v = find_field(mesh.point_fields(), spec.vectors)) {
        for (std::size_t p = 0; p < v->num_tuples(); ++p) {
            const double m = v->magnitude(p);
            if (std::isfinite(m)) speed += m, ++counted;
        }
    }
    speed = counted > 0 ? speed / static_cast<double>(counted) : 0;
    spec.dt = speed > 0 ? 0.5 * diagonal / (spec.steps * speed) : 0.05;
    return spec;
}

Status check_flow_spec(const FlowDomain& domain, const FlowVolumeSpec& spec) {
    for (const std::string& name : domain.vector_arrays) {
        if (name == spec.vectors) return {};
    }
    std::string names;
    for (const std::string& name : domain.vector_arrays)
        names += (names.empty() ? "" : ", ") + name;
    return make_error(ErrorCode::kNotFound,
                      "no 3-component point array '" + spec.vectors + "' (vector arrays: " +
                          (names.empty() ? std::string("none") : names) + ")",
                      domain.path);
}

TransferFunction dye_transfer_function(const FlowVolumeSpec& spec, const TetMesh& domain) {
    const double unit = spec.unit_distance.value_or(domain.bounds().diagonal() / 30.0);
    return TransferFunction::create({{0.0, spec.color}}, {{0.0, 0.0}, {1.0, spec.opacity}},
                                    unit > 0 ? unit : 1.0)
        .value();
}

DyeSeed dye_seed(const FlowVolumeSpec& spec) {
    DyeSeed seed;
    seed.center = spec.seed_center;
    seed.width = spec.seed_width;
    seed.height = spec.seed_height;
    seed.resolution = spec.seed_resolution;
    seed.normal = spec.seed_normal;
    return seed;
}

FlowVolumeOptions flow_volume_options(const FlowVolumeSpec& spec, const std::vector<double>& times,
                                      int time_step) {
    FlowVolumeOptions options;
    options.steps = spec.steps;
    options.dt = spec.dt;
    options.compressible = spec.compressible;
    options.split_threshold = spec.split_threshold;
    options.start_time = spec.start_time;
    if (spec.unsteady && !spec.start_time && times.size() > 1 && time_step >= 0 &&
        static_cast<std::size_t>(time_step) < times.size()) {
        options.start_time = times[static_cast<std::size_t>(time_step)];
    }
    return options;
}

std::optional<std::array<Vec3, 4>> seed_polygon(const FlowDomain& domain,
                                                const PointLocator& locator,
                                                const FlowVolumeSpec& spec) {
    const TetMesh& mesh = domain.mesh();
    const Field* field = find_field(mesh.point_fields(), spec.vectors);
    const auto location = locator.locate(spec.seed_center);
    if (!field || field->num_components != 3 || !location) return std::nullopt;
    Vec3 normal = spec.seed_normal.value_or(interpolate_vector(mesh, *field, *location));
    const double length = glm::length(normal);
    if (!std::isfinite(length) || length == 0) return std::nullopt;
    // As grow_flow_volume makes the polygon's axes.
    normal /= length;
    const Vec3 other = std::abs(normal.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    const Vec3 u = glm::normalize(glm::cross(other, normal)) * (spec.seed_width / 2);
    const Vec3 v = glm::cross(normal, glm::normalize(u)) * (spec.seed_height / 2);
    const Vec3& c = spec.seed_center;
    return std::array<Vec3, 4>{c - u - v, c + u - v, c + u + v, c - u + v};
}

Result<VelocityField> load_velocity(const FlowDomain& domain, const std::string& vectors,
                                    bool unsteady, const LoadOptions& load) {
    FlowVolumeSpec wanted;
    wanted.vectors = vectors;
    TR_TRY_STATUS(check_flow_spec(domain, wanted));
    const TetMesh& mesh = domain.mesh();
    const Field& first = *find_field(mesh.point_fields(), vectors);
    if (!unsteady) return VelocityField::steady(mesh, first);
    const std::vector<double>& times = domain.loaded->input.time_values;
    if (times.size() < 2 || domain.path.empty()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "unsteady flow needs a time series (.pvd, Exodus with several steps); "
                          "this mesh has " +
                              std::to_string(std::max<std::size_t>(times.size(), 1)) + " time step",
                          domain.path);
    }
    std::vector<Field> samples;
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (static_cast<int>(k) == domain.loaded->input.time_step) {
            samples.push_back(first);
            continue;
        }
        LoadOptions options = load;
        options.time_step = static_cast<int>(k);
        TR_TRY(const LoadedMesh step, load_tet_mesh(domain.path, options));
        if (step.tets.num_points() != mesh.num_points() ||
            step.tets.num_tets() != mesh.num_tets()) {
            return make_error(ErrorCode::kInvalidMesh,
                              "time step " + std::to_string(k) +
                                  " has another mesh than the first (unsteady flow needs one "
                                  "mesh for all steps)",
                              domain.path);
        }
        const Field* field = find_field(step.tets.point_fields(), vectors);
        if (!field || field->num_components != 3) {
            return make_error(ErrorCode::kNotFound,
                              "time step " + std::to_string(k) +
                                  " has no 3-component point array '" + vectors + "'",
                              domain.path);
        }
        samples.push_back(*field);
        report_progress(load.progress, "reading time steps",
                        static_cast<double>(k + 1) / static_cast<double>(times.size()));
    }
    return VelocityField::unsteady(mesh, std::move(samples), times);
}

Result<FlowVolume> grow_scene_flow_volume(const FlowDomain& domain, const FlowVolumeSpec& spec,
                                          const ProgressFn& progress) {
    try {
        TR_TRY_STATUS(check_flow_spec(domain, spec));
        LoadOptions load;
        load.progress = progress;
        TR_TRY(const VelocityField velocity,
               load_velocity(domain, spec.vectors, spec.unsteady, load));
        auto fv = grow_flow_volume(domain.mesh(), *domain.adjacency, velocity, dye_seed(spec),
                                   flow_volume_options(spec, domain.loaded->input.time_values,
                                                       domain.loaded->input.time_step),
                                   progress);
        if (!fv.ok()) return with_where(fv.error(), domain.path);
        return std::move(fv).value();
    } catch (const std::exception& e) {  // e.g. out of memory: an error, not a crash
        return make_error(ErrorCode::kInternal, e.what(), domain.path);
    }
}

}  // namespace tr
