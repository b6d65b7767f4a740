#include <mesh/cell_type.h>

namespace tr {

std::string_view cell_type_name(CellType type) {
    switch (type) {
        case CellType::kVertex:
            return "vertex";
        case CellType::kTriangle:
            return "triangle";
        case CellType::kQuad:
            return "quad";
        case CellType::kTetra:
            return "tetra";
        case CellType::kVoxel:
            return "voxel";
        case CellType::kHexahedron:
            return "hexahedron";
        case CellType::kWedge:
            return "wedge";
        case CellType::kPyramid:
            return "pyramid";
        case CellType::kPentagonalPrism:
            return "pentagonal_prism";
        case CellType::kHexagonalPrism:
            return "hexagonal_prism";
        case CellType::kQuadraticTetra:
            return "quadratic_tetra";
        case CellType::kQuadraticHexahedron:
            return "quadratic_hexahedron";
        case CellType::kQuadraticWedge:
            return "quadratic_wedge";
        case CellType::kQuadraticPyramid:
            return "quadratic_pyramid";
        case CellType::kTriquadraticHexahedron:
            return "triquadratic_hexahedron";
        case CellType::kQuadraticLinearWedge:
            return "quadratic_linear_wedge";
        case CellType::kBiquadraticQuadraticWedge:
            return "biquadratic_quadratic_wedge";
        case CellType::kBiquadraticQuadraticHexahedron:
            return "biquadratic_quadratic_hexahedron";
    }
    return "unknown";
}

int cell_node_count(CellType type) {
    switch (type) {
        case CellType::kVertex:
            return 1;
        case CellType::kTriangle:
            return 3;
        case CellType::kQuad:
            return 4;
        case CellType::kTetra:
            return 4;
        case CellType::kVoxel:
            return 8;
        case CellType::kHexahedron:
            return 8;
        case CellType::kWedge:
            return 6;
        case CellType::kPyramid:
            return 5;
        case CellType::kPentagonalPrism:
            return 10;
        case CellType::kHexagonalPrism:
            return 12;
        case CellType::kQuadraticTetra:
            return 10;
        case CellType::kQuadraticHexahedron:
            return 20;
        case CellType::kQuadraticWedge:
            return 15;
        case CellType::kQuadraticPyramid:
            return 13;
        case CellType::kTriquadraticHexahedron:
            return 27;
        case CellType::kQuadraticLinearWedge:
            return 12;
        case CellType::kBiquadraticQuadraticWedge:
            return 18;
        case CellType::kBiquadraticQuadraticHexahedron:
            return 24;
    }
    return 0;
}

CellType linear_type(CellType type) {
    switch (type) {
        case CellType::kQuadraticTetra:
            return CellType::kTetra;
        case CellType::kQuadraticHexahedron:
        case CellType::kTriquadraticHexahedron:
        case CellType::kBiquadraticQuadraticHexahedron:
            return CellType::kHexahedron;
        case CellType::kQuadraticWedge:
        case CellType::kQuadraticLinearWedge:
        case CellType::kBiquadraticQuadraticWedge:
            return CellType::kWedge;
        case CellType::kQuadraticPyramid:
            return CellType::kPyramid;
        default:
            return type;
    }
}

bool is_quadratic(CellType type) { return linear_type(type) != type; }

int cell_corner_count(CellType type) {
    switch (linear_type(type)) {
        case CellType::kTetra:
            return 4;
        case CellType::kVoxel:
        case CellType::kHexahedron:
            return 8;
        case CellType::kWedge:
            return 6;
        case CellType::kPyramid:
            return 5;
        case CellType::kPentagonalPrism:
            return 10;
        case CellType::kHexagonalPrism:
            return 12;
        default:
            return 0;
    }
}

bool is_supported_volume_cell(CellType type) { return cell_corner_count(type) > 0; }

bool is_known_cell_type(int vtk_id) {
    if (vtk_id < 0 || vtk_id > 255) return false;
    return cell_node_count(static_cast<CellType>(vtk_id)) > 0;
}

}  // namespace tr
