// tetrender-tetgen-worker: runs one TetGen call for the tetrender library (run_tetgen in
// tetgen_plc.cpp starts it; not for direct use). The only translation unit that includes TetGen
// (built with TETLIBRARY: failures throw).
//
//   tetrender-tetgen-worker --parent PID
//
// Reads the request (tetgen_wire.h) from descriptor 3, a socket, to its end; writes the answer
// to the same socket and exits. Dies with its parent (PR_SET_PDEATHSIG), and exits at once when
// the parent is already gone.
#include <mesh/copyleft/detail/tetgen_wire.h>

#include <tetgen.h>

#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <pthread.h>
#include <string>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <unistd.h>
#include <vector>

namespace tr::detail {
namespace {

constexpr int kSocket = 3;

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

// Calls TetGen. Its failures throw an int after TetGen has freed its memory; in Debian's 1.5.0
// unwinding through tetrahedralize() then destroys its tetgenmesh a second time and crashes.
// So this runs on a thread with no handler anywhere on its stack: an exception then finds no
// handler in the search phase, and the C++ runtime calls std::terminate without unwinding
// anything; on_terminate reads the exception and reports it.
TetgenAnswer call_tetgen_unguarded(const TetgenRequest& request) {
    TetgenAnswer answer;
    tetgenio in;
    tetgenio out;
    fill_input(request.plc, in);
    std::string command = request.switches + "z";
    std::vector<char> buffer(command.begin(), command.end());
    buffer.push_back('\0');
    tetgenbehavior behavior;
    if (!behavior.parse_commandline(buffer.data())) {
        answer.outcome = TetgenOutcome::kBadSwitches;
        return answer;
    }
    tetrahedralize(&behavior, &in, &out);

    TetgenResult& result = answer.result;
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
                answer.outcome = TetgenOutcome::kBadOutput;
                answer.result = {};
                return answer;
            }
            result.tets[t][k] = static_cast<PointId>(p);
        }
    }
    return answer;
}

bool send_all(const std::vector<char>& bytes) {
    const char* p = bytes.data();
    std::size_t size = bytes.size();
    while (size > 0) {
        const ssize_t n = ::send(kSocket, p, size, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

[[noreturn]] void send_answer(const TetgenAnswer& answer) {
    bool ok = false;
    try {
        ok = send_all(encode_answer(answer));
    } catch (...) {
    }
    ::_exit(ok ? 0 : 1);  // no destructors: TetGen's state may be half freed
}

// std::terminate handler: the exception TetGen's thread did not catch.
[[noreturn]] void on_terminate() {
    TetgenAnswer answer;
    answer.outcome = TetgenOutcome::kException;
    answer.text = "unknown exception";
    if (std::exception_ptr e = std::current_exception()) {
        try {
            std::rethrow_exception(e);
        } catch (int code) {
            answer.outcome = TetgenOutcome::kTetgenError;
            answer.code = code;
        } catch (const std::bad_alloc&) {
            answer.outcome = TetgenOutcome::kOutOfMemory;
        } catch (const std::exception& x) {
            answer.text = x.what();
        } catch (...) {
        }
    }
    send_answer(answer);
}

TetgenRequest g_request;  // the thread's input (this process does nothing else)

void* tetgen_thread(void*) { send_answer(call_tetgen_unguarded(g_request)); }

bool read_request(std::vector<char>& bytes) {
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::recv(kSocket, buffer, sizeof(buffer), 0);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) return true;
        bytes.insert(bytes.end(), buffer, buffer + n);
    }
}

int worker_main(int argc, char** argv) {
    if (argc != 3 || std::strcmp(argv[1], "--parent") != 0) {
        std::fprintf(stderr,
                     "tetrender-tetgen-worker: runs TetGen for the tetrender library, which "
                     "starts it; not for direct use\n");
        return 2;
    }
    // Dies with the parent (killed, crashed): TetGen must never run on alone.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (std::to_string(::getppid()) != argv[2]) return 1;  // the parent died before prctl
    std::vector<char> bytes;
    if (!read_request(bytes)) return 1;
    auto request = decode_request(bytes);
    if (!request.ok()) {
        TetgenAnswer answer;
        answer.outcome = TetgenOutcome::kException;
        answer.text = request.error().message;
        send_answer(answer);
    }
    g_request = std::move(request).value();
    bytes = {};
    std::set_terminate(on_terminate);
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, std::size_t{256} << 20);  // TetGen recurses
    pthread_t thread;
    if (pthread_create(&thread, &attributes, tetgen_thread, nullptr) != 0) {
        TetgenAnswer answer;
        answer.outcome = TetgenOutcome::kException;
        answer.text = "could not start a thread for TetGen";
        send_answer(answer);
    }
    pthread_join(thread, nullptr);  // tetgen_thread ends the process
    return 1;
}

}  // namespace
}  // namespace tr::detail

int main(int argc, char** argv) {
    try {
        return tr::detail::worker_main(argc, argv);
    } catch (...) {
        return 1;
    }
}
