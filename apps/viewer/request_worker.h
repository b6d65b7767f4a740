#pragma once
// What the viewer's background workers (pbvr_worker.h, fused_worker.h, animation_worker.h)
// share: one worker thread, the newest request waiting for it (a newer one replaces it, with a
// larger id) and the stop flag, under one mutex that also guards the worker's own state (its
// latest picture, ...); `wake_` wakes the worker, `done_` those waiting for a picture.
//
// A worker derives from it, starts `thread_` at the end of its constructor (when the rest of it
// is ready) and calls stop_and_join() first in its destructor (before its members go).
//
// AccumulatingWorker adds what the particle and fused workers (pbvr_worker.h, fused_worker.h)
// share: a target of repetitions where accumulation stops, and the latest picture, which callers
// read or wait for.

#include <apps/viewer/view_method.h>
#include <pipeline/progressive_render.h>

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <functional>
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

// Frame: the picture so far of one request, a ProgressiveStats with `image`, `request_id`,
// `finished` (nothing more to draw until a new request or target) and `error`.
template <class Request, class Frame>
class AccumulatingWorker : protected RequestWorker<Request> {
  public:
    // wait_for's `repetitions` that waits for the request's last picture.
    static constexpr int kWaitFinished = kMaxRepetitions + 1;

    // Where accumulation stops (clamped to [1, kMaxRepetitions]); raising it resumes a finished
    // accumulation, lowering it finishes it after the current batch. No restart.
    void set_target(int repetitions) {
        {
            std::lock_guard lock(this->mutex_);
            target_ = std::clamp(repetitions, 1, kMaxRepetitions);
            if (latest_) latest_->finished = finished_at(*latest_, target_);
        }
        this->wake_.notify_all();
        this->done_.notify_all();
    }

    int target() const {
        std::lock_guard lock(this->mutex_);
        return target_;
    }

    // The latest picture, if any (of the latest request or an older one).
    std::optional<Frame> latest() const {
        std::lock_guard lock(this->mutex_);
        return latest_;
    }

    // Blocks until the frame of `request_id` has at least `repetitions` (or is exact, finished or
    // failed), or a later request has a frame; returns that frame.
    Frame wait_for(std::uint64_t request_id, int repetitions) {
        std::unique_lock lock(this->mutex_);
        this->done_.wait(lock, [&] {
            if (!latest_) return false;
            const Frame& f = *latest_;
            if (f.request_id != request_id) return f.request_id > request_id;
            if (f.finished || !f.error.empty()) return true;
            return repetitions < kWaitFinished && (f.exact || f.repetitions >= repetitions);
        });
        return *latest_;
    }

    // Called from the worker thread after each picture is published (e.g. glfwPostEmptyEvent, to
    // wake the window loop). Set before the first request.
    void set_on_frame(std::function<void()> on_frame) { on_frame_ = std::move(on_frame); }

  protected:
    explicit AccumulatingWorker(int target) : target_(std::clamp(target, 1, kMaxRepetitions)) {}
    ~AccumulatingWorker() = default;

    // Whether `frame` has nothing more to draw at `target` repetitions.
    virtual bool finished_at(const Frame& frame, int target) const = 0;

    // Publishes `render`'s picture and stats so far as request `id`'s `frame` (its own fields set
    // by the caller), with `error` (empty: none); wakes those waiting.
    void publish_frame(const ProgressiveRender& render, std::uint64_t id, std::string error,
                       Frame frame) {
        static_cast<ProgressiveStats&>(frame) = render.stats();
        frame.image = render.picture();
        frame.request_id = id;
        frame.error = std::move(error);
        {
            std::lock_guard lock(this->mutex_);
            frame.finished = finished_at(frame, target_);
            latest_ = std::move(frame);
        }
        this->done_.notify_all();
        if (on_frame_) on_frame_();
    }

    std::function<void()> on_frame_;
    std::optional<Frame> latest_;  // under mutex_
    int target_;                   // under mutex_
};

}  // namespace tr::viewer
