#include <mesh/unstructured_mesh.h>

#include <string>

namespace tr {

void UnstructuredMesh::add_cell(CellType type, const std::vector<std::int64_t>& nodes) {
    if (offsets.empty()) offsets.push_back(0);
    connectivity.insert(connectivity.end(), nodes.begin(), nodes.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(type);
}

Result<UnstructuredMesh> make_unstructured_mesh(const std::vector<double>& xyz,
                                                const std::vector<std::int64_t>& connectivity,
                                                const std::vector<std::int64_t>& offsets,
                                                const std::vector<std::uint8_t>& cell_types) {
    if (xyz.size() % 3 != 0) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "point array has " + std::to_string(xyz.size()) + " values, not a multiple of 3");
    }
    UnstructuredMesh mesh;
    mesh.format = "arrays";
    mesh.points.resize(xyz.size() / 3);
    for (std::size_t i = 0; i < mesh.points.size(); ++i) {
        mesh.points[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    }
    mesh.types.reserve(cell_types.size());
    for (std::uint8_t t : cell_types) mesh.types.push_back(static_cast<CellType>(t));
    mesh.connectivity = connectivity;
    if (cell_types.empty()) {
        if (!connectivity.empty()) {
            return make_error(ErrorCode::kInvalidArgument, "connectivity given but no cell types");
        }
        return mesh;
    }
    if (offsets.empty()) {
        mesh.offsets.reserve(cell_types.size() + 1);
        mesh.offsets.push_back(0);
        for (std::size_t c = 0; c < cell_types.size(); ++c) {
            const int n = cell_node_count(mesh.types[c]);
            if (n == 0) {
                return make_error(ErrorCode::kUnsupported,
                                  "cell " + std::to_string(c) + " has unknown type " +
                                      std::to_string(cell_types[c]) + ": give offsets");
            }
            mesh.offsets.push_back(mesh.offsets.back() + n);
        }
    } else {
        mesh.offsets = offsets;
    }
    if (mesh.offsets.size() != cell_types.size() + 1 || mesh.offsets.front() != 0 ||
        mesh.offsets.back() != static_cast<std::int64_t>(connectivity.size())) {
        return make_error(ErrorCode::kInvalidArgument,
                          "offsets must have one entry per cell plus one, start at 0 and end "
                          "at the connectivity size (" +
                              std::to_string(connectivity.size()) + ")");
    }
    for (std::size_t c = 0; c + 1 < mesh.offsets.size(); ++c) {
        if (mesh.offsets[c + 1] < mesh.offsets[c]) {
            return make_error(ErrorCode::kInvalidArgument,
                              "offsets decrease at cell " + std::to_string(c));
        }
    }
    return mesh;
}

}  // namespace tr
