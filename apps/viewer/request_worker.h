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
// share: the pipeline's progressive render they draw with, the worker thread's loop (a request
// begun, then drawn a step at a time), a target of repetitions where accumulation stops, and the
// latest picture, which callers read or wait for.

#include <apps/viewer/view_method.h>
#include <pipeline/progressive_render.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

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
    // `opaque`, `options`: the progressive render's (pipeline/progressive_render.h);
    // `out_of_memory`: the error a request ends with when drawing it runs out of memory.
    AccumulatingWorker(int target, std::vector<OpaqueSurface> opaque, ProgressiveOptions options,
                       std::string out_of_memory)
        : render_(std::move(opaque), std::move(options)),
          out_of_memory_(std::move(out_of_memory)),
          target_(std::clamp(target, 1, kMaxRepetitions)) {}
    ~AccumulatingWorker() = default;

    // The request being drawn (worker thread only).
    struct Job {
        Request request;
        std::uint64_t id = 0;
        bool fresh = false;   // begin() not yet called
        bool active = false;  // a request has begun
        std::string error;    // a step failed: nothing more for this request
    };

    // The worker thread's body: waits for a new request, or for work at the target, then begins
    // a new request, draws one step of it and publishes the picture; running out of memory ends
    // the request (its kept particles and shaders dropped). The derived class starts it.
    void run() {
        Job job;
        for (;;) {
            int target = 0;
            {
                std::unique_lock lock(this->mutex_);
                this->wake_.wait(lock, [&] {
                    return this->stop_ || this->pending_.has_value() || has_work(job, target_);
                });
                if (!this->stop_ && !this->pending_) wait_before_step(lock, job);
                if (this->stop_) return;
                if (this->pending_) {
                    job.request = std::move(this->pending_->first);
                    job.id = this->pending_->second;
                    job.fresh = true;
                    this->pending_.reset();
                }
                target = target_;
            }
            try {
                if (job.fresh) {
                    job.fresh = false;
                    job.active = true;
                    job.error.clear();
                    begin(job.request);
                }
                step(job, target);
            } catch (const std::bad_alloc&) {
                render_.release_memory();
                job.error = out_of_memory_;
            }
            publish(job);
        }
    }

    // Whether `frame` has nothing more to draw at `target` repetitions.
    virtual bool finished_at(const Frame& frame, int target) const = 0;
    // Starts `request`'s picture (render_.begin).
    virtual void begin(const Request& request) = 0;
    // Draws one step of the job towards `target` repetitions, into render_ (a failure: job.error).
    virtual void step(Job& job, int target) = 0;
    // A frame with the derived class's own fields for the job (its method, mode).
    virtual Frame frame_of(const Job& job) const = 0;
    // Under the lock, before a step of a job that has work: may wait (on wake_) for a new request.
    virtual void wait_before_step(std::unique_lock<std::mutex>& /*lock*/, const Job& /*job*/) {}

    ProgressiveRender render_;                         // worker thread only
    std::chrono::steady_clock::time_point published_;  // worker thread only: the last picture

  private:
    // The job's frame so far, without its picture.
    Frame frame_so_far(const Job& job) const {
        Frame frame = frame_of(job);
        static_cast<ProgressiveStats&>(frame) = render_.stats();
        frame.request_id = job.id;
        frame.error = job.error;
        return frame;
    }

    bool has_work(const Job& job, int target) const {
        return job.active && job.error.empty() && !finished_at(frame_so_far(job), target);
    }

    // Publishes render_'s picture and stats so far as the job's frame; wakes those waiting.
    void publish(const Job& job) {
        published_ = std::chrono::steady_clock::now();
        Frame frame = frame_so_far(job);
        frame.image = render_.picture();
        {
            std::lock_guard lock(this->mutex_);
            frame.finished = finished_at(frame, target_);
            latest_ = std::move(frame);
        }
        this->done_.notify_all();
        if (on_frame_) on_frame_();
    }

    const std::string out_of_memory_;

  protected:
    std::function<void()> on_frame_;
    std::optional<Frame> latest_;  // under mutex_
    int target_;                   // under mutex_
};

}  // namespace tr::viewer
