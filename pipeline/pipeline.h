#pragma once
// The one path from a scene to an image (docs/architecture.md): load each volume's mesh, then
// hand the scene to the rendering method it names (pipeline/methods/method.h), which takes what it
// needs from here — visibility orders, shaders, opaque surfaces, flow volumes. A Pipeline keeps
// what it loaded and prepared (meshes, adjacency, convexification, sort buffers, the
// pre-integrated table) between renders, so another view of the same scene (an orbit, the
// viewer) costs only the sort and the raster.
//
// `tetrender render`, `demo`, `flowvol`, `sort`, the viewer and the tests all render through it.
// Not thread-safe: one render at a time per Pipeline.

#include <core/image.h>
#include <core/progress.h>
#include <core/result.h>
#include <flowvol/flow_volume.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/render_stats.h>
#include <pipeline/scene.h>
#include <pipeline/sort_preparation.h>
#include <project/opaque_geometry.h>
#include <project/segment_shader.h>
#include <sort/visibility_sort.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tr {

struct RenderOptions {
    // Projected tetrahedra: the visibility order (pipeline/sort_preparation.h) and how each
    // cell's segment is integrated.
    SortMethod sort = SortMethod::kAuto;
    Integrator integrator = Integrator::kPreintegrated;
    // The brute-force reference ray caster instead (project/reference_raycaster.h): no sort,
    // no opaque geometry, no flow volumes. The picture other methods are tested against.
    bool reference = false;
    // Flow volumes: called with the picture after each layer, in order (`tetrender flowvol
    // --frames`); an error stops the render and is returned.
    std::function<Status(std::size_t layer, const Image& picture)> on_flow_volume_layer;
    // Animated methods (texture-advection, spot-noise): called with the picture of each frame
    // 0, 1, ..., the method's `steps`, in order (`tetrender render --frames`); the render then
    // returns the last. An error stops the render and is returned. Unset: the picture of the
    // method's `frame` only.
    std::function<Status(int frame, const Image& picture)> on_frame;
    // The volume alone, as premultiplied RGBA over transparent black: RenderResult::image its
    // colour, RenderResult::alpha its opacity per pixel (the picture over a background b is
    // image + (1 - alpha) b). Opaque surfaces stop the rays but are not drawn, nor is the
    // background: how each MPI rank draws its part (distributed/). Methods:
    // projected-tetrahedra (not its flow volumes or the reference ray caster), pbvr-image,
    // pbvr-object; the others refuse it in check().
    bool transparent = false;
};

// The names users give sorts and integrators, with one wording of their errors for every
// program (kInvalidArgument listing the names).
Result<SortMethod> sort_method_named(std::string_view name);  // auto, mpvo, mpvonc, exact, centroid
Result<Integrator> integrator_named(std::string_view name);   // preintegrated, exact, exp-texture
// Sets options.integrator from a name, or options.reference for "reference".
Status set_integrator_option(RenderOptions& options, std::string_view name);

// Whether a width x height picture's buffers fit the memory budget (core/memory_budget.h):
// Pipeline::check's test, for callers that know the size before they load anything.
Status check_picture_memory(int width, int height);

struct RenderResult {
    Image image;
    NamedStats stats;                // each stage's time (ms) and counts, in order
    std::vector<std::string> notes;  // what the user should know (an order that is not exact)
    std::shared_ptr<const FlowVolume> flow_volume;  // the flow volume drawn, if any
    std::vector<float> alpha;  // RenderOptions::transparent: opacity per pixel, rows as image's
};

// Opaque surfaces of a scene, resolved: the surfaces and their colours.
struct OpaqueSet {
    std::vector<std::shared_ptr<const SurfaceMesh>> surfaces;
    std::vector<Vec3> colors;

    // For render_opaque (pointers into `surfaces`: valid while this set lives).
    std::vector<OpaqueSurface> layers() const;
    bool empty() const { return surfaces.empty(); }
};

// One view's back-to-front order of a volume's real cells.
struct ViewOrder {
    PreparedSort prepared;  // the mesh sorted (maybe convexified) and what the order claims
    std::vector<CellId> order;
    SortStats stats;
    bool exact = false;  // order_is_exact: claimed, and no visibility cycle broken in this view
};

