#include <mesh/field.h>

#include <cmath>
#include <limits>

namespace tr {

std::size_t Field::num_tuples() const {
    const std::size_t n = std::visit([](const auto& v) { return v.size(); }, values);
    return num_components > 0 ? n / static_cast<std::size_t>(num_components) : 0;
}

double Field::get(std::size_t i, int c) const {
    const std::size_t k =
        i * static_cast<std::size_t>(num_components) + static_cast<std::size_t>(c);
    return std::visit([k](const auto& v) { return static_cast<double>(v[k]); }, values);
}

double Field::magnitude(std::size_t i) const {
    if (num_components == 1) return get(i, 0);
    double sum = 0.0;
    for (int c = 0; c < num_components; ++c) {
        const double x = get(i, c);
        sum += x * x;
    }
    return std::sqrt(sum);
}

std::size_t Field::byte_size() const {
    return std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, values);
}

Field make_float_field(std::string name, int num_components, std::vector<float> values) {
    Field f;
    f.name = std::move(name);
    f.num_components = num_components;
    f.values = std::move(values);
    return f;
}

Field make_double_field(std::string name, int num_components, std::vector<double> values) {
    Field f;
    f.name = std::move(name);
    f.num_components = num_components;
    f.values = std::move(values);
    return f;
}

std::pair<double, double> field_range(const Field& field, int component) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    const std::size_t n = field.num_tuples();
    for (std::size_t i = 0; i < n; ++i) {
        const double x = component < 0 ? field.magnitude(i) : field.get(i, component);
        if (std::isnan(x)) return {x, x};
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    return {lo, hi};
}

std::int64_t first_non_finite(const Field& field) {
    return std::visit(
        [](const auto& v) -> std::int64_t {
            for (std::size_t i = 0; i < v.size(); ++i) {
                if (!std::isfinite(v[i])) return static_cast<std::int64_t>(i);
            }
            return -1;
        },
        field.values);
}

const Field* find_field(const std::vector<Field>& fields, const std::string& name) {
    for (const Field& f : fields) {
        if (f.name == name) return &f;
    }
    return nullptr;
}

}  // namespace tr
