#include <core/config.h>
#include <core/parallel.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#if TETRENDER_HAS_TBB
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#endif

namespace tr {
namespace {

int hardware_threads() {
    unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : static_cast<int>(n);
}

std::atomic<int> g_thread_count{0};  // 0: the hardware's

#if TETRENDER_HAS_TBB
std::mutex g_control_mutex;
std::unique_ptr<tbb::global_control> g_control;
#endif

}  // namespace

int thread_count() {
    int n = g_thread_count.load();
    return n > 0 ? n : hardware_threads();
}

void set_thread_count(int n) {
    g_thread_count.store(n > 0 ? n : 0);
#if TETRENDER_HAS_TBB
    std::lock_guard<std::mutex> lock(g_control_mutex);
    g_control.reset();
    if (n > 0) {
        g_control = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
    }
#endif
}

void parallel_for_chunks(std::size_t begin, std::size_t end, std::size_t grain,
                         const std::function<void(std::size_t, std::size_t)>& body) {
    if (end <= begin) return;
    grain = std::max<std::size_t>(grain, 1);
#if TETRENDER_HAS_TBB
    if (thread_count() > 1 && end - begin > grain) {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(begin, end, grain),
            [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
        return;
    }
#endif
    for (std::size_t b = begin; b < end; b += grain) body(b, std::min(end, b + grain));
}

}  // namespace tr
