// The library's side of a TetGen call: the request goes to the worker program
// (tetgen_worker_main.cpp, the only code that includes tetgen.h) over a socket, the mesh comes
// back on it.
#include <mesh/copyleft/detail/tetgen_plc.h>
#include <mesh/copyleft/detail/tetgen_wire.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <fcntl.h>
#include <limits>
#include <new>
#include <poll.h>
#include <spawn.h>
#include <string>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace tr::detail {

std::string tetgen_number(double value) {
    const int magnitude = value > 0 ? static_cast<int>(std::floor(std::log10(value))) : 0;
    const int decimals = std::clamp(11 - magnitude, 0, 300);
    std::vector<char> buffer(static_cast<std::size_t>(std::max(magnitude, 0) + decimals + 8));
    std::snprintf(buffer.data(), buffer.size(), "%.*f", decimals, value);
    std::string text(buffer.data());
    if (text.find('.') != std::string::npos) {
        while (text.back() == '0') text.pop_back();
        if (text.back() == '.') text.pop_back();
    }
    return text;
}

std::string tetgen_error_message(int code) {
    switch (code) {
        case 1:
            return "TetGen ran out of memory";
        case 2:
            return "TetGen hit an internal error (please report the input)";
        case 3:
            return "the input surface intersects itself (TetGen found two facets crossing)";
        case 4:
            return "the input has a feature too small for TetGen's tolerance (try a smaller "
                   "tolerance, -T, or clean the surface)";
        case 5:
            return "the input has two facets too close to each other (nearly overlapping)";
        case 10:
            return "TetGen rejected the input (invalid facets, indices or switches)";
        default:
            return "TetGen failed with error code " + std::to_string(code);
    }
}

namespace {

Result<TetgenResult> to_result(TetgenAnswer answer) {
    switch (answer.outcome) {
        case TetgenOutcome::kOk:
            return std::move(answer.result);
        case TetgenOutcome::kTetgenError: {
            const int code = answer.code;
            return make_error(code == 1 || code == 2 ? ErrorCode::kInternal
                              : code == 10           ? ErrorCode::kInvalidArgument
                                                     : ErrorCode::kInvalidMesh,
                              tetgen_error_message(code));
        }
        case TetgenOutcome::kOutOfMemory:
            return make_error(ErrorCode::kInternal, tetgen_error_message(1));
        case TetgenOutcome::kBadSwitches:
            return make_error(ErrorCode::kInvalidArgument, "TetGen rejected its switches");
        case TetgenOutcome::kBadOutput:
            return make_error(ErrorCode::kInternal,
                              "TetGen returned a tet with a point index out of range");
        case TetgenOutcome::kException:
            break;
    }
    return make_error(ErrorCode::kInternal, "TetGen failed: " + answer.text);
}

std::string errno_text(const char* what) {
    return std::string(what) + " failed: " + std::strerror(errno);
}

bool is_executable_file(const std::string& path) {
    return !path.empty() && ::access(path.c_str(), X_OK) == 0 &&
           ::access((path + "/.").c_str(), F_OK) != 0;  // not a directory
}

std::string folder_of(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Where the worker may be, in order: next to the running program (tetrender, the tests), next to
// the shared object holding this code (the Python module's package), the build tree's, the
// installed one.
std::vector<std::string> worker_candidates() {
    std::vector<std::string> candidates;
    std::vector<char> self(4096);
    const ssize_t n = ::readlink("/proc/self/exe", self.data(), self.size() - 1);
    if (n > 0) {
        candidates.push_back(folder_of(std::string(self.data(), static_cast<std::size_t>(n))) +
                             "/" + kTetgenWorkerName);
    }
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&tetgen_worker_path), &info) != 0 && info.dli_fname &&
        std::strstr(info.dli_fname, ".so")) {
        candidates.push_back(folder_of(info.dli_fname) + "/" + kTetgenWorkerName);
    }
    candidates.emplace_back(TETRENDER_TETGEN_WORKER_BUILD_PATH);
    candidates.emplace_back(TETRENDER_TETGEN_WORKER_INSTALL_PATH);
    return candidates;
}

// Writes all of `bytes` to `fd`, or fails at `deadline` or when the other end is gone.
bool send_all(int fd, const std::vector<char>& bytes,
              std::chrono::steady_clock::time_point deadline, bool& timed_out) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return !(timed_out = true);
        pollfd p{fd, POLLOUT, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
        if (ready < 0 && errno == EINTR) continue;
        if (ready < 0) return false;
        if (ready == 0) continue;
        const ssize_t sent =
            ::send(fd, bytes.data() + at, bytes.size() - at, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (sent < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (sent <= 0) return false;
        at += static_cast<std::size_t>(sent);
    }
    return true;
}

enum class ReadOutcome { kDone, kFailed, kTimedOut };

// Reads `fd` to its end, or until `deadline`.
ReadOutcome read_all(int fd, std::vector<char>& bytes,
                     std::chrono::steady_clock::time_point deadline) {
    char buffer[1 << 16];
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return ReadOutcome::kTimedOut;
        pollfd p{fd, POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
        if (ready < 0 && errno == EINTR) continue;
        if (ready < 0) return ReadOutcome::kFailed;
        if (ready == 0) continue;  // the deadline is checked above
        const ssize_t n = ::recv(fd, buffer, sizeof(buffer), MSG_DONTWAIT);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        // The worker closed its end without reading all of the request: that is its end too.
        if (n == 0 || (n < 0 && errno == ECONNRESET)) return ReadOutcome::kDone;
        if (n < 0) return ReadOutcome::kFailed;
        bytes.insert(bytes.end(), buffer, buffer + n);
    }
}

// Starts the worker with `socket` as its descriptor 3, stdin from and stdout/stderr to /dev/null
// (TetGen prints even with -Q) and nothing else inherited.
Result<pid_t> spawn_worker(const std::string& path, int socket) {
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) {
        return make_error(ErrorCode::kIo, "could not prepare TetGen's process");
    }
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, socket, 3);  // clears close-on-exec, even if 3
    posix_spawn_file_actions_addclosefrom_np(&actions, 4);
    const std::string parent = std::to_string(::getpid());
    std::vector<char*> argv = {const_cast<char*>(path.c_str()), const_cast<char*>("--parent"),
                               const_cast<char*>(parent.c_str()), nullptr};
    pid_t pid = 0;
    const int failed = posix_spawn(&pid, path.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (failed != 0) {
        return make_error(ErrorCode::kIo,
                          "could not start TetGen's worker " + path + ": " + std::strerror(failed));
    }
    return pid;
}

}  // namespace

