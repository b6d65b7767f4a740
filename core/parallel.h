#pragma once
// The one parallel facade: parallel_for over index ranges and the thread count.
// TBB underneath when built with TETRENDER_WITH_TBB, otherwise serial. Modules never start
// threads themselves.

#include <cstddef>
#include <functional>

namespace tr {

// Number of worker threads parallel_for may use (>= 1). Defaults to the hardware's.
int thread_count();

// Limits the worker threads to n (n <= 0: back to the hardware's count). Affects later calls
// in this process.
void set_thread_count(int n);

// Calls body(begin_chunk, end_chunk) on disjoint chunks that cover [begin, end), chunks of at
// most `grain` indices (grain >= 1), possibly concurrently. Returns when all are done. The
// body must not throw.
void parallel_for_chunks(std::size_t begin, std::size_t end, std::size_t grain,
                         const std::function<void(std::size_t, std::size_t)>& body);

// Calls body(i) for every i in [begin, end), possibly concurrently.
template <class Body>
void parallel_for(std::size_t begin, std::size_t end, std::size_t grain, Body&& body) {
    parallel_for_chunks(begin, end, grain, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) body(i);
    });
}

}  // namespace tr
