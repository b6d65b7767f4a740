#pragma once
// A triangulated surface: opaque geometry (Exodus side sets, STL/OFF/PLY files) or the input
// of TetGen's volume meshing.

#include <core/math.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tr {

struct SurfaceMesh {
    std::string name;  // side-set name or file stem
    std::vector<Vec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into points
    // Optional: points strictly inside holes of a closed surface (TetGen .poly hole lists).
    std::vector<Vec3> holes;
};

}  // namespace tr
