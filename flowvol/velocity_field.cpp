#include <flowvol/velocity_field.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tr {
namespace {

Status check_sample(const TetMesh& mesh, const Field& field) {
    if (field.num_components != 3 || field.num_tuples() != mesh.num_points()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "velocity '" + field.name + "' must have 3 components per point (has " +
                              std::to_string(field.num_components) + " components, " +
                              std::to_string(field.num_tuples()) + " tuples for " +
                              std::to_string(mesh.num_points()) + " points)");
    }
    return {};
}

}  // namespace

Result<VelocityField> VelocityField::steady(const TetMesh& mesh, const Field& field) {
    TR_TRY_STATUS(check_sample(mesh, field));
    VelocityField v;
    v.mesh_ = &mesh;
    v.samples_ = {&field};
    v.times_ = {0.0};
    return v;
}

Result<VelocityField> VelocityField::unsteady(const TetMesh& mesh, std::vector<Field> samples,
                                              std::vector<double> times) {
    if (samples.empty() || samples.size() != times.size()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "an unsteady velocity needs one time per sample, and a sample");
    }
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (!std::isfinite(times[k]) || (k > 0 && !(times[k] > times[k - 1]))) {
            return make_error(ErrorCode::kInvalidArgument,
                              "the velocity's sample times must be finite and increasing (time " +
                                  std::to_string(k) + ")");
        }
    }
    for (const Field& f : samples) TR_TRY_STATUS(check_sample(mesh, f));
    VelocityField v;
    v.mesh_ = &mesh;
    v.owned_ = std::move(samples);
    for (const Field& f : v.owned_) v.samples_.push_back(&f);
    v.times_ = std::move(times);
    return v;
}

Vec3 VelocityField::at_unsteady(const Location& location, double time) const {
    if (time <= times_.front()) {
        return interpolate_vector(*mesh_, *samples_.front(), location);
    }
    if (time >= times_.back()) return interpolate_vector(*mesh_, *samples_.back(), location);
    const auto upper = std::upper_bound(times_.begin(), times_.end(), time);
    const std::size_t k = static_cast<std::size_t>(upper - times_.begin());  // 1 .. size-1
    const double s = (time - times_[k - 1]) / (times_[k] - times_[k - 1]);
    const Vec3 a = interpolate_vector(*mesh_, *samples_[k - 1], location);
    const Vec3 b = interpolate_vector(*mesh_, *samples_[k], location);
    return (1.0 - s) * a + s * b;
}

}  // namespace tr
