// The only translation unit that includes TetGen (built with TETLIBRARY: failures throw).
#include <mesh/copyleft/detail/tetgen_plc.h>

#include <tetgen.h>

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
#include <exception>
#include <fcntl.h>
#include <limits>
#include <mutex>
#include <new>
#include <poll.h>
#include <pthread.h>
#include <string>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace tr::detail {
namespace {

// tetgenio frees its arrays with delete[] in its destructor, so fill it with new[].
int* new_polygon(tetgenio::polygon& polygon, std::size_t num_vertices) {
    polygon.numberofvertices = static_cast<int>(num_vertices);
    polygon.vertexlist = new int[num_vertices];
    return polygon.vertexlist;
}

tetgenio::facet& init_facet(tetgenio::facet& facet, int num_polygons) {
    tetgenio::init(&facet);
    facet.numberofpolygons = num_polygons;
    facet.polygonlist = new tetgenio::polygon[static_cast<std::size_t>(num_polygons)];
    for (int i = 0; i < num_polygons; ++i) tetgenio::init(&facet.polygonlist[i]);
    return facet;
}

REAL* new_points(const std::vector<Vec3>& points) {
    REAL* out = new REAL[points.size() * 3];
    for (std::size_t i = 0; i < points.size(); ++i) {
        out[3 * i + 0] = points[i].x;
        out[3 * i + 1] = points[i].y;
        out[3 * i + 2] = points[i].z;
    }
    return out;
}

void fill_input(const TetgenPlc& plc, tetgenio& in) {
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(plc.points.size());
    in.pointlist = new_points(plc.points);
    const std::size_t num_facets = plc.triangles.size() + plc.quads.size() + plc.facets.size();
    in.numberoffacets = static_cast<int>(num_facets);
    in.facetlist = new tetgenio::facet[num_facets];
    // Initialize every facet first: the destructor walks all numberoffacets of them.
    for (std::size_t f = 0; f < num_facets; ++f) tetgenio::init(&in.facetlist[f]);
    std::size_t f = 0;
    for (const auto& tri : plc.triangles) {
        tetgenio::facet& facet = init_facet(in.facetlist[f++], 1);
        int* v = new_polygon(facet.polygonlist[0], 3);
        for (int k = 0; k < 3; ++k) v[k] = static_cast<int>(tri[k]);
    }
    for (const auto& quad : plc.quads) {
        tetgenio::facet& facet = init_facet(in.facetlist[f++], 1);
        int* v = new_polygon(facet.polygonlist[0], 4);
        for (int k = 0; k < 4; ++k) v[k] = static_cast<int>(quad[k]);
    }
    for (const TetgenFacet& general : plc.facets) {
        tetgenio::facet& facet =
            init_facet(in.facetlist[f++], static_cast<int>(general.polygons.size()));
        for (std::size_t p = 0; p < general.polygons.size(); ++p) {
            int* v = new_polygon(facet.polygonlist[p], general.polygons[p].size());
            for (std::size_t k = 0; k < general.polygons[p].size(); ++k) {
                v[k] = static_cast<int>(general.polygons[p][k]);
            }
        }
        if (!general.holes.empty()) {
            facet.numberofholes = static_cast<int>(general.holes.size());
            facet.holelist = new_points(general.holes);
        }
    }
    if (!plc.holes.empty()) {
        in.numberofholes = static_cast<int>(plc.holes.size());
        in.holelist = new_points(plc.holes);
    }
}

}  // namespace

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

// What the TetGen call produced, as it travels from the child process (see run_tetgen).
enum class Outcome : std::int32_t {
    kOk,
    kTetgenError,  // TetGen threw an int: `code`
    kOutOfMemory,
    kException,  // another exception: the message follows
    kBadSwitches,
    kBadOutput,  // a tet with an index out of range
};

struct MessageHeader {
    Outcome outcome = Outcome::kOk;
    std::int32_t code = 0;
    std::uint64_t num_points = 0;
    std::uint64_t num_tets = 0;
    std::uint64_t text_size = 0;
};

struct Message {
    MessageHeader header;
    std::string text;
    TetgenResult result;
};

