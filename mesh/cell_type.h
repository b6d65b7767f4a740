#pragma once
// Cell types of input meshes, numbered as VTK numbers them, and what we know about each.

#include <cstdint>
#include <string_view>

namespace tr {

// Values are VTK's cell-type ids, so files and simulation arrays map one to one.
enum class CellType : std::uint8_t {
    kVertex = 1,
    kTriangle = 5,
    kQuad = 9,
    kTetra = 10,
    kVoxel = 11,
    kHexahedron = 12,
    kWedge = 13,
    kPyramid = 14,
    kPentagonalPrism = 15,
    kHexagonalPrism = 16,
    kQuadraticTetra = 24,
    kQuadraticHexahedron = 25,
    kQuadraticWedge = 26,
    kQuadraticPyramid = 27,
    kTriquadraticHexahedron = 29,
    kQuadraticLinearWedge = 31,
    kBiquadraticQuadraticWedge = 32,
    kBiquadraticQuadraticHexahedron = 33,
};

// "tetra", "hexahedron", "quadratic_tetra", ... ("unknown" for anything else).
std::string_view cell_type_name(CellType type);

// Number of nodes a cell of this type has in a file (10 for a quadratic tetra); 0 when the
// type is unknown.
int cell_node_count(CellType type);

// Number of corner nodes used for tetrahedralization (4 for a quadratic tetra): the first
// nodes of the cell, in VTK order. 0 for types that are not 3D cells.
int cell_corner_count(CellType type);

// The linear type whose corners a higher-order type uses (kQuadraticTetra -> kTetra); the type
// itself when linear.
CellType linear_type(CellType type);

// True for the higher-order (quadratic) 3D types, whose mid-edge/face nodes we ignore.
bool is_quadratic(CellType type);

// True for 3D cells we can split into tetrahedra.
bool is_supported_volume_cell(CellType type);

// True when the raw id is one of the enumerators above.
bool is_known_cell_type(int vtk_id);

}  // namespace tr