struct PipelineOptions {
    LoadOptions load;     // merging and Delaunay options for every mesh (time_step: per volume)
    ProgressFn progress;  // long stages (reading, tetrahedralizing, growing) report here
};

class Pipeline {
  public:
    explicit Pipeline(PipelineOptions options = {});
    ~Pipeline();
    Pipeline(Pipeline&&) noexcept;
    Pipeline& operator=(Pipeline&&) noexcept;

    // Checks what can be checked before loading anything: the method exists in this build and
    // accepts the scene's method keys and the rest of the scene. Errors name the scene file
    // and the JSON path ("s.json: error: $.method.name: unknown method 'x' (...)").
    Status check(const Scene& scene, const RenderOptions& options = {}) const;

    // Renders `scene` with its method. Errors: check()'s, then loading, an unknown array, a
    // non-finite scalar, and each method's own. Cost: the first render of a scene loads and
    // prepares its meshes; later ones with the same volumes reuse them.
    Result<RenderResult> render(const Scene& scene, const RenderOptions& options = {});

    // --- What methods and tools take from here (cached) ---

    // The volume's mesh, read and tetrahedralized once per (file or handed-over mesh, time step).
    Result<std::shared_ptr<const LoadedMesh>> mesh(const SceneVolume& volume);

    // The volume's mesh prepared for `method` (adjacency, maybe convexified), cached per mesh
    // and per whether it is convexified.
    Result<PreparedSort> prepared_sort(const SceneVolume& volume, SortMethod method);

    // The order of `volume`'s cells for the view `frame`, sorted by `method` with the
    // pipeline's sorter (its buffers reused from view to view).
    Result<ViewOrder> visibility_order(const SceneVolume& volume, const CameraFrame& frame,
                                       SortMethod method);

    // The volume's point scalar (scene.md "The scalar") on `on` — its own mesh or a sorted
    // (convexified) one: points only virtual tets use get 0 (never drawn). Errors: no such
    // array (listing the arrays), a component out of range, a value that is not finite (naming
    // the point).
    Result<std::vector<float>> scalar(const SceneVolume& volume, const TetMesh& on);

    // The domain a flow (flow volume, texture advection, spot noise) of `volume` takes: the mesh
    // as loaded, never convexified; a planar 2D mesh as its slab (mesh/planar_slab.h, with
    // FlowDomain::planar set), which no other use of the volume sees.
    Result<FlowDomain> flow_domain(const SceneVolume& volume);

    // The scene's opaque surfaces: files read, side sets and boundaries of its volumes. Errors:
    // a surface file that does not read, a side set the volume's mesh does not have.
    Result<OpaqueSet> opaque(const Scene& scene);

    // The shader for `tf` and `integrator` over segments up to `max_length`, made once and kept
    // (the pre-integrated table takes tens of milliseconds; the last kMaxShaders made are kept,
    // enough for every volume of a scene). The reference stays valid until kMaxShaders others
    // have been made or clear() is called.
    const SegmentShader& shader(const TransferFunction& tf, Integrator integrator,
                                double max_length);

    // The sorter whose buffers every render reuses.
    VisibilitySorter& sorter() { return sorter_; }

    const PipelineOptions& options() const { return options_; }

    // Drops every cached mesh and preparation.
    void clear();

  private:
    std::string mesh_key(const SceneVolume& volume) const;
    Result<std::shared_ptr<const SortedMesh>> sorted_mesh(const SceneVolume& volume,
                                                          bool convexify);

    PipelineOptions options_;
    std::map<std::string, std::shared_ptr<const LoadedMesh>> meshes_;
    std::map<std::string, std::shared_ptr<const SortedMesh>> sorted_;
    // Planar 2D meshes loaded as slabs for flow_domain, and their adjacency.
    struct SlabDomain {
        std::shared_ptr<const LoadedMesh> loaded;
        std::shared_ptr<const FaceAdjacency> adjacency;
    };
    std::map<std::string, SlabDomain> slabs_;
    VisibilitySorter sorter_;
    static constexpr std::size_t kMaxShaders = 2 * kMaxVolumes;
    struct CachedShader;  // a shader with a copy of its transfer function
    std::vector<std::unique_ptr<CachedShader>> shaders_;  // oldest first
};

}  // namespace tr