// Calls TetGen. Its failures throw an int after TetGen has freed its memory; in Debian's 1.5.0
// unwinding through tetrahedralize() then destroys its tetgenmesh a second time and crashes.
// So this runs in a child process (run_tetgen), on a thread with no handler anywhere on its
// stack: an exception then finds no handler in the search phase, and the C++ runtime calls
// std::terminate without unwinding anything; on_terminate reads the exception and reports it.
Message call_tetgen_unguarded(const TetgenPlc& plc, const std::string& switches) {
    Message message;
    tetgenio in;
    tetgenio out;
    fill_input(plc, in);
    std::string command = switches + "z";
    std::vector<char> buffer(command.begin(), command.end());
    buffer.push_back('\0');
    tetgenbehavior behavior;
    if (!behavior.parse_commandline(buffer.data())) {
        message.header.outcome = Outcome::kBadSwitches;
        return message;
    }
    tetrahedralize(&behavior, &in, &out);

    TetgenResult& result = message.result;
    result.points.resize(static_cast<std::size_t>(out.numberofpoints));
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        result.points[i] =
            Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    }
    const std::size_t corners = static_cast<std::size_t>(out.numberofcorners);
    result.tets.resize(static_cast<std::size_t>(out.numberoftetrahedra));
    for (std::size_t t = 0; t < result.tets.size(); ++t) {
        for (std::size_t k = 0; k < 4; ++k) {
            const int p = out.tetrahedronlist[t * corners + k];
            if (p < 0 || p >= out.numberofpoints) {
                message.header.outcome = Outcome::kBadOutput;
                message.result = {};
                return message;
            }
            result.tets[t][k] = static_cast<PointId>(p);
        }
    }
    return message;
}

Result<TetgenResult> to_result(Message message) {
    switch (message.header.outcome) {
        case Outcome::kOk:
            return std::move(message.result);
        case Outcome::kTetgenError: {
            const int code = message.header.code;
            return make_error(code == 1 || code == 2 ? ErrorCode::kInternal
                              : code == 10           ? ErrorCode::kInvalidArgument
                                                     : ErrorCode::kInvalidMesh,
                              tetgen_error_message(code));
        }
        case Outcome::kOutOfMemory:
            return make_error(ErrorCode::kInternal, tetgen_error_message(1));
        case Outcome::kBadSwitches:
            return make_error(ErrorCode::kInvalidArgument, "TetGen rejected its switches");
        case Outcome::kBadOutput:
            return make_error(ErrorCode::kInternal,
                              "TetGen returned a tet with a point index out of range");
        case Outcome::kException:
            break;
    }
    return make_error(ErrorCode::kInternal, "TetGen failed: " + message.text);
}

bool write_all(int fd, const void* data, std::size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

[[noreturn]] void send_message(int fd, Message& message) {
    message.header.num_points = message.result.points.size();
    message.header.num_tets = message.result.tets.size();
    message.header.text_size = message.text.size();
    const bool ok =
        write_all(fd, &message.header, sizeof(message.header)) &&
        write_all(fd, message.text.data(), message.text.size()) &&
        write_all(fd, message.result.points.data(), message.result.points.size() * sizeof(Vec3)) &&
        write_all(fd, message.result.tets.data(), message.result.tets.size() * sizeof(Tet));
    ::_exit(ok ? 0 : 1);  // no destructors, no atexit handlers, no flush of inherited buffers
}

// The child process's job (globals are fine there: the child does nothing else).
struct ChildJob {
    const TetgenPlc* plc = nullptr;
    const std::string* switches = nullptr;
    int fd = -1;
};
ChildJob g_child_job;

// std::terminate handler of the child: the exception TetGen's thread did not catch.
[[noreturn]] void on_terminate() {
    Message message;
    message.header.outcome = Outcome::kException;
    message.text = "unknown exception";
    if (std::exception_ptr e = std::current_exception()) {
        try {
            std::rethrow_exception(e);
        } catch (int code) {
            message.header.outcome = Outcome::kTetgenError;
            message.header.code = code;
        } catch (const std::bad_alloc&) {
            message.header.outcome = Outcome::kOutOfMemory;
        } catch (const std::exception& x) {
            message.text = x.what();
        } catch (...) {
        }
    }
    send_message(g_child_job.fd, message);
}

void* tetgen_thread(void*) {
    Message message = call_tetgen_unguarded(*g_child_job.plc, *g_child_job.switches);
    send_message(g_child_job.fd, message);
}

[[noreturn]] void child_main(int fd, const TetgenPlc& plc, const std::string& switches) {
    // TetGen prints even with -Q; the library must not.
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (null_fd >= 0) {
        ::dup2(null_fd, STDOUT_FILENO);
        ::dup2(null_fd, STDERR_FILENO);
    }
    // Close every other inherited descriptor, in particular the write ends of pipes that
    // concurrent run_tetgen calls in other threads of the parent are reading to their end.
    const unsigned first_other = STDERR_FILENO + 1;
    const auto own = static_cast<unsigned>(fd);
    if (own > first_other) ::close_range(first_other, own - 1, 0);
    ::close_range(own + 1, ~0u, 0);
    g_child_job = {&plc, &switches, fd};
    std::set_terminate(on_terminate);
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, std::size_t{256} << 20);  // TetGen recurses
    pthread_t thread;
    if (pthread_create(&thread, &attributes, tetgen_thread, nullptr) != 0) {
        Message message;
        message.header.outcome = Outcome::kException;
        message.text = "could not start a thread for TetGen";
        send_message(fd, message);
    }
    pthread_join(thread, nullptr);  // tetgen_thread ends the process
    ::_exit(1);
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
        const ssize_t n = ::read(fd, buffer, sizeof(buffer));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return ReadOutcome::kFailed;
        if (n == 0) return ReadOutcome::kDone;
        bytes.insert(bytes.end(), buffer, buffer + n);
    }
}

