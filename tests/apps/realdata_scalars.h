#pragma once
// The real data sets in ../shared/data that have a scalar, each with the array the tests render
// in quick mode (`tetrender render FILE --scalar ARRAY`).

#include <array>
#include <ostream>
#include <string_view>

namespace tr::testing {

struct RealDataScalar {
    const char* file;  // under ../shared/data
    const char* scalar;
};

inline void PrintTo(const RealDataScalar& c, std::ostream* os) { *os << c.file; }

inline constexpr std::array<RealDataScalar, 16> kRealDataScalars = {{
    {"angular_sector/AngularSector.vtk", "PointId"},
    {"bluntfin/bluntfin.vtu", "Density"},
    {"can/can.vtu", "EQPS"},
    {"carotid/carotid.vtk", "scalars"},
    {"combustor/combustor.vtu", "Density"},
    {"cylinder_tets/CylinderLinear.vtk", "vel_norm"},
    {"cylinder_tets_quadratic/CylinderQuadratic.vtk", "pressure"},
    {"disk_out_ref/disk_out_ref.ex2", "Temp"},
    {"fea_bracket/dataset.vtu", "Equivalent (von-Mises) Stress (psi)"},
    {"iron_protein/ironProt.vtk", "scalars"},
    {"lox_post/lox_post.vtu", "Momentum"},
    {"mfem_escher/escher.vtu", "attribute"},
    {"mfem_fichera_mixed/fichera-mixed.vtu", "attribute"},
    {"office/office.binary.vtk", "scalars"},
    {"prisms_penta_hexa/PentaHexa.vtk", "scalar2"},
    {"tetra_mesh/tetraMesh.vtk", "scalars"},
}};

// In the sanitizer build (tests/support/sanitized.h) the accuracy sweeps over these sets leave
// out the four that take 15 to 40 s each there; the other twelve still read every format.
inline bool light_under_sanitizers(const RealDataScalar& c) {
    for (const char* heavy : {"carotid", "can/", "iron_protein", "lox_post"}) {
        if (std::string_view(c.file).find(heavy) != std::string_view::npos) return false;
    }
    return true;
}

}  // namespace tr::testing
