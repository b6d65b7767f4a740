#include <core/stopwatch.h>
#include <pipeline/flow_volume_render.h>
#include <pipeline/methods/projected_tetrahedra.h>
#include <pipeline/scene_volumes.h>
#include <project/cpu_renderer.h>
#include <project/reference_raycaster.h>
#include <project/segment_merge.h>

#include <chrono>

namespace tr {
namespace {

using Clock = std::chrono::steady_clock;

void add_load_stats(NamedStats& stats, const LoadedMesh& loaded) {
    stats.set("load_ms", loaded.read_ms);
    stats.set("tetrahedralize_ms", loaded.tetrahedralize_ms);
}

// The dye grown from volume 0's mesh, drawn over the opaque geometry without sorting.
Result<RenderResult> render_flow_volume(Pipeline& pipeline, const Scene& scene,
                                        const RenderOptions& options) {
    const SceneVolume& volume = scene.volumes[0];
    RenderResult result;
    TR_TRY(const FlowDomain domain, pipeline.flow_domain(volume));
    add_load_stats(result.stats, *domain.loaded);
    // A scene file's scalar is checked (the file stays a valid spec scene) but not drawn.
    if (!volume.scalar.empty()) TR_TRY_STATUS(pipeline.scalar(volume, domain.mesh()));
    // What the scene left to the data (seed_center, seed_size, dt) is chosen, and said.
    TR_TRY(const FlowVolumeSpec spec, resolve_flow_spec(domain, *scene.flow_volume, &result.notes));
    auto start = Clock::now();
    TR_TRY(FlowVolume grown, grow_scene_flow_volume(domain, spec, pipeline.options().progress));
    auto fv = std::make_shared<const FlowVolume>(std::move(grown));
    result.stats.set("grow_ms", ms_since(start));
    if (fv->unresolved_edges > 0) {
        result.notes.push_back(std::to_string(fv->unresolved_edges) +
                               " stretched front edges were left unsplit (at the refinement "
                               "limit, e.g. at a stagnation point, or their new particle left "
                               "the domain)");
    }
    TR_TRY(const OpaqueSet opaque, pipeline.opaque(scene));
    FlowVolumeView view{scene.camera,    scene.width, scene.height, scene.background,
                        opaque.layers(), spec,        nullptr};
    if (spec.fit_camera_to_dye) {
        if (auto camera = dye_camera(fv->mesh, scene.camera, scene.width, scene.height)) {
            view.camera = *camera;
            result.notes.push_back(
                "the dye covers less than half the picture: the camera frames "
                "the dye alone");
        }
    }
    SurfaceMesh boundary;
    if (spec.context) {
        boundary = boundary_surface(domain.mesh(), *domain.adjacency);
        view.context = &boundary;
    }
    start = Clock::now();
    FlowVolumeRenderer renderer(*fv, domain.mesh(), view);
    if (options.on_flow_volume_layer) {
        for (std::size_t k = 0; k < fv->layer_tets.size(); ++k) {
            TR_TRY_STATUS(
                options.on_flow_volume_layer(k, renderer.render_up_to(fv->layer_tets[k])));
        }
    }
    result.image = renderer.render_up_to(fv->mesh.num_tets());
    result.stats.set("render_ms", ms_since(start));
    result.stats.set("layers", fv->layer_tets.size());
    result.stats.set("flow_volume_tets", fv->mesh.num_tets());
    result.stats.set("particles_inserted", fv->particles_inserted);
    result.stats.set("particles_stopped", fv->particles_stopped);
    result.stats.set("unresolved_edges", fv->unresolved_edges);
    result.flow_volume = std::move(fv);
    return result;
}

// The brute-force reference ray caster: no sort, no opaque geometry. Several volumes go by its
// own path for them (project/reference_raycaster.h), one volume by the one-mesh path.
Result<RenderResult> render_reference_picture(Pipeline& pipeline, const Scene& scene) {
    RenderResult result;
    TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
           load_scene_volumes(pipeline, scene, result.stats));
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    const auto start = Clock::now();
    if (scene.volumes.size() == 1) {
        result.image =
            render_reference(loaded->meshes[0]->tets, loaded->scalars[0],
                             scene.volumes[0].transfer_function, frame, scene.background);
    } else {
        std::vector<ReferenceVolume> volumes;
        for (const VolumeData& v : loaded->scene.volumes) {
            volumes.push_back({v.mesh, v.scalar, v.tf});
        }
        result.image = render_reference(volumes, frame, scene.background);
    }
    result.stats.set("raster_ms", ms_since(start));
    result.stats.set("integrator", "reference");
    return result;
}

// Every volume's segments merged per pixel by depth (project/segment_merge.h): several volumes
// in one space, or one mesh whose cells have no provable visibility order. `why` is said in a
// note and in the stats.
Result<RenderResult> render_merged(Pipeline& pipeline, const Scene& scene,
                                   const RenderOptions& options, const OpaqueLayer* stops,
                                   std::vector<std::string> notes, const std::string& why) {
    RenderResult result;
    result.notes = std::move(notes);
    if (scene.volumes.size() == 1) {
        result.notes.push_back(why +
                               "; drawn by merging each pixel's segments by depth "
                               "instead, which needs no order");
    }
    TR_TRY(const std::unique_ptr<SceneVolumes> loaded,
           load_scene_volumes(pipeline, scene, result.stats));
    const auto start = Clock::now();
    VolumeScene& merged = loaded->scene;
    for (VolumeData& v : merged.volumes) {
        v.shader = &pipeline.shader(*v.tf, options.integrator, longest_edge(*v.mesh));
    }
    result.stats.set("shader_ms", ms_since(start));
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    OpaqueLayer layer;  // the scene's opaque surfaces, unless stops stand in for them
    if (!stops) {
        TR_TRY(layer, opaque_layer(pipeline, scene, frame, result.stats));
    }
    static_cast<View&>(merged) = scene_view(scene, options, frame, stops ? *stops : layer);
    SegmentMergeStats merge;
    result.image =
        render_segment_merge(merged, &merge, options.transparent ? &result.alpha : nullptr);
    NamedStats& stats = result.stats;
    stats.set("raster_ms", merge.raster_ms);
    stats.set("fragments", merge.fragments);
    stats.set("overlap_intervals", merge.overlap_intervals);
    stats.set("compositing", "merged");
    stats.set("merged_because", why);
    stats.set("integrator", std::string(integrator_name(options.integrator)));
    return result;
}

class ProjectedTetrahedra final : public RenderMethod {
  public:
    std::string_view name() const override { return kDefaultMethod; }
    bool draws_transparent() const override { return true; }

