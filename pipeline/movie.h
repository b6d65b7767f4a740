#pragma once
// Animations as numbered frames and, through the `ffmpeg` program when it is installed, a movie:
// the cameras of an orbit, where frame k goes, and the encoding of a folder of frames.

#include <core/camera.h>
#include <core/result.h>
#include <pipeline/pipeline.h>

#include <filesystem>
#include <functional>
#include <vector>

namespace tr {

// `frames` cameras turning `degrees` in all about the axis through the focal point along the
// camera's view_up, frame 0 the camera itself and frame k turned by degrees * k / frames (so a
// full turn's frames loop without repeating the first). The view_up is kept: no roll.
// Precondition: frames >= 1.
std::vector<Camera> orbit_cameras(const Camera& start, double degrees, int frames);

// What an animation of a scene varies from frame to frame.
struct AnimationSpec {
    double orbit_degrees = 0;  // 0: no orbit
    int orbit_frames = 36;     // frames of the orbit (>= 1)
    bool every_time_step = false;
    int splat_cycle = 0;  // > 0: the frames of the scene's vector splats' texture cycle (method
                          // key "frame" = 0 .. N - 1; the scene's method is splat with vectors)
};

// Hands `frame` the scene of each frame of an animation of `scene`, in order (k = 0, 1, ...):
// an orbit's cameras, or a vector-splat cycle's frames; with every_time_step, those of each
// step of the series in turn (an orbit then turns once over all the steps, a camera a step),
// until volume 0 has no such step (loading it answers kInvalidArgument). Stops at the first
// error `frame` returns, and returns it; else the number of frames.
Result<int> for_each_animation_frame(Pipeline& pipeline, const Scene& scene,
                                     const AnimationSpec& spec,
                                     const std::function<Status(int, const Scene&)>& frame);

// DIR/frame_0000.png for k = 0: four digits at least, more past 9999.
std::filesystem::path frame_path(const std::filesystem::path& dir, int k);

// Whether the `ffmpeg` program is on the PATH.
bool movie_encoder_available();

// Encodes DIR/frame_0000.png, frame_0001.png, ... (as frame_path writes them) at `fps` frames a
// second into `out` (.mp4: H.264 in yuv420p, sides padded to even; .webm: VP9; .gif), through a
// temporary file renamed at the end. Errors: no ffmpeg ("needs the ffmpeg program (Debian:
// ffmpeg)"), an extension it does not take, ffmpeg failing (its last line of output).
Status encode_movie(const std::filesystem::path& frames_dir, double fps,
                    const std::filesystem::path& out);

}  // namespace tr
