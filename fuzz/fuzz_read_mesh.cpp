// libFuzzer target: a mesh file through read_mesh() (io/read_mesh.h), the whole path a user's
// file takes (our pre-checks and parsers, then VTK where it reads). There is no in-memory entry
// point, so each input is written to a temporary file named with TR_FUZZ_EXTENSION (".vtk":
// the legacy reader, ".vtu": the XML reader, ".csv": point clouds, ".mesh": MFEM, ".exo":
// Exodus II through netCDF), in /dev/shm when there is one. A mesh read must pass the checks of
// checks.h (check_mesh).

#include <fuzz/checks.h>
#include <io/read_mesh.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#ifndef TR_FUZZ_EXTENSION
#error "define TR_FUZZ_EXTENSION (\".vtk\", \".vtu\", \".csv\", \".mesh\", \".exo\")"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path path = tr::fuzz::temp_file(TR_FUZZ_EXTENSION);
    tr::fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
    auto mesh = tr::read_mesh(path);
    if (!mesh.ok()) {
        (void)mesh.error().to_string();
        return 0;
    }
    tr::fuzz::check_mesh(mesh.value());
    return 0;
}