    const MethodKeys& keys() const override {
        static const MethodKeys none{};
        return none;
    }

    Status check(const Scene& scene, const RenderOptions& options) const override {
        TR_TRY_STATUS(check_method_keys(scene, name(), keys()));
        if (scene.flow_volume && scene.volumes.size() > 1) {
            return make_error(ErrorCode::kUnsupported,
                              "$.flow_volume: a flow volume grows through one mesh; this scene "
                              "has several volumes",
                              scene.source);
        }
        if (options.reference && !scene.opaque.empty()) {
            return make_error(ErrorCode::kUnsupported,
                              "the reference ray caster draws no opaque geometry", scene.source);
        }
        if (options.transparent && (options.reference || scene.flow_volume)) {
            return make_error(ErrorCode::kUnsupported,
                              "the reference ray caster and flow volumes are not drawn over "
                              "transparent black",
                              scene.source);
        }
        if (options.reference && scene.flow_volume) {
            return make_error(ErrorCode::kUnsupported,
                              "the reference ray caster does not draw flow volumes", scene.source);
        }
        return {};
    }

    Result<RenderResult> render(Pipeline& pipeline, const Scene& scene,
                                const RenderOptions& options) const override {
        if (scene.flow_volume) return render_flow_volume(pipeline, scene, options);
        if (options.reference) return render_reference_picture(pipeline, scene);
        return render_projected_volume(pipeline, scene, options);
    }
};

}  // namespace

