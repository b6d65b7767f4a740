#pragma once
// The viewer's flow volumes, without GL: the domain the dye grows through (the mesh as loaded:
// the sort's mesh may be convexified), a default seed for meshes without a scene spec, and
// growing off the frame's thread, so that the window stays responsive while it grows.

#include <apps/cli_common.h>
#include <core/result.h>
#include <flowvol/flow_volume.h>
#include <flowvol/point_locator.h>
#include <flowvol/velocity_field.h>
#include <mesh/face_adjacency.h>
#include <project/scene.h>
#include <project/transfer_function.h>

#include <array>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace tr::viewer {

// What a flow volume grows through. Kept only when the mesh has a 3-component point array.
struct FlowDomain {
    std::string path;         // the mesh file (unsteady velocities read its time steps)
    apps::LoadedMesh loaded;  // tets as loaded; input holds only time_values and time_step
    FaceAdjacency adjacency;  // of loaded.tets
    std::vector<std::string> vector_arrays;  // its 3-component point arrays
};

// The 3-component point arrays of `mesh`.
std::vector<std::string> vector_arrays(const TetMesh& mesh);

// A seed for a mesh without a spec: the first vector array, the polygon at the bounds' centre,
// an eighth of the diagonal wide and high, 16 quads a side, 50 steps of a dt that carries the
// dye at the mean speed over half the diagonal.
FlowVolumeSpec default_flow_spec(const FlowDomain& domain);

// Checks a spec against the domain before growing: a vector array of it. Error kNotFound listing
// the vector arrays.
Status check_flow_spec(const FlowDomain& domain, const FlowVolumeSpec& spec);

// The dye's transfer function as `tetrender render` makes it (apps/flowvol_render.cpp): one glow
// colour, opacity by concentration up to spec.opacity at 1, unit distance spec.unit_distance or
// the domain's diagonal / 30.
TransferFunction dye_transfer_function(const FlowVolumeSpec& spec, const TetMesh& domain);

// The dye polygon's corners where grow_flow_volume places it: normal the spec's or the flow at
// the centre (the loaded time step's), first axis (width) across it. Nothing when the centre is
// outside the mesh or the flow there is zero. `locator` is over domain.loaded.tets. Cost: one
// point location.
std::optional<std::array<Vec3, 4>> seed_polygon(const FlowDomain& domain,
                                                const PointLocator& locator,
                                                const FlowVolumeSpec& spec);

struct GrownFlowVolume {
    FlowVolumeSpec spec;               // what it was grown from
    std::uint64_t id = 0;              // the request it answers
    std::optional<FlowVolume> volume;  // empty on error
    std::optional<Error> error;        // why growth failed
    std::vector<float> concentration;  // one per point of volume->mesh (1 when absent)
    double longest_edge = 1;           // of volume->mesh
    double grow_ms = 0;
};

// Grows `spec` through `domain` now (on the calling thread). The velocity is read for it (an
// unsteady one reads every time step of the file).
GrownFlowVolume grow_now(const FlowDomain& domain, const FlowVolumeSpec& spec,
                         std::uint64_t id = 0);

// Grows flow volumes in a worker thread, newest request first: a request replaces one not yet
// started; a result that a newer request supersedes is still handed out (take() says its id).
class FlowGrower {
  public:
    // `domain` must outlive the grower.
    explicit FlowGrower(const FlowDomain& domain);
    ~FlowGrower();  // waits for a growth in progress
    FlowGrower(const FlowGrower&) = delete;
    FlowGrower& operator=(const FlowGrower&) = delete;

    void request(const FlowVolumeSpec& spec, std::uint64_t id);
    // A finished result not taken yet, if any.
    std::shared_ptr<GrownFlowVolume> take();
    // Whether a request is pending or growing, or a result waits to be taken.
    bool busy() const;
    // Blocks until the result for `id` (or a later request) is finished, and takes it.
    std::shared_ptr<GrownFlowVolume> wait_for(std::uint64_t id);

  private:
    void run();

    const FlowDomain& domain_;
    mutable std::mutex mutex_;
    std::condition_variable wake_, done_;
    struct Request {
        FlowVolumeSpec spec;
        std::uint64_t id = 0;
    };
    std::optional<Request> pending_;
    bool growing_ = false;
    std::shared_ptr<GrownFlowVolume> finished_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace tr::viewer
