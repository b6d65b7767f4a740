#pragma once
// A rendering method's own scene keys (`$.method.KEY`, ../shared/spec/scene.md "Method"),
// declared once in a table: the type and range each takes, its default and one line of docs.
// check_method_keys() checks a scene against the table, with errors whose words come from it
// ("$.method.cycle: expected an integer from 1 to 1024"); the getters read a checked scene;
// method_keys_markdown() writes the tables docs/scene-file.md shows (a test keeps them equal).

#include <core/result.h>
#include <pipeline/scene.h>

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tr {

enum class KeyType {
    kString,   // a non-empty string (an array's name)
    kChoice,   // one of `choices`
    kInteger,  // an integer in [lo, hi]
    kNumber,   // a finite number in [lo, hi] ((lo, hi] with open_lo)
    kBool,
    kLists,  // a list of lists of numbers
};

struct MethodKey {
    std::string_view key = {};
    KeyType type = KeyType::kString;
    std::string_view default_value = {};  // as docs show it; empty: none (required, or computed)
    std::string_view doc = {};            // one line for docs/scene-file.md
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool open_lo = false;
    std::vector<std::string_view> choices = {};
    bool required = false;
    std::string_view expected = {};  // the words of a type error; empty: made from type and range
};

// What a method takes: its own keys, and whether `repetitions` and `seed` mean anything to it
// (a method that ignores them still accepts them: the pipeline notes it).
struct MethodKeys {
    std::vector<MethodKey> keys = {};
    bool uses_repetitions = false;
    bool uses_seed = false;
};

// The words an error uses for what `key` takes ("an integer from 1 to 16", "\"a\" or \"b\"").
std::string expected_words(const MethodKey& key);

// An error unless every option of the scene's method is in `table` with the type and range it
// declares, and every required key is given. Errors: `$.method.KEY: expected WORDS`,
// `$.method.KEY: unknown key for NAME (it takes ...)`, `$.method.KEY: missing (NAME needs it)`.
Status check_method_keys(const Scene& scene, std::string_view name, const MethodKeys& table);

// An error for a method option at `$.method.<key>` of the scene (its file in `where`).
Error method_option_error(const Scene& scene, const std::string& key, const std::string& message);

// A library's error about its input `error.about` (Error::about, e.g. "iso" or "slices[1]") as
// the scene's: `$.method.<about>: message`, named by the scene file; `fallback` when the library
// did not say which input.
Error method_key_error(const Scene& scene, const Error& error, const std::string& fallback);

// The method's own option `key`, if the scene gives it.
const MethodOption* option(const Scene& scene, const std::string& key);

// The value of a key a checked scene gives, else `fallback`.
std::string string_key(const Scene& scene, const std::string& key, std::string fallback = {});
double number_key(const Scene& scene, const std::string& key, double fallback);
std::int64_t integer_key(const Scene& scene, const std::string& key, std::int64_t fallback);
bool bool_key(const Scene& scene, const std::string& key, bool fallback);

// The method's `repetitions` and `seed`, else the defaults.
int repetitions_of(const Scene& scene, int fallback);
std::uint64_t seed_of(const Scene& scene, std::uint64_t fallback);

// One method's keys as a markdown table (key, takes, default, what it does).
std::string method_keys_markdown(std::string_view name, const MethodKeys& table);

}  // namespace tr