Result<RenderResult> render_projected_volume(Pipeline& pipeline, const Scene& scene,
                                             const RenderOptions& options,
                                             const OpaqueLayer* stops) {
    std::vector<std::string> notes;
    if (scene.volumes.size() > 1) {
        return render_merged(pipeline, scene, options, stops, std::move(notes), "several volumes");
    }
    const SceneVolume& volume = scene.volumes[0];
    RenderResult result;
    result.notes = std::move(notes);
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(volume));
    add_load_stats(result.stats, *loaded);
    const CameraFrame frame(scene.camera, scene.width, scene.height);
    TR_TRY(const ViewOrder view, pipeline.visibility_order(volume, frame, options.sort));
    const PreparedSort& prepared = view.prepared;
    const SortStats& sort_stats = view.stats;
    if (wants_convexification(options.sort) && !view.exact) {
        // An exact order was asked for and cannot be had: merge each pixel's segments by
        // depth instead, which needs none.
        std::string why = !prepared.sorted->failure.empty()
                              ? prepared.sorted->failure
                              : std::to_string(sort_stats.cells_in_cycles) +
                                    " cells lie in visibility cycles of this view";
        return render_merged(pipeline, scene, options, stops, std::move(result.notes),
                             "no exact visibility order (" + why + ")");
    }
    if (!prepared.note.empty()) result.notes.push_back(prepared.note);
    if (prepared.exact && !view.exact) {
        result.notes.push_back(std::to_string(sort_stats.cells_in_cycles) +
                               " cells lie in visibility cycles of this view, broken by "
                               "rule: the order is not exact there");
    }
    result.stats.set("adjacency_ms", prepared.sorted->adjacency_ms);
    result.stats.set("convexify_ms", prepared.sorted->convexify_ms);
    TR_TRY(const std::vector<float> scalar, pipeline.scalar(volume, prepared.mesh()));
    result.stats.set("sort_ms", sort_stats.milliseconds);
    const auto start = Clock::now();
    const SegmentShader& shader = pipeline.shader(volume.transfer_function, options.integrator,
                                                  longest_edge(prepared.mesh()));
    result.stats.set("shader_ms", ms_since(start));
    OpaqueLayer layer;  // the scene's opaque surfaces, unless stops stand in for them
    if (!stops) {
        TR_TRY(layer, opaque_layer(pipeline, scene, frame, result.stats));
    }

    RenderInputs in;
    static_cast<View&>(in) = scene_view(scene, options, frame, stops ? *stops : layer);
    in.mesh = &prepared.mesh();
    in.scalar = scalar;
    in.order = view.order;
    in.shader = &shader;
    RenderStats raster;
    result.image =
        render_projected_tetrahedra(in, &raster, options.transparent ? &result.alpha : nullptr);
    NamedStats& stats = result.stats;
    stats.set("raster_ms", raster.raster_ms);
    stats.set("cells", loaded->tets.num_real_tets());
    stats.set("cells_drawn", raster.cells_drawn);
    stats.set("fragments", raster.fragments);
    stats.set("sort", std::string(sort_method_name(options.sort)));
    stats.set("sort_exact", view.exact);
    stats.set("compositing", "sorted");
    stats.set("convexified", prepared.sorted->convexified);
    stats.set("cells_by_fallback", sort_stats.by_fallback);
    stats.set("cells_in_cycles", sort_stats.cells_in_cycles);
    stats.set("integrator", std::string(integrator_name(options.integrator)));
    return result;
}

std::unique_ptr<RenderMethod> make_projected_tetrahedra_method() {
    return std::make_unique<ProjectedTetrahedra>();
}

}  // namespace tr
