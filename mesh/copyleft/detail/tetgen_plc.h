#pragma once
// Private: one call into TetGen for a piecewise linear complex, in std and GLM types. The only
// code that includes tetgen.h is detail/tetgen_plc.cpp.

#include <core/result.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tr::detail {

// A planar facet: one or more polygons (outer boundary and inner rings, vertex indices into
// TetgenPlc::points, either winding) and points strictly inside its holes.
struct TetgenFacet {
    std::vector<std::vector<std::uint32_t>> polygons;
    std::vector<Vec3> holes;
};

struct TetgenPlc {
    std::vector<Vec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // facets that are one triangle
    std::vector<std::array<std::uint32_t, 4>> quads;      // facets that are one planar quad
    std::vector<TetgenFacet> facets;                      // general facets
    std::vector<Vec3> holes;                              // points inside volume holes
};

struct TetgenResult {
    std::vector<Vec3> points;  // the input points first, in order, then any Steiner points
    std::vector<Tet> tets;     // the four corners, orientation as TetGen gives it
};

// Runs tetrahedralize() with `switches` (TetGen syntax without the dash; 'z' is added so that
// indices start at 0) in a separate process, the worker program tetrender-tetgen-worker
// (tetgen_worker_main.cpp), started with posix_spawn; the PLC goes to it and the mesh comes
// back over a socket (tetgen_wire.h). Why a process: Debian's TetGen 1.5.0 frees its memory
// twice when it fails (terminatetetgen frees it, then the unwinding destroys the tetgenmesh
// again), which would crash this process. Why spawned, not forked: a child forked from a
// process with other threads may only call async-signal-safe functions; GCC 12's
// AddressSanitizer allocator, for one, deadlocked there. TetGen's failures (the int it throws)
// become an Error with a sentence for the code; out-of-memory, other exceptions, a crashed
// worker and a missing one (tetgen_worker_path) too. POSIX only; calls may run concurrently.
// Cost: TetGen's, plus starting a small program (~1 ms, whatever this process's size) and
// copying the PLC and the mesh through the socket (~0.1 s per 10M tets).
//
// Bounded: the worker dies with this process (PR_SET_PDEATHSIG), and is killed when it runs past
// `time_limit` seconds, which is then an error saying so (kUnsupported).
Result<TetgenResult> run_tetgen(const TetgenPlc& plc, const std::string& switches,
                                double time_limit);

// The default time limit of a TetGen call: the environment's TETRENDER_TETGEN_TIME_LIMIT
// (seconds, > 0) when set, else max(kTetgenMinTimeLimit, kTetgenSecondsPerItem x the input's
// points and facets) — far beyond what TetGen takes on any mesh that fits in memory here
// (about 20 s for the 1M-tet demo), so only a runaway job meets it.
inline constexpr double kTetgenMinTimeLimit = 600.0;
inline constexpr double kTetgenSecondsPerItem = 1e-3;
double tetgen_time_limit(const TetgenPlc& plc);

// run_tetgen with the default time limit.
inline Result<TetgenResult> run_tetgen(const TetgenPlc& plc, const std::string& switches) {
    return run_tetgen(plc, switches, tetgen_time_limit(plc));
}
// The worker program's file name, and where it is: $TETRENDER_TETGEN_WORKER when set (an error
// if that is not an executable file), else the first executable file of: next to the running
// program, next to the shared object holding this code (the Python module), in the build tree,
// installed (PREFIX/libexec/tetrender). kNotFound, naming the places, when none is.
inline constexpr const char* kTetgenWorkerName = "tetrender-tetgen-worker";
Result<std::string> tetgen_worker_path();

// A positive number as a plain decimal with 12 significant digits ("0.000125"): TetGen's
// switch parser reads digits and '.', so no exponent.
std::string tetgen_number(double value);

// A sentence for TetGen's error code (1 = out of memory, 3 = self-intersection, ...).
std::string tetgen_error_message(int code);

}  // namespace tr::detail
