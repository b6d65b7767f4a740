#pragma once
// Properties every mesh or surface a reader returns must have (beyond "no crash"), shared by
// the file-format fuzz targets; a broken one traps (a libFuzzer finding). And the temporary
// files those targets write their input to (in /dev/shm when there is one).

#include <mesh/surface_mesh.h>
#include <mesh/unstructured_mesh.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace tr::fuzz {

inline bool finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Cells: one offset per cell plus one, from 0, monotone, ending at the connectivity's size,
// every id below the point count (a point cloud: no offsets, no connectivity); finite points;
// every field one tuple per point (cell), values matching the component count.
inline void check_mesh(const UnstructuredMesh& m) {
    for (const Vec3& p : m.points) {
        if (!finite(p)) __builtin_trap();
    }
    const auto& offsets = m.offsets;
    if (offsets.empty()) {  // a point cloud
        if (!m.connectivity.empty() || !m.types.empty()) __builtin_trap();
    } else {
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
    }
    auto check_fields = [](const std::vector<Field>& fields, std::size_t tuples) {
        for (const Field& f : fields) {
            const std::size_t values = std::visit([](const auto& v) { return v.size(); }, f.values);
            if (f.num_components < 1 || f.num_tuples() != tuples ||
                values != tuples * static_cast<std::size_t>(f.num_components)) {
                __builtin_trap();
            }
        }
    };
    check_fields(m.point_fields, m.points.size());
    check_fields(m.cell_fields, m.types.size());
}

// At least one triangle, every corner below the point count, finite points and holes.
inline void check_surface(const SurfaceMesh& s) {
    if (s.triangles.empty()) __builtin_trap();
    for (const Vec3& p : s.points) {
        if (!finite(p)) __builtin_trap();
    }
    for (const Vec3& p : s.holes) {
        if (!finite(p)) __builtin_trap();
    }
    for (const auto& tri : s.triangles) {
        for (std::uint32_t id : tri) {
            if (id >= s.points.size()) __builtin_trap();
        }
    }
}

// "<dir>/tetrender_fuzz_<pid><suffix>", dir /dev/shm when there is one.
inline std::filesystem::path temp_file(const std::string& suffix) {
    static const std::filesystem::path dir = std::filesystem::exists("/dev/shm")
                                                 ? std::filesystem::path("/dev/shm")
                                                 : std::filesystem::temp_directory_path();
    return dir / ("tetrender_fuzz_" + std::to_string(getpid()) + suffix);
}

inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace tr::fuzz