Result<std::string> tetgen_worker_path() {
    if (const char* chosen = std::getenv("TETRENDER_TETGEN_WORKER"); chosen && *chosen) {
        if (is_executable_file(chosen)) return std::string(chosen);
        return make_error(ErrorCode::kNotFound, std::string("TETRENDER_TETGEN_WORKER=") + chosen +
                                                    ": not an executable file");
    }
    const std::vector<std::string> candidates = worker_candidates();
    for (const std::string& candidate : candidates) {
        if (is_executable_file(candidate)) return candidate;
    }
    std::string looked;
    for (const std::string& candidate : candidates) {
        looked += (looked.empty() ? "" : ", ") + candidate;
    }
    return make_error(ErrorCode::kNotFound, std::string("TetGen's worker program ") +
                                                kTetgenWorkerName + " was not found (looked at " +
                                                looked + "; set TETRENDER_TETGEN_WORKER to it)");
}

double tetgen_time_limit(const TetgenPlc& plc) {
    if (const char* text = std::getenv("TETRENDER_TETGEN_TIME_LIMIT")) {
        char* end = nullptr;
        const double seconds = std::strtod(text, &end);
        if (end != text && *end == '\0' && seconds > 0 && std::isfinite(seconds)) return seconds;
    }
    const double size = static_cast<double>(plc.points.size() + plc.triangles.size() +
                                            plc.quads.size() + plc.facets.size());
    return std::max(kTetgenMinTimeLimit, kTetgenSecondsPerItem * size);
}

Result<TetgenResult> run_tetgen(const TetgenPlc& plc, const std::string& switches,
                                double time_limit) {
    const std::size_t max_int = static_cast<std::size_t>(std::numeric_limits<int>::max() / 4);
    if (plc.points.size() >= max_int ||
        plc.triangles.size() + plc.quads.size() + plc.facets.size() >= max_int) {
        return make_error(ErrorCode::kInvalidArgument, "input too large for TetGen");
    }
    TR_TRY(const std::string worker, tetgen_worker_path());
    std::vector<char> request;
    try {
        request = encode_request(TetgenRequest{switches, plc});
    } catch (const std::bad_alloc&) {
        return make_error(ErrorCode::kInternal, "out of memory preparing TetGen's input");
    }
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
        return make_error(ErrorCode::kIo, errno_text("socketpair for TetGen"));
    }
    auto spawned = spawn_worker(worker, fds[1]);
    ::close(fds[1]);
    if (!spawned.ok()) {
        ::close(fds[0]);
        return spawned.error();
    }
    const pid_t pid = *spawned;
    const auto deadline =
        std::chrono::steady_clock::now() +
        std::chrono::milliseconds(static_cast<long long>(std::min(time_limit, 1e9) * 1000.0));
    bool timed_out = false;
    std::vector<char> bytes;
    std::string read_error;
    ErrorCode read_error_code = ErrorCode::kIo;
    ReadOutcome read = ReadOutcome::kFailed;
    // A worker that died early makes the send fail; what it said, if anything, is read anyway.
    send_all(fds[0], request, deadline, timed_out);
    request = {};
    if (!timed_out) {
        ::shutdown(fds[0], SHUT_WR);  // the end of the request
        try {
            read = read_all(fds[0], bytes, deadline);
            if (read == ReadOutcome::kFailed) read_error = errno_text("reading TetGen's answer");
        } catch (const std::bad_alloc&) {
            read_error = "out of memory reading TetGen's mesh";
            read_error_code = ErrorCode::kInternal;
        }
    }
    ::close(fds[0]);
    timed_out = timed_out || read == ReadOutcome::kTimedOut;
    if (timed_out) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (timed_out) {
        char seconds[32];
        std::snprintf(seconds, sizeof(seconds), "%g", time_limit);
        return make_error(ErrorCode::kUnsupported,
                          std::string("TetGen ran past its time limit of ") + seconds +
                              " s and was stopped (set TETRENDER_TETGEN_TIME_LIMIT, in seconds, "
                              "for a larger job)");
    }
    if (WIFSIGNALED(status)) {
        return make_error(ErrorCode::kInternal, "TetGen crashed (signal " +
                                                    std::to_string(WTERMSIG(status)) + ": " +
                                                    ::strsignal(WTERMSIG(status)) + ")");
    }
    if (!read_error.empty()) return make_error(read_error_code, read_error);
    TR_TRY(TetgenAnswer answer, decode_answer(bytes));
    return to_result(std::move(answer));
}

}  // namespace tr::detail
