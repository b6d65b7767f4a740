#include <core/config.h>
#include <core/memory_budget.h>
#include <core/parallel.h>
#include <mesh/point_data.h>
#include <pipeline/methods/method.h>
#include <pipeline/pipeline.h>

#if TETRENDER_HAS_VTK
#include <io/read_surface.h>
#endif

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

namespace tr {
namespace {

bool same_transfer_function(const TransferFunction& a, const TransferFunction& b) {
    if (a.unit_distance() != b.unit_distance()) return false;
    const auto& ac = a.color_points();
    const auto& bc = b.color_points();
    const auto& ao = a.opacity_points();
    const auto& bo = b.opacity_points();
    if (ac.size() != bc.size() || ao.size() != bo.size()) return false;
    for (std::size_t i = 0; i < ac.size(); ++i) {
        if (ac[i].s != bc[i].s || ac[i].rgb != bc[i].rgb) return false;
    }
    for (std::size_t i = 0; i < ao.size(); ++i) {
        if (ao[i].s != bo[i].s || ao[i].a != bo[i].a) return false;
    }
    return true;
}

Error scene_error(const Scene& scene, ErrorCode code, const std::string& message) {
    return make_error(code, message, scene.source);
}

}  // namespace

Result<SortMethod> sort_method_named(std::string_view name) {
    if (auto m = parse_sort_method(name)) return *m;
    return make_error(ErrorCode::kInvalidArgument, "unknown sort '" + std::string(name) +
                                                       "' (auto, mpvo, mpvonc, exact, centroid)");
}

Result<Integrator> integrator_named(std::string_view name) {
    if (auto i = parse_integrator(name)) return *i;
    return make_error(ErrorCode::kInvalidArgument,
                      "unknown integrator '" + std::string(name) +
                          "' (preintegrated, exact, exp-texture; reference where rendering "
                          "takes it)");
}

Status set_integrator_option(RenderOptions& options, std::string_view name) {
    if (name == "reference") {
        options.reference = true;
        return {};
    }
    TR_TRY(options.integrator, integrator_named(name));
    options.reference = false;
    return {};
}

std::vector<OpaqueSurface> OpaqueSet::layers() const {
    std::vector<OpaqueSurface> out;
    for (std::size_t i = 0; i < surfaces.size(); ++i) out.push_back({surfaces[i].get(), colors[i]});
    return out;
}

struct Pipeline::CachedShader {
    TransferFunction tf;
    Integrator integrator;
    double max_length;
    std::unique_ptr<SegmentShader> shader;
};

Pipeline::Pipeline(PipelineOptions options) : options_(std::move(options)) {
    if (!options_.load.progress) options_.load.progress = options_.progress;
}

Pipeline::~Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;

void Pipeline::clear() {
    meshes_.clear();
    sorted_.clear();
    slabs_.clear();
    shaders_.clear();
}

Status check_picture_memory(int width, int height) {
    // 16 bytes a pixel. Measured: an 8192^2 picture of projected tetrahedra (a 2000-tet mesh)
    // peaked at 1.03 GB resident, 14.6 bytes a pixel.
    const double pixels = static_cast<double>(width) * static_cast<double>(height);
    return check_memory(pixels * 16.0,
                        "a " + std::to_string(width) + "x" + std::to_string(height) + " picture");
}

Status Pipeline::check(const Scene& scene, const RenderOptions& options) const {
    if (scene.volumes.empty()) {
        return scene_error(scene, ErrorCode::kInvalidArgument, "the scene has no volume");
    }
    if (const Status fits = check_picture_memory(scene.width, scene.height); !fits.ok()) {
        return scene_error(scene, fits.error().code, fits.error().message);
    }
    const RenderMethod* method = find_method(scene.method_name());
    if (!method) {
        std::string names;
        for (const std::string& n : method_names()) names += (names.empty() ? "" : ", ") + n;
        return scene_error(
            scene, ErrorCode::kInvalidArgument,
            "$.method.name: unknown method '" + scene.method_name() + "' (" + names + ")");
    }
    if (options.transparent && !method->draws_transparent()) {
        return scene_error(scene, ErrorCode::kUnsupported,
                           "$.method.name: " + scene.method_name() +
                               " does not draw a volume alone over transparent black");
    }
    return method->check(scene, options);
}

namespace {

// Whether any of `box` may be seen by `camera`: false only when the box lies wholly behind a
// perspective eye or its projection (the hull of its projected corners) misses the picture.
bool may_be_in_view(const Bounds3& box, const CameraFrame& camera) {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    bool behind = false;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                     (corner & 4) ? box.hi.z : box.lo.z);
        const Vec3 s = camera.project(p);
        if (!camera.orthographic() && s.z <= 0) {
            behind = true;
            continue;
        }
        x0 = std::min(x0, s.x), x1 = std::max(x1, s.x);
        y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
    }
    if (behind) return x0 <= x1;  // straddles the eye's plane: maybe; wholly behind: no
    return x1 >= 0 && y1 >= 0 && x0 <= camera.width() && y0 <= camera.height();
}

