#include <core/stopwatch.h>
#include <flowtex/frame_loop.h>

#include <chrono>

namespace tr {

Result<FrameLoopTimes> run_frame_loop(int last, bool draw_every_frame,
                                      const std::function<void()>& advance,
                                      const std::function<Status(int frame)>& draw) {
    FrameLoopTimes times;
    for (int k = 0; k <= last; ++k) {
        if (k > 0) {
            const auto start = std::chrono::steady_clock::now();
            advance();
            times.advance_ms += ms_since(start);
        }
        if (!draw_every_frame && k < last) continue;
        const auto start = std::chrono::steady_clock::now();
        TR_TRY_STATUS(draw(k));
        times.draw_ms += ms_since(start);
        ++times.drawn;
    }
    return times;
}

}  // namespace tr
