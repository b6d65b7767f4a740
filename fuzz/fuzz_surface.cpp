// libFuzzer target: a surface file through read_surface() (io/read_surface.h). The first byte
// picks the extension (.off, .stl, .ply, .obj: all our own parsers), the rest is the file, written
// to a temporary file in /dev/shm. A surface read must pass check_surface (checks.h): triangles,
// ids in range, finite points.

#include <fuzz/checks.h>
#include <io/read_surface.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const std::array<std::filesystem::path, 4> paths = {
        tr::fuzz::temp_file(".off"), tr::fuzz::temp_file(".stl"), tr::fuzz::temp_file(".ply"),
        tr::fuzz::temp_file(".obj")};
    const std::filesystem::path& path = paths[data[0] % paths.size()];
    tr::fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    auto surface = tr::read_surface(path);
    if (!surface.ok()) {
        (void)surface.error().to_string();
        return 0;
    }
    tr::fuzz::check_surface(surface.value());
    return 0;
}
