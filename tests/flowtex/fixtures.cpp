#include <mesh/tetrahedralize.h>
#include <tests/flowtex/fixtures.h>
#include <tests/support/mixed_grid.h>

namespace tr::testing {

// A sheet over [lo, lo + n * spacing]^2 in the z = 0 plane.
Sheet square_sheet(double lo, int n, double spacing) {
    return grid_sheet(Vec3(lo, lo, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n, spacing).value();
}

// Looking down -z at the origin, [-1, 1]^2 filling a size x size picture (64 px per unit at
// 128): x to the right, y up.
CameraFrame top_view(int size) {
    Camera c;
    c.parallel = true;
    c.parallel_scale = 1.0;
    c.position = Vec3(0, 0, 5);
    c.focal_point = Vec3(0, 0, 0);
    c.view_up = Vec3(0, 1, 0);
    return CameraFrame(c, size, size);
}

// The point (x, y) a layer's texture coordinate came from, for a sheet in the z = 0 plane
// with axes x, y (the layer's offset, layer / 2 periods, removed).
glm::dvec2 source_point(const TextureAdvection& adv, const Sheet& sheet, int layer, std::size_t i,
                        double period) {
    return (adv.texcoords(layer)[i] - glm::dvec2(0.5 * layer)) * period +
           glm::dvec2(sheet.origin.x, sheet.origin.y);
}

// A mixed grid over [-2, 2]^3 carrying v = a p + b.
MeshFixture mesh_with_field(const glm::dmat3& a, const Vec3& b) {
    MixedGridOptions grid;
    grid.nx = grid.ny = grid.nz = 4;
    grid.offset = Vec3(-2.0);
    MeshFixture f;
    f.mesh = tetrahedralize(make_mixed_grid(grid)).value();
    f.adjacency = build_face_adjacency(f.mesh).value();
    std::vector<float> values;
    for (const Vec3& p : f.mesh.points()) {
        const Vec3 v = a * p + b;
        values.insert(values.end(), {float(v.x), float(v.y), float(v.z)});
    }
    f.field = make_float_field("velocity", 3, values);
    return f;
}

}  // namespace tr::testing
