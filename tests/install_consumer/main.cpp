// Hands a simulation's arrays to tetrender without a file: one hexahedron, split into tets.
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>

#include <cmath>
#include <cstdio>

int main() {
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                     0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    auto input = tr::make_unstructured_mesh(xyz, {0, 1, 2, 3, 4, 5, 6, 7}, {}, {12});
    if (!input.ok()) return 1;
    auto mesh = tr::tetrahedralize(*input);
    if (!mesh.ok()) return 1;
    auto adjacency = tr::build_face_adjacency(*mesh);
    if (!adjacency.ok()) return 1;
    std::printf("%zu tets, volume %g, %zu boundary faces\n", mesh->num_tets(), mesh->real_volume(),
                adjacency->boundary_faces.size());
    return mesh->num_tets() == 6 && std::abs(mesh->real_volume() - 1.0) < 1e-12 ? 0 : 1;
}