// A note when the scene gives `repetitions` or `seed` and the method's table says it ignores
// them; empty otherwise.
std::string ignored_method_keys_note(const Scene& scene, const RenderMethod& method) {
    if (!scene.method) return {};
    const bool repetitions = scene.method->repetitions && !method.keys().uses_repetitions;
    const bool seed = scene.method->seed && !method.keys().uses_seed;
    if (!repetitions && !seed) return {};
    return std::string(repetitions && seed ? "repetitions and seed apply"
                       : repetitions       ? "repetitions apply"
                                           : "seed applies") +
           " to the stochastic methods: " + std::string(method.name()) + " ignores " +
           (repetitions && seed ? "them" : "it");
}

}  // namespace

Result<RenderResult> Pipeline::render(const Scene& scene, const RenderOptions& options) {
    TR_TRY_STATUS(check(scene, options));
    const RenderMethod* method = find_method(scene.method_name());
    try {
        TR_TRY(RenderResult result, method->render(*this, scene, options));
        if (std::string note = ignored_method_keys_note(scene, *method); !note.empty()) {
            result.notes.insert(result.notes.begin(), std::move(note));
        }
        // What every method's stats say, set here once.
        result.stats.set("method", std::string(method->name()));
        result.stats.set("threads", thread_count());
        result.stats.set("width", scene.width);
        result.stats.set("height", scene.height);
        // A volume out of view draws nothing: say so (the picture is right, but rarely meant).
        // Not for a transparent picture, which is a part of one.
        if (!scene.flow_volume && !options.transparent) {
            const CameraFrame frame(scene.camera, scene.width, scene.height);
            bool any_out = false;
            for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
                auto loaded = mesh(scene.volumes[v]);  // kept from the render: no reload
                if (!loaded.ok() || (*loaded)->tets.num_real_tets() == 0) continue;
                if (!may_be_in_view((*loaded)->tets.bounds(), frame)) {
                    result.notes.push_back(
                        (scene.volumes.size() > 1 ? "volume " + std::to_string(v) + " (" +
                                                        scene.volumes[v].mesh.string() + ")"
                                                  : scene.volumes[v].mesh.string()) +
                        ": no cell is in view of the camera; nothing of it is drawn");
                    any_out = true;
                }
            }
            // Every pixel the background (none off by half an 8-bit level) while the volumes are
            // in view: the transfer function shows nothing of these values.
            const Vec3f background(scene.background);
            const bool empty = std::all_of(
                result.image.pixels.begin(), result.image.pixels.end(), [&](const Vec3f& p) {
                    return glm::all(glm::lessThan(glm::abs(p - background), Vec3f(0.5f / 255.0f)));
                });
            if (empty && !any_out && !result.image.pixels.empty()) {
                result.notes.push_back(
                    "the picture is empty: every pixel is the background (the transfer "
                    "function's opacity is zero or too small over the values in view)");
            }
        }
        return result;
    } catch (const std::bad_alloc&) {
        return scene_error(scene, ErrorCode::kInternal, "out of memory while rendering");
    }
}

std::string Pipeline::mesh_key(const SceneVolume& volume) const {
    std::string key;
    if (volume.tets) {
        key = "tets@" + std::to_string(reinterpret_cast<std::uintptr_t>(volume.tets.get()));
    } else if (volume.data) {
        key = "data@" + std::to_string(reinterpret_cast<std::uintptr_t>(volume.data.get()));
    } else {
        key = "file:" + volume.mesh.string();
    }
    return key + "#" + std::to_string(volume.time_step);
}

