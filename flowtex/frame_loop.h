#pragma once
// The frame loop of every animated flow texture (`tetrender advect`, `tetrender spotnoise`, the
// scene methods texture-advection and spot-noise, and so the viewer's animation): frame 0 as
// made, then for each frame 1 .. last one `advance` of the flow's state; `draw(k)` for every
// frame, or, when only the last is wanted, for it alone.

#include <core/result.h>

#include <functional>

namespace tr {

struct FrameLoopTimes {
    double advance_ms = 0;  // summed over the advances
    double draw_ms = 0;     // summed over the draws
    int drawn = 0;          // frames drawn
};

// Runs frames 0 .. last. Errors: the first of draw's, which ends the loop.
Result<FrameLoopTimes> run_frame_loop(int last, bool draw_every_frame,
                                      const std::function<void()>& advance,
                                      const std::function<Status(int frame)>& draw);

}  // namespace tr
