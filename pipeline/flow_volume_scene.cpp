#include <pipeline/flow_volume_scene.h>
#include <pipeline/quick_look.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <utility>

namespace tr {

std::string planar_flow_note(const PlanarSheet& sheet) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "2D mesh: the flow on its plane through (%.4g, %.4g, %.4g), normal (%.3g, "
                  "%.3g, %.3g); cells split into triangles, the velocity linear on each and "
                  "tangent to the plane",
                  sheet.point.x, sheet.point.y, sheet.point.z, sheet.normal.x, sheet.normal.y,
                  sheet.normal.z);
    return line;
}

std::vector<std::string> vector_arrays(const TetMesh& mesh) {
    std::vector<std::string> names;
    for (const Field& f : mesh.point_fields()) {
        if (f.num_components == 3) names.push_back(f.name);
    }
    return names;
}

FlowVolumeSpec default_flow_spec(const FlowDomain& domain) {
    FlowVolumeSpec spec;
    if (!domain.vector_arrays.empty()) spec.vectors = domain.vector_arrays.front();
    spec.seed_resolution = 16;
    spec.steps = 50;
    // As `tetrender flowvol` chooses them; a still flow (or none) keeps the centre of the bounds.
    auto chosen =
        choose_flow_spec(domain, spec, {.seed_center = true, .seed_size = true, .dt = true});
    if (chosen.ok()) return std::move(chosen).value();
    const Bounds3 bounds = domain.mesh().bounds();
    spec.seed_center = 0.5 * (bounds.lo + bounds.hi);
    spec.seed_width = spec.seed_height = (bounds.diagonal() > 0 ? bounds.diagonal() : 1.0) / 8;
    return spec;
}

namespace {

std::string xyz(const Vec3& p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g)", p.x, p.y, p.z);
    return text;
}

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return text;
}

// The centroid of a real tet at point `p` (inside the domain even when `p` is on its boundary);
// the point itself when no tet uses it.
Vec3 inside_at(const TetMesh& mesh, std::size_t p) {
    for (std::size_t t = 0; t < mesh.num_real_tets(); ++t) {
        const auto& tet = mesh.tets()[t];
        if (std::find(tet.begin(), tet.end(), p) == tet.end()) continue;
        Vec3 sum(0.0);
        for (auto v : tet) sum += mesh.points()[v];
        return sum / 4.0;
    }
    return mesh.points()[p];
}

}  // namespace

Result<FlowVolumeSpec> choose_flow_spec(const FlowDomain& domain, FlowVolumeSpec spec,
                                        const FlowSpecChoices& choose,
                                        std::vector<std::string>* notes) {
    TR_TRY_STATUS(check_flow_spec(domain, spec));
    const TetMesh& mesh = domain.mesh();
    const Field& velocity = *find_field(mesh.point_fields(), spec.vectors);
    std::vector<std::pair<double, std::size_t>> speeds;  // finite, non-zero
    for (std::size_t p = 0; p < velocity.num_tuples(); ++p) {
        const double m = velocity.magnitude(p);
        if (std::isfinite(m) && m > 0) speeds.emplace_back(m, p);
    }
    if (speeds.empty()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the flow '" + spec.vectors +
                              "' is zero everywhere: there is nothing to release dye into",
                          domain.path);
    }
    const Bounds3 bounds = mesh.bounds();
    const double diagonal = bounds.diagonal() > 0 ? bounds.diagonal() : 1.0;
    const auto say = [&](std::string line) {
        if (notes) notes->push_back(std::move(line));
    };
    // The seed's speed: at the fastest point but for a thousandth (spikes), chosen as the seed's
    // centre; or, for dt alone, at the point nearest the centre given.
    double seed_speed = 0;
    if (choose.seed_center) {
        const std::size_t rank = (speeds.size() - 1) * 999 / 1000;
        std::nth_element(speeds.begin(), speeds.begin() + static_cast<std::ptrdiff_t>(rank),
                         speeds.end());
        seed_speed = speeds[rank].first;
        spec.seed_center = inside_at(mesh, speeds[rank].second);
        say("seed centre chosen: the dye is released at " + xyz(spec.seed_center) +
            ", where the flow is fastest (speed " + number(seed_speed) + ")");
    } else if (choose.dt) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& [m, p] : speeds) {
            const double d = glm::length(mesh.points()[p] - spec.seed_center);
            if (d < nearest) nearest = d, seed_speed = m;
        }
    }
    if (choose.seed_size) {
        spec.seed_width = spec.seed_height = diagonal / 8;
        say("seed size chosen: the dye polygon is " + number(spec.seed_width) + " x " +
            number(spec.seed_height) + " (an eighth of the domain's diagonal a side)");
    }
    if (choose.dt) {
        spec.dt = kDyeTravel * diagonal / (spec.steps * seed_speed);
        say("dt chosen: dt = " + number(spec.dt) + ", so that the front travels " +
            std::to_string(static_cast<int>(std::lround(100 * kDyeTravel))) +
            "% of the domain's diagonal in " + std::to_string(spec.steps) +
            " layers at the seed's speed");
    }
    return spec;
}

Result<FlowVolumeSpec> resolve_flow_spec(const FlowDomain& domain, const FlowVolumeSpec& spec,
                                         std::vector<std::string>* notes) {
    if (!spec.choose.any()) return spec;
    TR_TRY(FlowVolumeSpec chosen, choose_flow_spec(domain, spec, spec.choose, notes));
    chosen.choose = {};
    return chosen;
}

std::optional<Camera> dye_camera(const TetMesh& dye, const Camera& camera, int width, int height) {
    const Bounds3 bounds = dye.bounds();
    if (dye.num_tets() == 0 || bounds.empty() || camera.parallel) return std::nullopt;
    const CameraFrame frame(camera, width, height);
    Vec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? bounds.hi.x : bounds.lo.x,
                     (corner & 2) ? bounds.hi.y : bounds.lo.y,
                     (corner & 4) ? bounds.hi.z : bounds.lo.z);
        const Vec3 image = frame.project(p);
        if (!(image.z > 0)) return std::nullopt;  // behind the eye
        lo = glm::min(lo, image), hi = glm::max(hi, image);
    }
    if (hi.x - lo.x >= 0.5 * width || hi.y - lo.y >= 0.5 * height) return std::nullopt;
    CameraFit fit;
    fit.from = camera.position - camera.focal_point;
    fit.width = width;
    fit.height = height;
    fit.view_angle = camera.view_angle;
    const TetMesh* meshes[] = {&dye};
    return fitting_camera(meshes, fit);
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
        options.planar_as_slab = domain.planar.has_value();
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
