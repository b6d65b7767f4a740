#include <mesh/point_data.h>

#include <string>

namespace tr {

Field cell_to_point(const TetMesh& mesh, const Field& cell_field) {
    const std::size_t nc = static_cast<std::size_t>(cell_field.num_components);
    std::vector<double> sum(mesh.num_points() * nc, 0.0);
    std::vector<double> weight(mesh.num_points(), 0.0);
    for (std::size_t t = 0; t < mesh.num_real_tets(); ++t) {
        const double w = mesh.tet_volume(static_cast<CellId>(t));
        for (PointId p : mesh.tet(static_cast<CellId>(t))) {
            weight[p] += w;
            for (std::size_t k = 0; k < nc; ++k) {
                sum[p * nc + k] += w * cell_field.get(t, static_cast<int>(k));
            }
        }
    }
    for (std::size_t p = 0; p < mesh.num_points(); ++p) {
        if (weight[p] > 0) {
            for (std::size_t k = 0; k < nc; ++k) sum[p * nc + k] /= weight[p];
        }
    }
    if (cell_field.is_double()) {
        return make_double_field(cell_field.name, cell_field.num_components, std::move(sum));
    }
    return make_float_field(cell_field.name, cell_field.num_components,
                            std::vector<float>(sum.begin(), sum.end()));
}

Result<std::vector<float>> point_scalar(const TetMesh& mesh, const std::string& name,
                                        int component) {
    const Field* field = find_field(mesh.point_fields(), name);
    Field converted;
    if (!field) {
        if (const Field* cell = find_field(mesh.cell_fields(), name)) {
            converted = cell_to_point(mesh, *cell);
            field = &converted;
        }
    }
    if (!field) {
        std::string names;
        for (const Field& f : mesh.point_fields()) names += (names.empty() ? "" : ", ") + f.name;
        for (const Field& f : mesh.cell_fields()) {
            names += (names.empty() ? "" : ", ") + f.name + " (cell)";
        }
        return make_error(ErrorCode::kNotFound,
                          "no array '" + name + "'; the mesh has: " +
                              (names.empty() ? std::string("no arrays") : names));
    }
    if (component >= field->num_components) {
        return make_error(ErrorCode::kInvalidArgument,
                          "array '" + name + "' has " + std::to_string(field->num_components) +
                              " components; component " + std::to_string(component) +
                              " does not exist");
    }
    std::vector<float> out(mesh.num_points());
    for (std::size_t p = 0; p < out.size(); ++p) {
        const double v = component < 0 ? field->magnitude(p) : field->get(p, component);
        out[p] = static_cast<float>(v);
    }
    return out;
}

}  // namespace tr
