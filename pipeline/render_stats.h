#pragma once
// What a render measured and counted, in the order it happened: named values that `tetrender
// render --stats` prints as one JSON line. Each method adds its own without a shared schema.

#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace tr {

// A value, or one number per MPI rank (distributed/: in rank order).
using StatValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

class NamedStats {
  public:
    // Sets `key` (replacing its value, keeping its place) or appends it.
    void set_value(std::string_view key, StatValue value);
    // The same for a bool, any integer, any floating-point number or anything a string is made
    // from.
    template <class T>
    void set(std::string_view key, const T& value) {
        if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::vector<double>>) {
            set_value(key, StatValue(value));
        } else if constexpr (std::is_integral_v<T>) {
            set_value(key, StatValue(static_cast<std::int64_t>(value)));
        } else if constexpr (std::is_floating_point_v<T>) {
            set_value(key, StatValue(static_cast<double>(value)));
        } else {
            set_value(key, StatValue(std::string(value)));
        }
    }

    // The value of `key`, or nullptr.
    const StatValue* find(std::string_view key) const;
    // A numeric value of `key` as a double (0 when absent or not a number).
    double number(std::string_view key) const;

    const std::vector<std::pair<std::string, StatValue>>& entries() const { return entries_; }

  private:
    std::vector<std::pair<std::string, StatValue>> entries_;
};

}  // namespace tr
