// A program outside the tree that uses an installed tetrender: it hands a simulation's arrays
// over without a file — a ring of hexahedra around a hole (not convex) with a scalar and a
// velocity — renders it through the pipeline with an exact visibility order, then grows and
// renders a flow volume through it.
#include <core/config.h>
#include <mesh/tetrahedralize.h>
#include <pipeline/pipeline.h>
#include <project/colormap.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace {

// 4 x 4 x 1 boxes of side 1 without the middle 2 x 2: a square ring, as VTK hexahedra.
std::shared_ptr<const tr::UnstructuredMesh> ring_of_hexahedra() {
    const int n = 4;
    std::vector<double> xyz;
    for (int k = 0; k <= 1; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) xyz.insert(xyz.end(), {double(i), double(j), double(k)});
    auto id = [&](int i, int j, int k) { return std::int64_t((k * (n + 1) + j) * (n + 1) + i); };
    std::vector<std::int64_t> connectivity;
    std::vector<std::uint8_t> types;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            if (i >= 1 && i <= 2 && j >= 1 && j <= 2) continue;  // the hole
            for (int k : {0, 1}) {
                connectivity.insert(connectivity.end(), {id(i, j, k), id(i + 1, j, k),
                                                         id(i + 1, j + 1, k), id(i, j + 1, k)});
            }
            types.push_back(12);  // VTK_HEXAHEDRON
        }
    }
    auto mesh = tr::make_unstructured_mesh(xyz, connectivity, {}, types);
    if (!mesh.ok()) return nullptr;
    std::vector<double> pressure, velocity;
    for (const tr::Vec3& p : mesh->points) {
        pressure.push_back(0.5 + 0.4 * std::sin(1.5 * p.x) * std::cos(1.1 * p.y));
        velocity.insert(velocity.end(), {-(p.y - 2.0), p.x - 2.0, 0.0});  // round the hole
    }
    mesh->point_fields.push_back(tr::make_double_field("pressure", 1, pressure));
    mesh->point_fields.push_back(tr::make_double_field("velocity", 3, velocity));
    return std::make_shared<const tr::UnstructuredMesh>(std::move(mesh).value());
}

std::size_t covered(const tr::Image& image, const tr::Vec3& background) {
    std::size_t n = 0;
    for (const tr::Vec3f& p : image.pixels) n += glm::length(tr::Vec3(p) - background) > 0.01;
    return n;
}

}  // namespace

int main() {
    tr::Scene scene;
    tr::SceneVolume volume;
    volume.mesh = "ring";  // only names it in messages
    volume.data = ring_of_hexahedra();
    volume.scalar = "pressure";
    volume.transfer_function =
        tr::make_quick_transfer_function("viridis", 0.1, 0.9, 0.6, 1.0).value();
    if (!volume.data) return 1;
    scene.volumes.push_back(volume);
    scene.camera = tr::framing_camera({{0, 0, 0}, {4, 4, 1}}, {0.6, -1.0, 0.9});
    scene.width = scene.height = 64;

    tr::Pipeline pipeline;
    tr::RenderOptions options;
    options.sort = tr::SortMethod::kExact;
    auto picture = pipeline.render(scene, options);
    if (!picture.ok()) {
        std::printf("render: %s\n", picture.error().to_string().c_str());
        return 1;
    }
    const tr::StatValue* exact = picture->stats.find("sort_exact");
    const bool is_exact = exact && std::get<bool>(*exact);
    const std::size_t volume_pixels = covered(picture->image, scene.background);

    tr::FlowVolumeSpec dye;
    dye.vectors = "velocity";
    dye.seed_center = {0.5, 2.0, 0.5};
    dye.seed_width = dye.seed_height = 0.6;
    dye.seed_resolution = 4;
    dye.steps = 10;
    dye.dt = 0.1;
    scene.flow_volume = dye;
    auto flow = pipeline.render(scene, options);
    if (!flow.ok()) {
        std::printf("flow volume: %s\n", flow.error().to_string().c_str());
        return 1;
    }
    const std::size_t dye_pixels = covered(flow->image, scene.background);
    std::printf("exact order %s, %zu volume pixels; flow volume %zu tets, %zu pixels\n",
                is_exact ? "yes" : "no", volume_pixels, flow->flow_volume->mesh.num_tets(),
                dye_pixels);
    // Without TetGen a non-convex mesh cannot be made exact: the render says so, honestly.
    const bool exact_as_built = TETRENDER_HAS_TETGEN ? is_exact : !is_exact;
    return exact_as_built && volume_pixels > 1000 && dye_pixels > 50 ? 0 : 1;
}
