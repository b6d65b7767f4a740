#pragma once
// Scene files (../shared/spec/scene.md, implemented exactly): one JSON object saying everything
// needed to render one image of one mesh, or of several volumes in one space, and how (the
// method). Unknown keys, wrong types and missing required keys are errors naming the JSON path
// ("scene.json: error: $.camera.position: expected ...").

#include <core/camera.h>
#include <core/result.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>
#include <project/transfer_function.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace tr {

// Opaque geometry drawn before the volume (an extension of the spec, docs/scene-file.md):
// a surface file (.stl .ply .obj .off .poly, relative to the scene file), a side set of a
// volume's mesh (Exodus), or that mesh's own boundary, with a colour.
struct OpaqueSpec {
    std::filesystem::path file;  // empty when side_set is used
    std::string side_set;        // a side-set name, or "*" for all of them
    bool boundary = false;       // the mesh's own boundary faces
    std::size_t volume = 0;      // whose side set or boundary (an index into Scene::volumes)
    std::shared_ptr<const SurfaceMesh> surface;  // set by code instead of a file (not written)
    Vec3 color{0.8, 0.8, 0.8};
};

// What a user left for the data to choose (`tetrender flowvol` without --seed-center,
// --seed-size or --dt; a scene's flow_volume without seed_center, seed_size or dt):
// pipeline/flow_volume_scene.h choose_flow_spec.
struct FlowSpecChoices {
    bool seed_center = false;
    bool seed_size = false;
    bool dt = false;
    bool any() const { return seed_center || seed_size || dt; }
};

// A flow volume grown from the scene's mesh and drawn instead of its scalar (an extension of
// the spec, docs/scene-file.md; flowvol/flow_volume.h says what each value does).
struct FlowVolumeSpec {
    std::string vectors;  // a 3-component point array of the mesh
    Vec3 seed_center{0.0};
    double seed_width = 1.0, seed_height = 1.0;
    int seed_resolution = 32;
    std::optional<Vec3> seed_normal;  // default: the flow at the centre
    int steps = 50;
    double dt = 0.05;
    bool compressible = false;
    double split_threshold = 2.0;  // 0: no adaptive subdivision
    bool unsteady = false;         // interpolate over all the mesh file's time steps
    std::optional<double> start_time;
    Vec3 color{0.85, 0.9, 1.0};           // the dye's glow
    double opacity = 0.3;                 // of a slab of full concentration, unit_distance thick
    std::optional<double> unit_distance;  // default: the mesh's bounding diagonal / 30
    bool context = false;                 // the domain's boundary as a faint veil
    // Not a scene-file key (`tetrender flowvol` sets it): when the grown dye covers less than
    // half the picture's width and height, the camera is turned to the dye's own extent, from
    // the same direction (pipeline/flow_volume_scene.h dye_camera).
    bool fit_camera_to_dye = false;
    // The values above the data chooses when the flow is grown (resolve_flow_spec); their
    // values here are placeholders until then.
    FlowSpecChoices choose;
};

// One volume of a scene: a mesh, the array rendered and its transfer function. A scene with
// the spec's top-level keys has one; a scene with `volumes` has 1 to kMaxVolumes.
struct SceneVolume {
    std::filesystem::path mesh;  // resolved against the scene file's folder
    // Set by code that hands a mesh over without a file, either as a simulation has it or
    // already tetrahedral: used instead of reading `mesh` (which then only names it in messages).
    std::shared_ptr<const UnstructuredMesh> data;
    std::shared_ptr<const TetMesh> tets;
    std::string scalar;
    int component = -1;  // -1: magnitude (or the only component); >= 0: that component
    int time_step = 0;
    TransferFunction transfer_function;
    // Whether the transfer function's points were spread evenly in log10 of the scalar (a quick
    // look's --log, project/transfer_function.h log_scaled): read by the legend for its axis.
    // Not a scene-file key (scene.md has none; the transfer function alone renders the same):
    // false for a scene read from a file.
    bool log_scale = false;
};

// A list of lists of numbers: a method key such as texture-advection's "slices"
// ([[px, py, pz, nx, ny, nz], ...]).
using NumberLists = std::vector<std::vector<double>>;

// A method's own keys (spec: "a method may take further keys of its own"), checked by the
// method that takes them.
using MethodOption = std::variant<bool, std::int64_t, double, std::string, NumberLists>;

// How the picture is made (spec section "Method"). The name is checked against the methods
// this build has when the scene is rendered (pipeline/), not here.
struct MethodSpec {
    std::string name = "projected-tetrahedra";
    std::optional<int> repetitions;               // >= 1; the method's default when absent
    std::optional<std::int64_t> seed;             // the method's default when absent
    std::map<std::string, MethodOption> options;  // every other key, e.g. pbvr-image's "depth"
};

inline constexpr const char* kDefaultMethod = "projected-tetrahedra";
inline constexpr std::size_t kMaxVolumes = 16;

struct Scene {
    std::vector<SceneVolume> volumes;  // at least one
    bool volumes_key = false;          // written with `volumes` rather than top-level keys
    Camera camera;
    int width = 512;
    int height = 512;
    Vec3 background{0.0};
    std::vector<OpaqueSpec> opaque;
    std::optional<FlowVolumeSpec> flow_volume;  // grown from volume 0
    std::optional<MethodSpec> method;           // absent: projected-tetrahedra
    std::string source;  // the file it was read from, for messages ("" when made in code)

    // The method's name (kDefaultMethod when the scene names none).
    const std::string& method_name() const;
};

// Limits on what a scene may ask for.
inline constexpr int kMaxImageSide = 16384;

// Reads and validates a scene file. Errors: missing or unreadable file, malformed JSON (with
// line and column), unknown keys, wrong types, out-of-range values (an image side outside
// [1, kMaxImageSide], a camera whose position equals its focal point or whose view_up is
// parallel to the view direction, a view angle outside (0, 180), repetitions < 1), both or
// neither of the top-level volume keys and `volumes`, `volumes` empty or longer than
// kMaxVolumes, an opaque entry naming a volume that is not there.
Result<Scene> read_scene(const std::filesystem::path& path);

// Parses scene JSON text; `base_dir` resolves the mesh path; `name` is used in errors.
Result<Scene> parse_scene(const std::string& text, const std::filesystem::path& base_dir,
                          const std::string& name);

// Writes `scene` as a scene file (mesh paths written relative to the file's folder when
// possible; top-level keys for one volume unless `volumes_key`). Written to a temporary file and
// renamed. Errors: kIo; kInvalidArgument for a scene with no volume.
Status write_scene(const Scene& scene, const std::filesystem::path& path);

}  // namespace tr