Result<std::shared_ptr<const LoadedMesh>> Pipeline::mesh(const SceneVolume& volume) {
    const std::string key = mesh_key(volume);
    if (auto it = meshes_.find(key); it != meshes_.end()) return it->second;
    LoadOptions load = options_.load;
    load.time_step = volume.time_step;
    std::shared_ptr<LoadedMesh> loaded;
    if (volume.tets) {
        loaded = std::make_shared<LoadedMesh>();
        loaded->tets = *volume.tets;
        loaded->report.num_tets = loaded->tets.num_tets();
    } else if (volume.data) {
        TR_TRY(LoadedMesh m, load_tet_mesh(*volume.data, volume.mesh.string(), load));
        loaded = std::make_shared<LoadedMesh>(std::move(m));
    } else {
        TR_TRY(LoadedMesh m, load_tet_mesh(volume.mesh, load));
        loaded = std::make_shared<LoadedMesh>(std::move(m));
    }
    meshes_[key] = loaded;
    return std::shared_ptr<const LoadedMesh>(loaded);
}

Result<std::shared_ptr<const SortedMesh>> Pipeline::sorted_mesh(const SceneVolume& volume,
                                                                bool convexify) {
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, mesh(volume));
    const std::string key = mesh_key(volume) + (convexify ? "/convexified" : "/bare");
    if (auto it = sorted_.find(key); it != sorted_.end()) return it->second;
    // A convex mesh needs no fill: both flavours are the same.
    const std::string other = mesh_key(volume) + (convexify ? "/bare" : "/convexified");
    if (auto it = sorted_.find(other); it != sorted_.end() && it->second->real_convex) {
        sorted_[key] = it->second;
        return it->second;
    }
    // The sorted mesh shares the loaded tets (aliasing the LoadedMesh that owns them).
    std::shared_ptr<const TetMesh> tets(loaded, &loaded->tets);
    auto prepared = prepare_sorted_mesh(std::move(tets), convexify);
    if (!prepared.ok()) return with_where(prepared.error(), volume.mesh.string());
    auto sorted = std::make_shared<const SortedMesh>(std::move(prepared).value());
    sorted_[key] = sorted;
    return std::shared_ptr<const SortedMesh>(sorted);
}

Result<PreparedSort> Pipeline::prepared_sort(const SceneVolume& volume, SortMethod method) {
    TR_TRY(std::shared_ptr<const SortedMesh> sorted,
           sorted_mesh(volume, wants_convexification(method)));
    return prepare_sort(std::move(sorted), method);
}

Result<ViewOrder> Pipeline::visibility_order(const SceneVolume& volume, const CameraFrame& frame,
                                             SortMethod method) {
    ViewOrder view;
    TR_TRY(view.prepared, prepared_sort(volume, method));
    view.stats = sorter_.sort(view.prepared.mesh(), view.prepared.adjacency(),
                              SortView::from_camera(frame), view.prepared.method, view.order);
    view.exact = order_is_exact(view.prepared, view.stats);
    return view;
}

Result<std::vector<float>> Pipeline::scalar(const SceneVolume& volume, const TetMesh& on) {
    auto values = point_scalar(on, volume.scalar, volume.component);
    if (!values.ok()) return with_where(values.error(), volume.mesh.string());
    // Points beyond the real ones (convexification) carry zeros: never drawn, not checked.
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, mesh(volume));
    const std::size_t real_points = std::min(values->size(), loaded->tets.num_points());
    for (std::size_t p = 0; p < real_points; ++p) {
        if (!std::isfinite((*values)[p])) {
            return make_error(
                ErrorCode::kInvalidMesh,
                "array '" + volume.scalar + "' is not finite at point " + std::to_string(p),
                volume.mesh.string());
        }
    }
    return values;
}

