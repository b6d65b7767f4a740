#pragma once
// Scene files (../shared/spec/scene.md, implemented exactly): one JSON object saying everything
// needed to render one image of one mesh. Unknown keys, wrong types and missing required keys
// are errors naming the JSON path ("scene.json: error: $.camera.position: expected ...").

#include <core/camera.h>
#include <core/result.h>
#include <project/transfer_function.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tr {

// Opaque geometry drawn before the volume (an extension of the spec, docs/scene-file.md):
// a surface file (.stl .ply .obj .off .poly, relative to the scene file), a side set of the
// mesh (Exodus), or the mesh's own boundary, with a colour.
struct OpaqueSpec {
    std::filesystem::path file;  // empty when side_set is used
    std::string side_set;        // a side-set name, or "*" for all of them
    bool boundary = false;       // the mesh's own boundary faces
    Vec3 color{0.8, 0.8, 0.8};
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
};

struct Scene {
    std::filesystem::path mesh;  // resolved against the scene file's folder
    std::string scalar;
    int component = -1;  // -1: magnitude (or the only component); >= 0: that component
    TransferFunction transfer_function;
    Camera camera;
    int width = 512;
    int height = 512;
    Vec3 background{0.0};
    int time_step = 0;
    std::vector<OpaqueSpec> opaque;
    std::optional<FlowVolumeSpec> flow_volume;
};

// Limits on what a scene may ask for.
inline constexpr int kMaxImageSide = 16384;

// Reads and validates a scene file. Errors: missing or unreadable file, malformed JSON (with
// line and column), unknown keys, wrong types, out-of-range values (an image side outside
// [1, kMaxImageSide], a camera whose position equals its focal point or whose view_up is
// parallel to the view direction, a view angle outside (0, 180)).
Result<Scene> read_scene(const std::filesystem::path& path);

// Parses scene JSON text; `base_dir` resolves the mesh path; `name` is used in errors.
Result<Scene> parse_scene(const std::string& text, const std::filesystem::path& base_dir,
                          const std::string& name);

// Writes `scene` as a scene file (mesh path written relative to the file's folder when
// possible). Written to a temporary file and renamed.
Status write_scene(const Scene& scene, const std::filesystem::path& path);

}  // namespace tr
