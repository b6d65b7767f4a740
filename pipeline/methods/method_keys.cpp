#include <pipeline/methods/method_keys.h>

#include <cmath>
#include <cstdio>
#include <optional>

namespace tr {
namespace {

// A bound as docs and errors write it: 16, 0.5, 1e+300.
std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", v);
    return text;
}

std::optional<double> as_number(const MethodOption& o) {
    if (const double* d = std::get_if<double>(&o)) return *d;
    if (const std::int64_t* i = std::get_if<std::int64_t>(&o)) return static_cast<double>(*i);
    return std::nullopt;
}

std::string range_words(const MethodKey& k, const char* kind) {
    const bool has_lo = std::isfinite(k.lo), has_hi = std::isfinite(k.hi);
    const std::string a = kind;
    if (has_lo && has_hi) {
        if (k.type == KeyType::kInteger) {
            return a + " from " + number_text(k.lo) + " to " + number_text(k.hi);
        }
        return a + " in " + (k.open_lo ? "(" : "[") + number_text(k.lo) + ", " + number_text(k.hi) +
               "]";
    }
    if (has_lo) return a + (k.open_lo ? " > " : " >= ") + number_text(k.lo);
    if (has_hi) return a + " <= " + number_text(k.hi);
    return a;
}

bool valid(const MethodKey& k, const MethodOption& value) {
    switch (k.type) {
        case KeyType::kString: {
            const auto* s = std::get_if<std::string>(&value);
            return s && !s->empty();
        }
        case KeyType::kChoice: {
            const auto* s = std::get_if<std::string>(&value);
            if (!s) return false;
            for (std::string_view c : k.choices) {
                if (c == *s) return true;
            }
            return false;
        }
        case KeyType::kBool:
            return std::holds_alternative<bool>(value);
        case KeyType::kLists:
            return std::holds_alternative<NumberLists>(value);
        case KeyType::kInteger:
        case KeyType::kNumber: {
            if (k.type == KeyType::kInteger && !std::holds_alternative<std::int64_t>(value)) {
                return false;
            }
            const std::optional<double> v = as_number(value);
            return v && std::isfinite(*v) && (k.open_lo ? *v > k.lo : *v >= k.lo) && *v <= k.hi;
        }
    }
    return false;
}

std::string takes_list(const MethodKeys& table) {
    std::string list = "name";
    if (table.uses_repetitions) list += ", repetitions";
    if (table.uses_seed) list += ", seed";
    for (const MethodKey& k : table.keys) list += ", " + std::string(k.key);
    if (!table.uses_repetitions || !table.uses_seed) {
        list += table.uses_seed          ? "; it ignores repetitions"
                : table.uses_repetitions ? "; it ignores seed"
                                         : "; it ignores repetitions and seed";
    }
    return list;
}

}  // namespace

std::string expected_words(const MethodKey& k) {
    if (!k.expected.empty()) return std::string(k.expected);
    switch (k.type) {
        case KeyType::kString:
            return "a name";
        case KeyType::kChoice: {
            std::string words;
            for (std::size_t i = 0; i < k.choices.size(); ++i) {
                if (i > 0) words += i + 1 == k.choices.size() ? " or " : ", ";
                words += '"';
                words += k.choices[i];
                words += '"';
            }
            return words;
        }
        case KeyType::kInteger:
            return range_words(k, "an integer");
        case KeyType::kNumber:
            return range_words(k, "a number");
        case KeyType::kBool:
            return "true or false";
        case KeyType::kLists:
            return "a list of lists of numbers";
    }
    return {};
}

Status check_method_keys(const Scene& scene, std::string_view name, const MethodKeys& table) {
    if (scene.method) {
        for (const auto& [key, value] : scene.method->options) {
            const MethodKey* rule = nullptr;
            for (const MethodKey& k : table.keys) {
                if (k.key == key) rule = &k;
            }
            if (!rule) {
                return method_option_error(scene, key,
                                           "unknown key for " + std::string(name) + " (it takes " +
                                               takes_list(table) + ")");
            }
            if (!valid(*rule, value)) {
                return method_option_error(scene, key, "expected " + expected_words(*rule));
            }
        }
    }
    for (const MethodKey& k : table.keys) {
        if (k.required && !option(scene, std::string(k.key))) {
            return method_option_error(scene, std::string(k.key),
                                       "missing (" + std::string(name) + " needs it)");
        }
    }
    return {};
}

Error method_option_error(const Scene& scene, const std::string& key, const std::string& message) {
    return make_error(ErrorCode::kInvalidArgument, "$.method." + key + ": " + message,
                      scene.source);
}

Error method_key_error(const Scene& scene, const Error& error, const std::string& fallback) {
    Error out = error;
    out.message =
        "$.method." + (error.about.empty() ? fallback : error.about) + ": " + error.message;
    if (!error.where.empty() && error.where != scene.source)
        out.message += " (" + error.where + ")";
    out.where = scene.source;
    return out;
}

const MethodOption* option(const Scene& scene, const std::string& key) {
    if (!scene.method) return nullptr;
    auto it = scene.method->options.find(key);
    return it == scene.method->options.end() ? nullptr : &it->second;
}

std::string string_key(const Scene& scene, const std::string& key, std::string fallback) {
    const MethodOption* o = option(scene, key);
    const auto* s = o ? std::get_if<std::string>(o) : nullptr;
    return s ? *s : fallback;
}

double number_key(const Scene& scene, const std::string& key, double fallback) {
    const MethodOption* o = option(scene, key);
    return o ? as_number(*o).value_or(fallback) : fallback;
}

std::int64_t integer_key(const Scene& scene, const std::string& key, std::int64_t fallback) {
    const MethodOption* o = option(scene, key);
    const auto* i = o ? std::get_if<std::int64_t>(o) : nullptr;
    return i ? *i : fallback;
}

bool bool_key(const Scene& scene, const std::string& key, bool fallback) {
    const MethodOption* o = option(scene, key);
    const auto* b = o ? std::get_if<bool>(o) : nullptr;
    return b ? *b : fallback;
}

int repetitions_of(const Scene& scene, int fallback) {
    return scene.method && scene.method->repetitions ? *scene.method->repetitions : fallback;
}

std::uint64_t seed_of(const Scene& scene, std::uint64_t fallback) {
    return scene.method && scene.method->seed ? static_cast<std::uint64_t>(*scene.method->seed)
                                              : fallback;
}

std::string method_keys_markdown(std::string_view name, const MethodKeys& table) {
    std::string md = "### `" + std::string(name) + "`\n\n";
    md += std::string("`repetitions`: ") +
          (table.uses_repetitions ? "used" : "ignored (a note says so)") +
          "; `seed`: " + (table.uses_seed ? "used" : "ignored (a note says so)") + ".\n\n";
    if (table.keys.empty()) return md + "No keys of its own.\n";
    md += "| key | takes | default | what it does |\n|---|---|---|---|\n";
    for (const MethodKey& k : table.keys) {
        const std::string dflt = k.required                ? "required"
                                 : k.default_value.empty() ? ""
                                                           : std::string(k.default_value);
        md += "| `" + std::string(k.key) + "` | " + expected_words(k) + " | " + dflt + " | " +
              std::string(k.doc) + " |\n";
    }
    return md;
}

}  // namespace tr
