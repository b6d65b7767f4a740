#include <apps/flowvol_setup.h>

#include <string>
#include <utility>

namespace tr::apps {
namespace {

Result<const Field*> vector_array(const TetMesh& mesh, const std::string& name,
                                  const std::string& path) {
    const Field* field = find_field(mesh.point_fields(), name);
    if (field && field->num_components == 3) return field;
    std::string names;
    for (const Field& f : mesh.point_fields()) {
        if (f.num_components == 3) names += (names.empty() ? "" : ", ") + f.name;
    }
    return make_error(ErrorCode::kNotFound,
                      "no 3-component point array '" + name + "' (vector arrays: " +
                          (names.empty() ? std::string("none") : names) + ")",
                      path);
}

}  // namespace

Result<VelocityField> load_velocity(const std::string& path, const LoadedMesh& loaded,
                                    const std::string& vectors, bool unsteady) {
    const TetMesh& domain = loaded.tets;
    TR_TRY(const Field* first, vector_array(domain, vectors, path));
    if (!unsteady) return VelocityField::steady(domain, *first);
    const std::vector<double>& times = loaded.input.time_values;
    if (times.size() < 2) {
        return make_error(ErrorCode::kInvalidArgument,
                          "unsteady flow needs a time series (.pvd, Exodus with several steps); "
                          "this file has " +
                              std::to_string(std::max<std::size_t>(times.size(), 1)) + " time step",
                          path);
    }
    std::vector<Field> samples;
    const ProgressFn progress = terminal_progress();
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (static_cast<int>(k) == loaded.input.time_step) {
            samples.push_back(*first);
            continue;
        }
        LoadOptions options;
        options.time_step = static_cast<int>(k);
        TR_TRY(const LoadedMesh step, load_tet_mesh(path, options));
        if (step.tets.num_points() != domain.num_points() ||
            step.tets.num_tets() != domain.num_tets()) {
            return make_error(ErrorCode::kInvalidMesh,
                              "time step " + std::to_string(k) +
                                  " has another mesh than the first (unsteady flow needs one "
                                  "mesh for all steps)",
                              path);
        }
        TR_TRY(const Field* field, vector_array(step.tets, vectors, path));
        samples.push_back(*field);
        report_progress(progress, "reading time steps", static_cast<double>(k + 1) / times.size());
    }
    return VelocityField::unsteady(domain, std::move(samples), times);
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

FlowVolumeOptions flow_volume_options(const FlowVolumeSpec& spec) {
    FlowVolumeOptions options;
    options.steps = spec.steps;
    options.dt = spec.dt;
    options.compressible = spec.compressible;
    options.split_threshold = spec.split_threshold;
    options.start_time = spec.start_time;
    return options;
}

}  // namespace tr::apps
