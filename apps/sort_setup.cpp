#include <apps/cli_common.h>
#include <apps/sort_setup.h>
#include <core/config.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/convexify.h>
#endif

#include <chrono>

namespace tr::apps {

Result<SortSetup> prepare_sort(TetMesh mesh, SortMethod requested) {
    SortSetup setup;
    auto start = std::chrono::steady_clock::now();
    TR_TRY(setup.adjacency, build_face_adjacency(mesh));
    setup.adjacency_ms = ms_since(start);
    setup.convex = check_convexity(mesh, setup.adjacency).convex;
    const bool wants_fill =
        (requested == SortMethod::kAuto || requested == SortMethod::kExact) && !setup.convex;
    setup.method = requested == SortMethod::kAuto || requested == SortMethod::kExact
                       ? SortMethod::kMpvo
                       : requested;
    if (wants_fill) {
#if TETRENDER_HAS_TETGEN
        start = std::chrono::steady_clock::now();
        auto filled = convexify(mesh, setup.adjacency);
        if (filled.ok()) {
            auto adjacency = build_face_adjacency(mesh);
            if (adjacency.ok()) {
                setup.adjacency = std::move(adjacency).value();
                setup.convexified = true;
            } else {
                mesh.remove_virtual();
                setup.note = "convexification gave an invalid mesh (" + adjacency.error().message +
                             "): sorting the bare mesh";
            }
        } else {
            mesh.remove_virtual();
            setup.note = "convexification failed (" + filled.error().message +
                         "): sorting the bare mesh, not exact";
        }
        setup.convexify_ms = ms_since(start);
#else
        setup.note = "no TetGen in this build to convexify the non-convex mesh: not exact";
#endif
    }
    setup.mesh = std::move(mesh);
    setup.exact =
        claims_exactness(setup.method, setup.convex || setup.convexified) && setup.note.empty();
    return setup;
}

}  // namespace tr::apps
