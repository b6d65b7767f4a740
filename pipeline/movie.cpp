#include <pipeline/movie.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace tr {

std::vector<Camera> orbit_cameras(const Camera& start, double degrees, int frames) {
    std::vector<Camera> cameras;
    const Vec3 axis = glm::normalize(start.view_up);
    const Vec3 offset = start.position - start.focal_point;
    for (int k = 0; k < frames; ++k) {
        const double a = glm::radians(degrees) * k / frames;
        Camera c = start;
        c.position = start.focal_point + offset * std::cos(a) +
                     glm::cross(axis, offset) * std::sin(a) +
                     axis * glm::dot(axis, offset) * (1.0 - std::cos(a));
        cameras.push_back(c);
    }
    return cameras;
}

Result<int> for_each_animation_frame(Pipeline& pipeline, const Scene& scene,
                                     const AnimationSpec& spec,
                                     const std::function<Status(int, const Scene&)>& frame) {
    const bool orbit = spec.orbit_degrees != 0;
    const std::vector<Camera> cameras =
        orbit_cameras(scene.camera, spec.orbit_degrees, orbit ? std::max(1, spec.orbit_frames) : 1);
    int written = 0;
    for (int step = 0;; ++step) {
        Scene view = scene;
        if (spec.every_time_step) {
            for (SceneVolume& v : view.volumes) v.time_step = step;
            // The series ends where its first volume has no step: a step out of range.
            if (step > 0) {
                auto mesh = pipeline.mesh(view.volumes[0]);
                if (!mesh.ok() && mesh.error().code == ErrorCode::kInvalidArgument) break;
            }
        }
        const std::size_t count =
            spec.splat_cycle > 0 ? static_cast<std::size_t>(spec.splat_cycle) : cameras.size();
        for (std::size_t k = 0; k < count; ++k) {
            // An orbit over a series turns once over all its frames: one camera a step.
            if (spec.every_time_step && orbit &&
                k != static_cast<std::size_t>(step) % cameras.size()) {
                continue;
            }
            if (spec.splat_cycle > 0) {
                MethodSpec method = view.method.value_or(MethodSpec{});
                method.options["frame"] = static_cast<std::int64_t>(k);
                view.method = method;
            } else {
                view.camera = cameras[k];
            }
            TR_TRY_STATUS(frame(written, view));
            ++written;
        }
        if (!spec.every_time_step) break;
    }
    return written;
}

std::filesystem::path frame_path(const std::filesystem::path& dir, int k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    return dir / name;
}

namespace {

std::filesystem::path find_ffmpeg() {
    const char* path = std::getenv("PATH");
    if (!path) return {};
    std::stringstream folders(path);
    std::string folder;
    while (std::getline(folders, folder, ':')) {
        if (folder.empty()) continue;
        const std::filesystem::path candidate = std::filesystem::path(folder) / "ffmpeg";
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return {};
}

}  // namespace

bool movie_encoder_available() { return !find_ffmpeg().empty(); }

Status encode_movie(const std::filesystem::path& frames_dir, double fps,
                    const std::filesystem::path& out) {
    const std::filesystem::path ffmpeg = find_ffmpeg();
    if (ffmpeg.empty()) {
        return make_error(ErrorCode::kNotFound,
                          "a movie needs the ffmpeg program (Debian: apt-get install ffmpeg)",
                          out.string());
    }
    const std::string ext = out.extension().string();
    std::vector<std::string> codec;
    if (ext == ".mp4") {
        codec = {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"};
    } else if (ext == ".webm") {
        codec = {"-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p"};
    } else if (ext == ".gif") {
        codec = {};
    } else {
        return make_error(ErrorCode::kInvalidArgument,
                          "a movie is .mp4, .webm or .gif, not '" + ext + "'", out.string());
    }
    if (!(fps > 0.0 && fps <= 1000.0)) {
        return make_error(ErrorCode::kInvalidArgument, "frames per second must be in (0, 1000]");
    }
    // ffmpeg writes the temporary file (its name keeps the extension: ffmpeg picks the format
    // from it); renamed when it succeeds.
    const std::filesystem::path temp =
        out.parent_path() / (".tmp." + std::to_string(::getpid()) + "." + out.filename().string());
    const std::filesystem::path log = temp.string() + ".log";
    std::vector<std::string> args = {
        ffmpeg.string(),     "-nostdin", "-y",
        "-loglevel",         "error",    "-framerate",
        std::to_string(fps), "-i",       (frames_dir / "frame_%04d.png").string()};
    args.insert(args.end(), codec.begin(), codec.end());
    args.push_back(temp.string());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        return make_error(ErrorCode::kIo, "could not start ffmpeg", out.string());
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
    }
    std::string last_line;
    {
        std::ifstream in(log);
        for (std::string line; std::getline(in, line);) {
            if (!line.empty()) last_line = line;
        }
    }
    std::error_code ignored;
    std::filesystem::remove(log, ignored);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::filesystem::remove(temp, ignored);
        return make_error(ErrorCode::kIo,
                          "ffmpeg failed" + (last_line.empty() ? std::string() : ": " + last_line),
                          out.string());
    }
    std::error_code renamed;
    std::filesystem::rename(temp, out, renamed);
    if (renamed) {
        std::filesystem::remove(temp, ignored);
        return make_error(ErrorCode::kIo, "could not write: " + renamed.message(), out.string());
    }
    return Status{};
}

}  // namespace tr