Result<FlowDomain> Pipeline::flow_domain(const SceneVolume& volume) {
    const std::string key = mesh_key(volume);
    if (!volume.tets && !meshes_.contains(key) && !slabs_.contains(key)) {
        // Loaded once as a flow would take it: a planar 2D mesh as a slab, kept apart; any
        // other mesh as mesh() loads it, cached as mesh() caches it.
        LoadOptions load = options_.load;
        load.time_step = volume.time_step;
        load.planar_as_slab = true;
        auto loaded = volume.data ? load_tet_mesh(*volume.data, volume.mesh.string(), load)
                                  : load_tet_mesh(volume.mesh, load);
        if (!loaded.ok()) return loaded.error();
        auto shared = std::make_shared<const LoadedMesh>(std::move(loaded).value());
        if (shared->planar) {
            auto adjacency = build_face_adjacency(shared->tets);
            if (!adjacency.ok()) return with_where(adjacency.error(), volume.mesh.string());
            slabs_[key] = {shared,
                           std::make_shared<const FaceAdjacency>(std::move(adjacency).value())};
        } else {
            meshes_[key] = shared;
        }
    }
    if (auto it = slabs_.find(key); it != slabs_.end()) {
        FlowDomain domain;
        domain.path = volume.data ? std::string() : volume.mesh.string();
        domain.loaded = it->second.loaded;
        domain.adjacency = it->second.adjacency;
        domain.vector_arrays = vector_arrays(domain.loaded->tets);
        domain.planar = domain.loaded->planar;
        return domain;
    }
    TR_TRY(std::shared_ptr<const SortedMesh> bare, sorted_mesh(volume, false));
    TR_TRY(std::shared_ptr<const LoadedMesh> loaded, mesh(volume));
    FlowDomain domain;
    domain.path = volume.data || volume.tets ? std::string() : volume.mesh.string();
    domain.adjacency = std::shared_ptr<const FaceAdjacency>(bare, &bare->adjacency);
    domain.vector_arrays = vector_arrays(loaded->tets);
    domain.loaded = std::move(loaded);
    return domain;
}

Result<OpaqueSet> Pipeline::opaque(const Scene& scene) {
    OpaqueSet set;
    for (const OpaqueSpec& spec : scene.opaque) {
        if (spec.surface) {
            set.surfaces.push_back(spec.surface);
            set.colors.push_back(spec.color);
            continue;
        }
        if (!spec.file.empty()) {
#if TETRENDER_HAS_VTK
            TR_TRY(SurfaceMesh surface, read_surface(spec.file));
            set.surfaces.push_back(std::make_shared<const SurfaceMesh>(std::move(surface)));
            set.colors.push_back(spec.color);
            continue;
#else
            return make_error(ErrorCode::kUnsupported,
                              "this build reads no surface files (TETRENDER_WITH_VTK=OFF)",
                              spec.file.string());
#endif
        }
        if (spec.volume >= scene.volumes.size()) {
            return scene_error(scene, ErrorCode::kInvalidArgument,
                               "an opaque surface names volume " + std::to_string(spec.volume) +
                                   ", which the scene does not have");
        }
        const SceneVolume& volume = scene.volumes[spec.volume];
        if (spec.boundary) {
            TR_TRY(std::shared_ptr<const SortedMesh> bare, sorted_mesh(volume, false));
            set.surfaces.push_back(std::make_shared<const SurfaceMesh>(
                boundary_surface(*bare->mesh, bare->adjacency)));
            set.colors.push_back(spec.color);
            continue;
        }
        TR_TRY(std::shared_ptr<const LoadedMesh> loaded, mesh(volume));
        bool found = false;
        for (const SurfaceMesh& s : loaded->input.surfaces) {
            if (spec.side_set == "*" || s.name == spec.side_set) {
                set.surfaces.push_back(std::make_shared<const SurfaceMesh>(s));
                set.colors.push_back(spec.color);
                found = true;
            }
        }
        if (!found) {
            std::string names;
            for (const SurfaceMesh& s : loaded->input.surfaces)
                names += (names.empty() ? "" : ", ") + s.name;
            return make_error(ErrorCode::kNotFound,
                              "no side set '" + spec.side_set + "' in the mesh (it has: " +
                                  (names.empty() ? std::string("none") : names) + ")",
                              volume.mesh.string());
        }
    }
    return set;
}

const SegmentShader& Pipeline::shader(const TransferFunction& tf, Integrator integrator,
                                      double max_length) {
    for (const auto& cached : shaders_) {
        if (cached->integrator == integrator && cached->max_length == max_length &&
            same_transfer_function(cached->tf, tf)) {
            return *cached->shader;
        }
    }
    auto cached = std::make_unique<CachedShader>(CachedShader{tf, integrator, max_length, {}});
    // The shader keeps a reference to its transfer function: the cached copy.
    cached->shader = std::make_unique<SegmentShader>(cached->tf, integrator, max_length);
    if (shaders_.size() >= kMaxShaders) shaders_.erase(shaders_.begin());
    shaders_.push_back(std::move(cached));
    return *shaders_.back()->shader;
}

}  // namespace tr
