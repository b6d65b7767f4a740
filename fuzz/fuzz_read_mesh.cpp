// libFuzzer target: a mesh file through read_mesh() (io/read_mesh.h), the whole path a user's
// file takes (our pre-checks, then VTK). There is no in-memory entry point, so each input is
// written to a temporary file named with TR_FUZZ_EXTENSION (".vtk": the legacy reader, ".vtu":
// the XML reader), in /dev/shm when there is one. A mesh read must pass TetMesh-level checks:
// offsets (empty for a point cloud) monotone, one per cell plus one, ending at the connectivity's
// size, every id below the point count.

#include <io/read_mesh.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#ifndef TR_FUZZ_EXTENSION
#error "define TR_FUZZ_EXTENSION (\".vtk\" or \".vtu\")"
#endif

namespace {

std::filesystem::path temp_file() {
    const std::filesystem::path dir = std::filesystem::exists("/dev/shm")
                                          ? std::filesystem::path("/dev/shm")
                                          : std::filesystem::temp_directory_path();
    return dir / ("tetrender_fuzz_" + std::to_string(getpid()) + TR_FUZZ_EXTENSION);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path path = temp_file();
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    auto mesh = tr::read_mesh(path);
    if (!mesh.ok()) {
        (void)mesh.error().to_string();
        return 0;
    }
    const tr::UnstructuredMesh& m = mesh.value();
    const auto& offsets = m.offsets;
    if (offsets.empty()) {  // a point cloud
        if (!m.connectivity.empty() || !m.types.empty()) __builtin_trap();
        return 0;
    }
    if (offsets.size() != m.types.size() + 1 || offsets.front() != 0 ||
        static_cast<std::size_t>(offsets.back()) != m.connectivity.size()) {
        __builtin_trap();
    }
    for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
        if (offsets[c + 1] < offsets[c]) __builtin_trap();
    }
    for (auto id : m.connectivity) {
        if (id < 0 || static_cast<std::size_t>(id) >= m.points.size()) __builtin_trap();
    }
    return 0;
}
