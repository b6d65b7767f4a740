#include <apps/flowvol_setup.h>
#include <apps/viewer/viewer_flow.h>
#include <project/cpu_renderer.h>

#include <chrono>
#include <cmath>
#include <exception>

namespace tr::viewer {

std::vector<std::string> vector_arrays(const TetMesh& mesh) {
    std::vector<std::string> names;
    for (const Field& f : mesh.point_fields()) {
        if (f.num_components == 3) names.push_back(f.name);
    }
    return names;
}

FlowVolumeSpec default_flow_spec(const FlowDomain& domain) {
    const TetMesh& mesh = domain.loaded.tets;
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

std::optional<std::array<Vec3, 4>> seed_polygon(const FlowDomain& domain,
                                                const PointLocator& locator,
                                                const FlowVolumeSpec& spec) {
    const TetMesh& mesh = domain.loaded.tets;
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

GrownFlowVolume grow_now(const FlowDomain& domain, const FlowVolumeSpec& requested,
                         std::uint64_t id) {
    GrownFlowVolume grown;
    grown.spec = requested;
    grown.id = id;
    FlowVolumeSpec spec = requested;
    const std::vector<double>& times = domain.loaded.input.time_values;
    if (spec.unsteady && !spec.start_time && times.size() > 1) {
        spec.start_time = times[static_cast<std::size_t>(domain.loaded.input.time_step)];
    }
    try {
        const Status checked = check_flow_spec(domain, spec);
        if (!checked.ok()) {
            grown.error = checked.error();
            return grown;
        }
        auto velocity =
            apps::load_velocity(domain.path, domain.loaded, spec.vectors, spec.unsteady);
        if (!velocity.ok()) {
            grown.error = velocity.error();
            return grown;
        }
        const auto start = std::chrono::steady_clock::now();
        auto fv = grow_flow_volume(domain.loaded.tets, domain.adjacency, *velocity,
                                   apps::dye_seed(spec), apps::flow_volume_options(spec));
        grown.grow_ms = apps::ms_since(start);
        if (!fv.ok()) {
            grown.error = apps::with_where(fv.error(), domain.path);
            return grown;
        }
        grown.volume = std::move(fv).value();
    } catch (const std::exception& e) {  // e.g. out of memory: an error, not a crash
        grown.error = Error{ErrorCode::kInternal, e.what(), domain.path};
        return grown;
    }
    const TetMesh& mesh = grown.volume->mesh;
    grown.concentration.assign(mesh.num_points(), 1.0f);
    if (const Field* c = find_field(mesh.point_fields(), "concentration")) {
        for (std::size_t p = 0; p < grown.concentration.size(); ++p)
            grown.concentration[p] = static_cast<float>(c->get(p));
    }
    grown.longest_edge = longest_edge(mesh);
    return grown;
}

FlowGrower::FlowGrower(const FlowDomain& domain) : domain_(domain), thread_([this] { run(); }) {}

FlowGrower::~FlowGrower() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void FlowGrower::request(const FlowVolumeSpec& spec, std::uint64_t id) {
    {
        std::lock_guard lock(mutex_);
        pending_ = Request{spec, id};
    }
    wake_.notify_all();
}

std::shared_ptr<GrownFlowVolume> FlowGrower::take() {
    std::lock_guard lock(mutex_);
    return std::move(finished_);
}

bool FlowGrower::busy() const {
    std::lock_guard lock(mutex_);
    return growing_ || pending_.has_value() || finished_ != nullptr;
}

std::shared_ptr<GrownFlowVolume> FlowGrower::wait_for(std::uint64_t id) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return finished_ && finished_->id >= id; });
    return std::move(finished_);
}

void FlowGrower::run() {
    for (;;) {
        Request request;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            request = std::move(*pending_);
            pending_.reset();
            growing_ = true;
        }
        auto grown = std::make_shared<GrownFlowVolume>(grow_now(domain_, request.spec, request.id));
        {
            std::lock_guard lock(mutex_);
            finished_ = std::move(grown);
            growing_ = false;
        }
        done_.notify_all();
    }
}

}  // namespace tr::viewer
