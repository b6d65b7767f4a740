#pragma once
// The viewer's flow volumes, without GL: growing off the frame's thread, so that the window
// stays responsive while it grows (the domain, seeds and growth: pipeline/flow_volume_scene.h).

#include <core/result.h>
#include <flowvol/flow_volume.h>
#include <pipeline/flow_volume_scene.h>
#include <pipeline/scene.h>

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
