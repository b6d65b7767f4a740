#pragma once
// What the viewer's background workers (pbvr_worker.h, fused_worker.h, animation_worker.h)
// share: one worker thread, the newest request waiting for it (a newer one replaces it, with a
// larger id) and the stop flag, under one mutex that also guards the worker's own state (its
// latest picture, ...); `wake_` wakes the worker, `done_` those waiting for a picture.
//
// A worker derives from it, starts `thread_` at the end of its constructor (when the rest of it
// is ready) and calls stop_and_join() first in its destructor (before its members go).

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace tr::viewer {

template <class Request>
class RequestWorker {
  protected:
    RequestWorker() = default;
    ~RequestWorker() = default;

    // Queues `request` in place of any not yet taken; returns its id.
    std::uint64_t post(Request request) {
        std::uint64_t id;
        {
            std::lock_guard lock(mutex_);
            id = ++next_id_;
            pending_.emplace(std::move(request), id);
        }
        wake_.notify_all();
        return id;
    }

    // Tells the worker thread to stop and waits for it.
    void stop_and_join() {
        {
            std::lock_guard lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }

    mutable std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::optional<std::pair<Request, std::uint64_t>> pending_;  // the request and its id
    std::uint64_t next_id_ = 0;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace tr::viewer
