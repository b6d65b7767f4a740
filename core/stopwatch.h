#pragma once
// Wall-clock time for the stats every stage reports: the steady clock, read in milliseconds or
// seconds since a start.

#include <chrono>

namespace tr {

using SteadyClock = std::chrono::steady_clock;

// Milliseconds since `start`.
inline double ms_since(SteadyClock::time_point start) {
    return std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count();
}

// Seconds since `start`.
inline double seconds_since(SteadyClock::time_point start) {
    return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace tr
