#pragma once
// Turning cell data into point data, and picking the scalar a renderer needs.

#include <core/result.h>
#include <mesh/field.h>
#include <mesh/tet_mesh.h>

#include <string>
#include <vector>

namespace tr {

// Point field from a cell field of `mesh` (one tuple per tet): each point gets the
// volume-weighted mean of the real tets around it (zero for points no real tet uses).
// Stored as float32 when the input is float32. Cost: O(tets).
Field cell_to_point(const TetMesh& mesh, const Field& cell_field);

// The point scalar `name` of `mesh`: a 1-component point field as is; a vector's component
// (component >= 0) or magnitude (component == -1); a cell field first turned into point data.
// Errors name the array and list the available ones. Result has one float per point.
Result<std::vector<float>> point_scalar(const TetMesh& mesh, const std::string& name,
                                        int component = -1);

}  // namespace tr
