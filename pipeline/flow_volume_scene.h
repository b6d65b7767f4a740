#pragma once
// Flow volumes from a scene (the `flow_volume` key, docs/scene-file.md): the domain the dye
// grows through, the velocity (steady, or over all of a file's time steps), the seed and
// options a FlowVolumeSpec describes, the dye's transfer function, and growing it.

#include <core/result.h>
#include <flowvol/flow_volume.h>
#include <flowvol/point_locator.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/scene.h>
#include <project/transfer_function.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tr {

// What a flow volume grows through: the mesh as loaded (never convexified) and its adjacency.
struct FlowDomain {
    std::string path;  // the mesh file (an unsteady velocity reads its time steps); "" in memory
    std::shared_ptr<const LoadedMesh> loaded;
    std::shared_ptr<const FaceAdjacency> adjacency;  // of loaded->tets
    std::vector<std::string> vector_arrays;          // its 3-component point arrays
    // Set when the file is a planar 2D mesh taken as its slab (mesh/planar_slab.h): the plane
    // a flow over it is drawn on.
    std::optional<PlanarSheet> planar;

    const TetMesh& mesh() const { return loaded->tets; }
};

// What a flow over a planar 2D mesh's slab is, in one line for the user: the plane, its cells
// split into triangles with the velocity linear on each and made tangent to the plane.
std::string planar_flow_note(const PlanarSheet& sheet);

// The 3-component point arrays of `mesh`.
std::vector<std::string> vector_arrays(const TetMesh& mesh);

// A seed for a mesh without a spec (the viewer's flow panel): the first vector array, 16 quads
// a side, 50 steps, and the seed, its size and dt as choose_flow_spec (below) chooses them; for
// a flow that is zero everywhere, the seed at the bounds' centre and dt 0.05.
FlowVolumeSpec default_flow_spec(const FlowDomain& domain);

// The share of the domain's bounding diagonal the dye's front travels over its steps when dt is
// chosen (at the speed where it is released).
inline constexpr double kDyeTravel = 0.4;

// Fills what `choose` names from spec.vectors at the loaded step: the seed's centre where the
// flow is fastest (the centroid of a real tet at the mesh point of the 99.9th percentile of
// speed, robust to a few spikes: in a channel or a room, near the inlet); its size an eighth of
// the domain's diagonal a side; dt so that the front, at the speed at the seed's centre (with a
// given centre: at the point nearest it), travels kDyeTravel of the diagonal in spec.steps
// layers. `notes` receives one line per choice, with its value. Errors: check_flow_spec's; no
// point with a finite, non-zero speed ("the flow is zero everywhere"). Cost: O(points + tets).
Result<FlowVolumeSpec> choose_flow_spec(const FlowDomain& domain, FlowVolumeSpec spec,
                                        const FlowSpecChoices& choose,
                                        std::vector<std::string>* notes = nullptr);

// spec with what spec.choose names chosen by choose_flow_spec (and spec.choose cleared); spec
// itself when it names nothing. What a scene's flow_volume without seed_center, seed_size or
// dt, the viewer's --flowvol-vectors and Python's flow_volume take. Errors: choose_flow_spec's.
Result<FlowVolumeSpec> resolve_flow_spec(const FlowDomain& domain, const FlowVolumeSpec& spec,
                                         std::vector<std::string>* notes = nullptr);

// A camera framing the dye `dye` from `camera`'s direction (quick_look.h fitting_camera, the
// same view angle) when the dye covers less than half of `width` x `height` in both directions
// from `camera`; nothing when it covers more, is empty, lies partly behind the eye, or the
// camera is orthographic.
std::optional<Camera> dye_camera(const TetMesh& dye, const Camera& camera, int width, int height);

// Checks a spec against the domain before growing: a vector array of it. Error kNotFound
// listing the vector arrays.
Status check_flow_spec(const FlowDomain& domain, const FlowVolumeSpec& spec);

// The dye's transfer function: one glow colour, opacity by concentration up to spec.opacity at
// 1, unit distance spec.unit_distance or the domain's diagonal / 30.
TransferFunction dye_transfer_function(const FlowVolumeSpec& spec, const TetMesh& domain);

// The seed polygon and growth options a spec describes. `times` are the file's time values
// and `time_step` the one loaded: an unsteady spec without a start time starts there.
DyeSeed dye_seed(const FlowVolumeSpec& spec);
FlowVolumeOptions flow_volume_options(const FlowVolumeSpec& spec, const std::vector<double>& times,
                                      int time_step);

// The dye polygon's corners where grow_flow_volume places it: normal the spec's or the flow at
// the centre (the loaded time step's), first axis (width) across it. Nothing when the centre
// is outside the mesh or the flow there is zero. `locator` is over domain.mesh(). Cost: one
// point location.
std::optional<std::array<Vec3, 4>> seed_polygon(const FlowDomain& domain,
                                                const PointLocator& locator,
                                                const FlowVolumeSpec& spec);

// The array `vectors` of the domain as a velocity: steady, or with `unsteady` the array at
// every time step of the domain's file (.pvd, Exodus), linear in time. Errors: no such array
// (the message lists the vector arrays), `unsteady` on a mesh with one time step or handed
// over in memory, a time step whose mesh differs from the first. Cost: one read per time step.
Result<VelocityField> load_velocity(const FlowDomain& domain, const std::string& vectors,
                                    bool unsteady, const LoadOptions& load = {});

// Grows the flow volume `spec` describes through `domain`. Errors: those of check_flow_spec,
// load_velocity and grow_flow_volume, with the path in `where`; kInternal for an exception
// (out of memory). Cost: grow_flow_volume's.
Result<FlowVolume> grow_scene_flow_volume(const FlowDomain& domain, const FlowVolumeSpec& spec,
                                          const ProgressFn& progress = {});

}  // namespace tr
