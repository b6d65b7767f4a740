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

    const TetMesh& mesh() const { return loaded->tets; }
};

// The 3-component point arrays of `mesh`.
std::vector<std::string> vector_arrays(const TetMesh& mesh);

// A seed for a mesh without a spec: the first vector array, the polygon at the bounds' centre,
// an eighth of the diagonal wide and high, 16 quads a side, 50 steps of a dt that carries the
// dye at the mean speed over half the diagonal.
FlowVolumeSpec default_flow_spec(const FlowDomain& domain);

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
