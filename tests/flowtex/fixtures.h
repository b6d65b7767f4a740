#pragma once
// What the flowtex tests share: sheets and views in the z = 0 plane, the source point of a
// texture coordinate, and a tet mesh carrying a linear velocity field.

#include <core/camera.h>
#include <flowtex/advection.h>
#include <flowtex/sheet.h>
#include <mesh/face_adjacency.h>
#include <mesh/field.h>
#include <mesh/tet_mesh.h>

namespace tr::testing {

// A sheet over [lo, lo + n * spacing]^2 in the z = 0 plane.
Sheet square_sheet(double lo, int n, double spacing);

// Looking down -z at the origin, [-1, 1]^2 filling a size x size picture (64 px per unit at
// 128): x to the right, y up.
CameraFrame top_view(int size);

// The point (x, y) a layer's texture coordinate came from, for a sheet in the z = 0 plane
// with axes x, y (the layer's offset, layer / 2 periods, removed).
glm::dvec2 source_point(const TextureAdvection& adv, const Sheet& sheet, int layer, std::size_t i,
                        double period);

struct MeshFixture {
    TetMesh mesh;
    FaceAdjacency adjacency;
    Field field;  // "velocity", 3 components
};

// A mixed grid over [-2, 2]^3 carrying v = a p + b (float storage).
MeshFixture mesh_with_field(const glm::dmat3& a, const Vec3& b);

}  // namespace tr::testing
