#include <apps/viewer/sort_worker.h>

namespace tr::viewer {

SortWorker::SortWorker(const TetMesh& mesh, const FaceAdjacency& adjacency)
    : mesh_(mesh), adjacency_(adjacency), thread_([this] { run(); }) {}

SortWorker::~SortWorker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void SortWorker::request(const SortView& view, SortMethod method, std::uint64_t view_id) {
    {
        std::lock_guard lock(mutex_);
        if (latest_ && latest_->view_id == view_id) return;
        pending_ = Request{view, method, view_id};
    }
    wake_.notify_all();
}

std::optional<SortedOrder> SortWorker::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

SortedOrder SortWorker::wait_for(std::uint64_t view_id) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return latest_ && latest_->view_id >= view_id; });
    return *latest_;
}

void SortWorker::run() {
    VisibilitySorter sorter;
    for (;;) {
        std::optional<Request> request;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
            if (stop_) return;
            request = pending_;
            pending_.reset();
        }
        auto order = std::make_shared<std::vector<CellId>>();
        const SortStats stats =
            sorter.sort(mesh_, adjacency_, request->view, request->method, *order);
        {
            std::lock_guard lock(mutex_);
            latest_ = SortedOrder{std::move(order), request->view_id, stats};
        }
        done_.notify_all();
    }
}

}  // namespace tr::viewer
