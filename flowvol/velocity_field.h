#pragma once
// The velocity a flow volume is grown through: a 3-component point field of a TetMesh, steady
// or sampled at increasing times and interpolated linearly in time between samples (unsteady
// flow, Becker, Lane and Max 1995).

#include <core/result.h>
#include <flowvol/point_locator.h>
#include <mesh/field.h>
#include <mesh/tet_mesh.h>

#include <vector>

namespace tr {

class VelocityField {
  public:
    // A steady field. `field` (3 components, one tuple per point of `mesh`) and `mesh` must
    // outlive the VelocityField. Errors: wrong component or tuple count.
    static Result<VelocityField> steady(const TetMesh& mesh, const Field& field);

    // An unsteady field: samples[k] holds at times[k] (strictly increasing, finite); at least
    // one sample. The samples are owned; `mesh` must outlive the VelocityField. Errors: sizes
    // that disagree, times not increasing.
    static Result<VelocityField> unsteady(const TetMesh& mesh, std::vector<Field> samples,
                                          std::vector<double> times);

    VelocityField(VelocityField&&) = default;
    VelocityField& operator=(VelocityField&&) = default;
    VelocityField(const VelocityField&) = delete;
    VelocityField& operator=(const VelocityField&) = delete;

    bool is_steady() const { return samples_.size() == 1; }
    // The times the field covers; both 0 for a steady field (which holds at any time).
    double first_time() const { return times_.front(); }
    double last_time() const { return times_.back(); }
    const std::vector<double>& times() const { return times_; }

    // The velocity at a location at `time`, linear in space (barycentric) and in time; times
    // outside [first_time, last_time] take the nearest sample. Cost: O(1) (a binary search
    // over the times).
    Vec3 at(const Location& location, double time) const {
        if (samples_.size() == 1) return interpolate_vector(*mesh_, *samples_.front(), location);
        return at_unsteady(location, time);
    }

  private:
    VelocityField() = default;
    Vec3 at_unsteady(const Location& location, double time) const;

    const TetMesh* mesh_ = nullptr;
    std::vector<Field> owned_;
    std::vector<const Field*> samples_;  // into owned_, or the caller's steady field
    std::vector<double> times_;
};

}  // namespace tr
