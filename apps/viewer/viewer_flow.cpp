#include <apps/viewer/viewer_flow.h>
#include <core/stopwatch.h>
#include <project/cpu_renderer.h>

#include <chrono>
#include <cmath>
#include <exception>

namespace tr::viewer {

GrownFlowVolume grow_now(const FlowDomain& domain, const FlowVolumeSpec& requested,
                         std::uint64_t id) {
    GrownFlowVolume grown;
    grown.spec = requested;
    grown.id = id;
    const auto start = std::chrono::steady_clock::now();
    auto fv = grow_scene_flow_volume(domain, requested);
    grown.grow_ms = ms_since(start);
    if (!fv.ok()) {
        grown.error = fv.error();
        return grown;
    }
    grown.volume = std::move(fv).value();
    const TetMesh& mesh = grown.volume->mesh;
    grown.concentration.assign(mesh.num_points(), 1.0f);
    if (const Field* c = find_field(mesh.point_fields(), "concentration")) {
        for (std::size_t p = 0; p < grown.concentration.size(); ++p)
            grown.concentration[p] = static_cast<float>(c->get(p));
    }
    grown.longest_edge = longest_edge(mesh);
    return grown;
}

FlowGrower::FlowGrower(const FlowDomain& domain) : domain_(domain), thread_([this] { run(); }) {}

FlowGrower::~FlowGrower() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void FlowGrower::request(const FlowVolumeSpec& spec, std::uint64_t id) {
    {
        std::lock_guard lock(mutex_);
        pending_ = Request{spec, id};
    }
    wake_.notify_all();
}

std::shared_ptr<GrownFlowVolume> FlowGrower::take() {
    std::lock_guard lock(mutex_);
    return std::move(finished_);
}

bool FlowGrower::busy() const {
    std::lock_guard lock(mutex_);
    return growing_ || pending_.has_value() || finished_ != nullptr;
}

std::shared_ptr<GrownFlowVolume> FlowGrower::wait_for(std::uint64_t id) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return finished_ && finished_->id >= id; });
    return std::move(finished_);
}

void FlowGrower::run() {
    for (;;) {
        Request request;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            request = std::move(*pending_);
            pending_.reset();
            growing_ = true;
        }
        auto grown = std::make_shared<GrownFlowVolume>(grow_now(domain_, request.spec, request.id));
        {
            std::lock_guard lock(mutex_);
            finished_ = std::move(grown);
            growing_ = false;
        }
        done_.notify_all();
    }
}

}  // namespace tr::viewer