// Parses what the child sent; an error when it is incomplete.
Result<Message> parse_message(const std::vector<char>& bytes) {
    Message message;
    auto incomplete = [] {
        return make_error(ErrorCode::kInternal, "TetGen's process ended without a full answer");
    };
    if (bytes.size() < sizeof(MessageHeader)) return incomplete();
    std::memcpy(&message.header, bytes.data(), sizeof(MessageHeader));
    const MessageHeader& h = message.header;
    const std::uint64_t expected = sizeof(MessageHeader) + h.text_size +
                                   h.num_points * sizeof(Vec3) + h.num_tets * sizeof(Tet);
    if (h.text_size > bytes.size() || h.num_points > bytes.size() || h.num_tets > bytes.size() ||
        bytes.size() != expected) {
        return incomplete();
    }
    const char* p = bytes.data() + sizeof(MessageHeader);
    message.text.assign(p, h.text_size);
    p += h.text_size;
    message.result.points.resize(h.num_points);
    if (h.num_points > 0) {
        std::memcpy(message.result.points.data(), p, h.num_points * sizeof(Vec3));
    }
    p += h.num_points * sizeof(Vec3);
    message.result.tets.resize(h.num_tets);
    if (h.num_tets > 0) std::memcpy(message.result.tets.data(), p, h.num_tets * sizeof(Tet));
    return message;
}

std::string errno_text(const char* what) {
    return std::string(what) + " failed: " + std::strerror(errno);
}

}  // namespace

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
    // TetGen runs in a child process so that its failures cannot take this one down (see
    // call_tetgen); the child sends the mesh back through a pipe. One call at a time: fewer
    // threads of ours are allocating while another forks (see tetgen_plc.h).
    static std::mutex one_at_a_time;
    const std::lock_guard<std::mutex> lock(one_at_a_time);
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return make_error(ErrorCode::kIo, errno_text("pipe"));
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return make_error(ErrorCode::kIo, errno_text("fork for TetGen"));
    }
    if (pid == 0) {
        // The child dies with its parent (killed, crashed): TetGen must never run on alone.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(1);  // the parent died before prctl
        ::close(fds[0]);
        child_main(fds[1], plc, switches);
    }
    ::close(fds[1]);
    const auto deadline =
        std::chrono::steady_clock::now() +
        std::chrono::milliseconds(static_cast<long long>(std::min(time_limit, 1e9) * 1000.0));
    std::vector<char> bytes;
    Result<TetgenResult> result = make_error(ErrorCode::kInternal, "TetGen did not run");
    ReadOutcome read = ReadOutcome::kFailed;
    try {
        read = read_all(fds[0], bytes, deadline);
    } catch (const std::bad_alloc&) {
        result = make_error(ErrorCode::kInternal, "out of memory reading TetGen's mesh");
    }
    ::close(fds[0]);
    if (read == ReadOutcome::kTimedOut) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (read == ReadOutcome::kTimedOut) {
        char seconds[32];
        std::snprintf(seconds, sizeof(seconds), "%g", time_limit);
        return make_error(ErrorCode::kUnsupported,
                          std::string("TetGen ran past its time limit of ") + seconds +
                              " s and was stopped (set TETRENDER_TETGEN_TIME_LIMIT, in seconds, "
                              "for a larger job)");
    }
    const bool read_ok = read == ReadOutcome::kDone;
    if (WIFSIGNALED(status)) {
        return make_error(ErrorCode::kInternal, "TetGen crashed (signal " +
                                                    std::to_string(WTERMSIG(status)) + ": " +
                                                    ::strsignal(WTERMSIG(status)) + ")");
    }
    if (!read_ok) return result.ok() ? make_error(ErrorCode::kIo, errno_text("read")) : result;
    auto message = parse_message(bytes);
    if (!message.ok()) return message.error();
    return to_result(std::move(message).value());
}

}  // namespace tr::detail
