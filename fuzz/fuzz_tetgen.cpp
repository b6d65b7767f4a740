// libFuzzer target: TetGen files (our parser, io/detail/text_readers.cpp). The first byte
// picks what is read; the rest is split at its first NUL byte (which no text file holds) into
// two files, the second absent when there is no NUL:
//   0: read_mesh(X.node) with X.node, X.ele   1: read_mesh(X.ele) with X.ele, X.node
//   2: read_surface(X.poly) with X.poly, X.node (a .poly without points reads its .node)
// A mesh read must pass check_mesh, a surface check_surface (checks.h).

#include <fuzz/checks.h>
#include <io/read_mesh.h>
#include <io/read_surface.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <system_error>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const std::filesystem::path node = tr::fuzz::temp_file(".node");
    static const std::filesystem::path ele = tr::fuzz::temp_file(".ele");
    static const std::filesystem::path poly = tr::fuzz::temp_file(".poly");
    const int what = data[0] % 3;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::size_t nul = bytes.find('\0');
    const std::string_view first = bytes.substr(0, nul);
    const bool has_second = nul != std::string_view::npos;
    const std::string_view second = has_second ? bytes.substr(nul + 1) : std::string_view();
    const std::filesystem::path& main_path = what == 0 ? node : what == 1 ? ele : poly;
    const std::filesystem::path& other_path = what == 0 ? ele : node;
    std::error_code ec;
    std::filesystem::remove(node, ec);
    std::filesystem::remove(ele, ec);
    std::filesystem::remove(poly, ec);
    tr::fuzz::write_file(main_path, first);
    if (has_second) tr::fuzz::write_file(other_path, second);
    if (what == 2) {
        auto surface = tr::read_surface(poly);
        if (!surface.ok()) {
            (void)surface.error().to_string();
            return 0;
        }
        tr::fuzz::check_surface(surface.value());
        return 0;
    }
    auto mesh = tr::read_mesh(main_path);
    if (!mesh.ok()) {
        (void)mesh.error().to_string();
        return 0;
    }
    tr::fuzz::check_mesh(mesh.value());
    return 0;
}
