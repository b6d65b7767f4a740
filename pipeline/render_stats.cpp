#include <pipeline/render_stats.h>

namespace tr {

void NamedStats::set_value(std::string_view key, StatValue value) {
    for (auto& [k, v] : entries_) {
        if (k == key) {
            v = std::move(value);
            return;
        }
    }
    entries_.emplace_back(std::string(key), std::move(value));
}

const StatValue* NamedStats::find(std::string_view key) const {
    for (const auto& [k, v] : entries_) {
        if (k == key) return &v;
    }
    return nullptr;
}

double NamedStats::number(std::string_view key) const {
    const StatValue* v = find(key);
    if (!v) return 0;
    if (const auto* i = std::get_if<std::int64_t>(v)) return static_cast<double>(*i);
    if (const auto* d = std::get_if<double>(v)) return *d;
    return 0;
}

}  // namespace tr
