#pragma once
// What the tetrender subcommands share: progress on a terminal, loading a file into a TetMesh,
// and the exit codes.

#include <core/progress.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <mesh/tetrahedralize.h>
#include <mesh/unstructured_mesh.h>

#include <chrono>
#include <string>

namespace tr::apps {

// Exit codes of every subcommand (README documents them).
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;  // bad input or a failure: one line on stderr says why
inline constexpr int kExitUsage = 2;  // bad command line

// A progress callback that draws "stage NN%" on stderr when stderr is a terminal (nothing
// otherwise, so logs and pipes stay clean).
ProgressFn terminal_progress();

// How a file becomes tets.
struct LoadOptions {
    int time_step = 0;
    double merge_tolerance = 0.0;  // 0: exact merging
    bool no_merge = false;
    bool delaunay = false;  // force Delaunay (point clouds always use it)
};

struct LoadedMesh {
    UnstructuredMesh input;  // as read (its fields are also on `tets`)
    TetMesh tets;
    TetrahedralizeReport report;
    bool used_delaunay = false;
    double read_ms = 0;
    double tetrahedralize_ms = 0;
};

// Reads `path` and tetrahedralizes it (Delaunay for point clouds, when built with CGAL).
Result<LoadedMesh> load_tet_mesh(const std::string& path, const LoadOptions& options);

// Parses "WxH" with both sides in [1, kMaxImageSide] (project/scene.h).
bool parse_image_size(const std::string& text, int& width, int& height);

// Milliseconds since `start`.
double ms_since(std::chrono::steady_clock::time_point start);

// `error` with `path` in front of its where ("path: where" or "path").
Error with_where(Error error, const std::string& path);

// Prints "tetrender: <error>" on stderr, returns kExitError.
int report_error(const Error& error);

}  // namespace tr::apps
