#pragma once
// A named data array on points or cells: 1 (scalar) or 3 (vector) or more components,
// stored as float32 or float64, as it was read.

#include <core/result.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace tr {

struct Field {
    std::string name;
    int num_components = 1;
    // Tuple-major: value c of tuple i is at i * num_components + c.
    std::variant<std::vector<float>, std::vector<double>> values;

    std::size_t num_tuples() const;
    bool is_double() const { return values.index() == 1; }
    // Value c of tuple i, as double. Precondition: i < num_tuples(), c < num_components.
    double get(std::size_t i, int c = 0) const;
    // Euclidean length of tuple i (the value itself for 1 component).
    double magnitude(std::size_t i) const;
    // Bytes used by the values.
    std::size_t byte_size() const;
};

// Makes a float32 field (the usual storage for rendering).
Field make_float_field(std::string name, int num_components, std::vector<float> values);
Field make_double_field(std::string name, int num_components, std::vector<double> values);

// Range of a component (c >= 0) or of the magnitude (c == -1) over all tuples, ignoring
// nothing: NaN anywhere gives NaN. {+inf, -inf} for an empty field.
std::pair<double, double> field_range(const Field& field, int component);

// Index of the first non-finite value (NaN or Inf), or -1 when all are finite.
std::int64_t first_non_finite(const Field& field);

// The field called `name`, or nullptr.
const Field* find_field(const std::vector<Field>& fields, const std::string& name);

}  // namespace tr
