#include <apps/cli_common.h>
#include <core/config.h>
#include <io/read_mesh.h>
#include <project/scene.h>

#if TETRENDER_HAS_CGAL
#include <mesh/copyleft/delaunay.h>
#endif

#include <cctype>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace tr::apps {

ProgressFn terminal_progress() {
    if (!isatty(fileno(stderr))) return {};
    struct State {
        std::string stage;
        int percent = -1;
    };
    auto state = std::make_shared<State>();
    return [state](std::string_view stage, double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (stage == state->stage && percent == state->percent) return;
        state->stage = stage;
        state->percent = percent;
        std::fprintf(stderr, "\r%-20.*s %3d%%", static_cast<int>(stage.size()), stage.data(),
                     percent);
        if (percent >= 100) std::fprintf(stderr, "\r%40s\r", "");
        std::fflush(stderr);
    };
}

bool parse_image_size(const std::string& text, int& width, int& height) {
    const auto x = text.find('x');
    if (x == std::string::npos || x == 0 || x + 1 >= text.size() || x > 5 ||
        text.size() - x - 1 > 5) {
        return false;
    }
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (i != x && !std::isdigit(static_cast<unsigned char>(text[i]))) return false;
    }
    width = std::stoi(text.substr(0, x));
    height = std::stoi(text.substr(x + 1));
    return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

Error with_where(Error error, const std::string& path) {
    error.where = error.where.empty() ? path : path + ": " + error.where;
    return error;
}

int report_error(const Error& error) {
    std::fprintf(stderr, "tetrender: %s\n", error.to_string().c_str());
    return kExitError;
}

Result<LoadedMesh> load_tet_mesh(const std::string& path, const LoadOptions& options) {
    LoadedMesh loaded;
    const ProgressFn progress = terminal_progress();
    auto start = std::chrono::steady_clock::now();
    ReadOptions read_options;
    read_options.time_step = options.time_step;
    read_options.progress = progress;
    TR_TRY(loaded.input, read_mesh(path, read_options));
    loaded.read_ms = ms_since(start);

    start = std::chrono::steady_clock::now();
    if (loaded.input.is_point_cloud() || options.delaunay) {
#if TETRENDER_HAS_CGAL
        UnstructuredMesh cloud;
        cloud.points = loaded.input.points;
        cloud.point_fields = loaded.input.point_fields;
        auto tets = delaunay_tetrahedralize(cloud);
        if (!tets.ok()) {
            Error e = tets.error();
            if (e.where.empty()) e.where = path;
            return e;
        }
        loaded.tets = std::move(tets).value();
        loaded.used_delaunay = true;
        loaded.report.num_tets = loaded.tets.num_tets();
#else
        return make_error(ErrorCode::kUnsupported,
                          "a point cloud needs Delaunay tetrahedralization: this build has no "
                          "CGAL (TETRENDER_WITH_CGAL=OFF)",
                          path);
#endif
    } else {
        TetrahedralizeOptions tet_options;
        tet_options.merge_points = !options.no_merge;
        tet_options.merge_tolerance = options.merge_tolerance;
        tet_options.progress = progress;
        auto tets = tetrahedralize(loaded.input, tet_options, &loaded.report);
        if (!tets.ok()) {
            Error e = tets.error();
            e.where = e.where.empty() ? path : path + ": " + e.where;
            return e;
        }
        loaded.tets = std::move(tets).value();
    }
    loaded.tetrahedralize_ms = ms_since(start);
    return loaded;
}

}  // namespace tr::apps
