#pragma once
// What the viewer shows, without GL: the mesh ready to sort, its arrays, the scalar in use, the
// transfer function the panel edits, the camera and the opaque surfaces. Loaded from a scene
// file or, for a mesh file, made the way `tetrender render` quick mode makes its scene.

#include <apps/viewer/fused_worker.h>
#include <apps/viewer/view_method.h>
#include <apps/viewer/viewer_flow.h>
#include <core/result.h>
#include <mesh/surface_mesh.h>
#include <mesh/unstructured_mesh.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_file_scene.h>
#include <pipeline/quick_scene.h>
#include <pipeline/scene.h>
#include <project/transfer_function.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tr::viewer {

struct ViewerOptions {
    std::string input;  // scene .json or mesh file
    // Scene mode: recolour with this map (empty: the scene's colours), scale the opacity
    // points to this largest opacity (0: as they are), this unit distance (0: the scene's).
    std::string colormap;
    double max_opacity = 0;
    double unit_distance = 0;
    // Mesh mode: the quick look's scene as `tetrender render MESH` makes it (its scalar,
    // colour map, opacity and unit distance as above; width, height from here), and which data
    // a name that is both means. With quick.log_scale (`--log`) the viewer shows log10 of the
    // scalar (values <= 0 as the smallest positive one) under the same transfer function in
    // decades, so that the GL renderer's table stays even in decades; `tetrender render --log`
    // keeps the field and spreads the transfer function instead, so a cell spanning decades
    // differs a little.
    QuickSceneOptions quick;
    QuickFileOptions file;
    int width = 960, height = 600;  // mesh mode (a scene file gives its own unless --size)
    bool size_given = false;
    SortMethod sort = SortMethod::kAuto;
    // A flow volume from the command line; replaces a scene's `flow_volume` key.
    std::optional<FlowVolumeSpec> flow_volume;
};

// The editable transfer function: a colour map spread over [lo, hi] and opacity points.
struct TransferEdit {
    std::string colormap;  // empty: the scene's own colours (`scene_colors`)
    std::vector<ColorPoint> scene_colors;
    std::vector<OpacityPoint> opacity;
    double unit_distance = 1;
    double lo = 0, hi = 1;  // the scalar's range
};

// One volume of a scene of several (scene.md "Several volumes in one space"), drawn fused on the
// CPU (fused_worker.h): its mesh as loaded (the fused renderers need no visibility order, so it
// is never convexified), the arrays that can be its scalar, the scalar in use and its transfer
// function as the panel edits it.
struct FusedVolume {
    std::shared_ptr<const LoadedMesh> loaded;
    std::vector<std::string> arrays;
    std::string scalar_name;
    std::vector<float> scalar;  // one per loaded->tets point
    TransferEdit edit;
    double longest_edge = 1;

    const TetMesh& mesh() const { return loaded->tets; }
};

struct ViewerScene {
    // Camera, size, background; each volume's transfer function (volumes[v].transfer_function:
    // as loaded, then as the panel edits it).
    Scene scene;
    // What was loaded and prepared (mesh, adjacency, convexification), kept for the session.
    std::unique_ptr<Pipeline> pipeline;
    PreparedSort sort;                // the mesh (maybe convexified) and adjacency sorted
    std::vector<std::string> arrays;  // point and cell arrays that can be the scalar
    std::string scalar_name;          // in use ("(constant)" when the mesh has none)
    std::vector<float> scalar;        // one per sort.mesh() point (log10 of it with log_scale)
    bool log_scale = false;           // quick.log_scale: `scalar` and `edit` in decades
    TransferEdit edit;
    double longest_edge = 1;
    OpaqueSet opaque;
    // The domain for flow volumes: only when the mesh has a 3-component point array. A flow
    // volume to show at start is scene.flow_volume (the scene's key or the command line's).
    std::unique_ptr<FlowDomain> flow;
    // How the picture is made at start (resolve_method: --method or the scene's `method` key)
    // and the particle-based modes' settings.
    ViewMethod method = ViewMethod::kProjectedTetrahedra;
    PbvrSettings pbvr;
    // A scene of several volumes: each one (the fields above then hold volume 0, prepared for
    // the GL renderer, which does not draw it: cells of intersecting meshes have no order).
    // Empty for one volume.
    std::vector<FusedVolume> fused;
    FusedMode fused_mode = FusedMode::kProgressive;  // how they are drawn at start
    // What the user should know of the quick look's choices (the array shown when none was
    // named, values <= 0 under --log, ...): the caller prints them.
    std::vector<std::string> notes;

    SceneVolume& volume() { return scene.volumes[0]; }
    const SceneVolume& volume() const { return scene.volumes[0]; }
};

// Loads everything through the pipeline, as `tetrender render` does. Errors as it words them
// (read_scene, loading, an unknown array listing the available ones, a flow volume's vectors
// that are no vector array of the mesh; with several volumes, prefixed "volume i: "). A scene
// of several volumes fills `fused` (each volume's mesh, scalar, edit; --colormap, --opacity and
// --unit-distance apply to each); kUnsupported for a flow volume with several volumes.
Result<ViewerScene> load_viewer_scene(const ViewerOptions& options);

// Switches to array `name` (a point or cell array of the mesh, magnitude of vectors): the
// scalar and the transfer function's range follow, opacity points keep their relative places.
Status select_scalar(ViewerScene& scene, const std::string& name);

// Switches fused volume `volume` to array `name`, as select_scalar does for one volume.
Status select_fused_scalar(ViewerScene& scene, std::size_t volume, const std::string& name);

// The transfer function of `edit`.
Result<TransferFunction> make_transfer_function(const TransferEdit& edit);

// The initial opacity points: a ramp from floor * max_opacity at lo to `max_opacity` at hi.
std::vector<OpacityPoint> ramp_opacity(double lo, double hi, double max_opacity,
                                       double floor = 0.0);

}  // namespace tr::viewer
