#pragma once
// Private: a rank's local step with its exceptions turned into errors. A rank must never leave
// the others waiting in the next collective, so every step between two collectives returns a
// Status (or Result) that MpiWorld::agree then shares.

#include <core/result.h>

#include <exception>
#include <new>
#include <string>

namespace tr::distributed_detail {

template <class F>
auto guarded(F&& step) -> decltype(step()) {
    try {
        return step();
    } catch (const std::bad_alloc&) {
        return make_error(ErrorCode::kIo, "out of memory");
    } catch (const std::exception& e) {
        return make_error(ErrorCode::kInternal, std::string("unexpected failure: ") + e.what());
    }
}

}  // namespace tr::distributed_detail
