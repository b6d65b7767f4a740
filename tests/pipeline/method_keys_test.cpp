// Each method's key table (pipeline/methods/method_keys.h) is what check() enforces and what
// docs/scene-file.md shows: a value of the wrong type or out of range is refused with the
// table's words, an unknown key lists the table, a required key is required, and the docs'
// block is the tables as methods_markdown() writes them.
#include <pipeline/methods/method.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace tr {
namespace {

// A scene for check(): one volume (never loaded), the method `name` with `options`.
Scene scene_of(std::string_view name, std::map<std::string, MethodOption> options) {
    Scene scene;
    SceneVolume v;
    v.mesh = "m.vtu";
    v.scalar = "s";
    scene.volumes.push_back(v);
    scene.width = scene.height = 16;
    scene.source = "s.json";
    MethodSpec m;
    m.name = std::string(name);
    m.options = std::move(options);
    scene.method = m;
    return scene;
}

// The valid values of the method's required keys.
std::map<std::string, MethodOption> required_values(const MethodKeys& table) {
    std::map<std::string, MethodOption> values;
    for (const MethodKey& k : table.keys) {
        if (!k.required) continue;
        if (k.type == KeyType::kString) values[std::string(k.key)] = std::string("v");
        if (k.type == KeyType::kNumber) values[std::string(k.key)] = 0.5;
    }
    return values;
}

std::string check_error(const RenderMethod& method, std::map<std::string, MethodOption> options) {
    const Status status = method.check(scene_of(method.name(), std::move(options)), {});
    return status.ok() ? std::string() : status.error().message;
}

// Values the key refuses: the wrong type, and each side of a finite range.
std::vector<MethodOption> refused_values(const MethodKey& k) {
    std::vector<MethodOption> values;
    switch (k.type) {
        case KeyType::kString:
        case KeyType::kChoice:
            values.emplace_back(std::int64_t{3});
            if (k.type == KeyType::kChoice) values.emplace_back(std::string("none-of-them"));
            break;
        case KeyType::kBool:
        case KeyType::kLists:
            values.emplace_back(std::string("x"));
            break;
        case KeyType::kInteger:
        case KeyType::kNumber:
            values.emplace_back(std::string("x"));
            if (k.type == KeyType::kInteger) values.emplace_back(0.5);
            if (std::isfinite(k.lo)) {
                const double below = k.open_lo ? k.lo : k.lo - 1;
                values.emplace_back(k.type == KeyType::kInteger
                                        ? MethodOption(static_cast<std::int64_t>(below))
                                        : MethodOption(below));
            }
            if (std::isfinite(k.hi)) {
                values.emplace_back(k.type == KeyType::kInteger
                                        ? MethodOption(static_cast<std::int64_t>(k.hi) + 1)
                                        : MethodOption(k.hi * 2 + 1));
            }
            break;
    }
    return values;
}

TEST(MethodKeys, EveryKeyRefusesWhatItsTableRefusesInTheTablesWords) {
    int refused = 0;
    for (const std::string& name : method_names()) {
        const RenderMethod* method = find_method(name);
        ASSERT_NE(method, nullptr) << name;
        for (const MethodKey& k : method->keys().keys) {
            for (const MethodOption& bad : refused_values(k)) {
                auto options = required_values(method->keys());
                options[std::string(k.key)] = bad;
                EXPECT_EQ(check_error(*method, options),
                          "$.method." + std::string(k.key) + ": expected " + expected_words(k))
                    << name;
                ++refused;
            }
        }
    }
    EXPECT_GE(refused, 60);  // 39 keys over 6 methods at the time of writing
}

TEST(MethodKeys, RequiredValuesAloneAreAccepted) {
    for (const std::string& name : method_names()) {
        const RenderMethod& method = *find_method(name);
        EXPECT_EQ(check_error(method, required_values(method.keys())), "") << name;
    }
}

TEST(MethodKeys, AnUnknownKeyListsTheTable) {
    for (const std::string& name : method_names()) {
        const RenderMethod& method = *find_method(name);
        auto options = required_values(method.keys());
        options["colour"] = std::string("red");
        const std::string error = check_error(method, options);
        EXPECT_EQ(error.rfind("$.method.colour: unknown key for " + name + " (it takes name", 0), 0)
            << error;
        for (const MethodKey& k : method.keys().keys) {
            EXPECT_NE(error.find(", " + std::string(k.key)), std::string::npos) << error;
        }
    }
}

TEST(MethodKeys, ARequiredKeyIsRequired) {
    int required = 0;
    for (const std::string& name : method_names()) {
        const RenderMethod& method = *find_method(name);
        for (const MethodKey& k : method.keys().keys) {
            if (!k.required) continue;
            auto options = required_values(method.keys());
            options.erase(std::string(k.key));
            EXPECT_EQ(check_error(method, options),
                      "$.method." + std::string(k.key) + ": missing (" + name + " needs it)");
            ++required;
        }
    }
    // texture-advection's vectors and spot-noise's (its iso only on a 3D mesh: checked when the
    // mesh is read, FlowtexScene.A2DMeshsSpotsEqualSpotNoiseFramesWithNoContour)
    EXPECT_EQ(required, 2);
}

TEST(MethodKeys, ExpectedWordsFromTypeAndRange) {
    EXPECT_EQ(expected_words({.key = "n", .type = KeyType::kInteger, .lo = 1, .hi = 16}),
              "an integer from 1 to 16");
    EXPECT_EQ(expected_words({.key = "n", .type = KeyType::kInteger, .lo = 0}), "an integer >= 0");
    EXPECT_EQ(expected_words({.key = "x", .type = KeyType::kNumber, .lo = 0, .open_lo = true}),
              "a number > 0");
    EXPECT_EQ(
        expected_words({.key = "x", .type = KeyType::kNumber, .lo = 0, .hi = 1, .open_lo = true}),
        "a number in (0, 1]");
    EXPECT_EQ(expected_words({.key = "x", .type = KeyType::kNumber}), "a number");
    EXPECT_EQ(expected_words({.key = "c", .type = KeyType::kChoice, .choices = {"a", "b", "c"}}),
              "\"a\", \"b\" or \"c\"");
    EXPECT_EQ(expected_words({.key = "s", .type = KeyType::kString, .expected = "an array's name"}),
              "an array's name");
}

TEST(MethodKeys, DocsShowEveryMethodsTable) {
    std::ifstream in(std::string(TETRENDER_SOURCE_DIR) + "/docs/scene-file.md");
    ASSERT_TRUE(in) << "docs/scene-file.md";
    std::stringstream text;
    text << in.rdbuf();
    const std::string doc = text.str();
    const std::string begin =
        "<!-- method keys: begin (methods_markdown(); `tetrender methods`) -->\n";
    const std::string end = "<!-- method keys: end -->";
    const std::size_t a = doc.find(begin), b = doc.find(end);
    ASSERT_NE(a, std::string::npos) << "no '" << begin << "' in docs/scene-file.md";
    ASSERT_NE(b, std::string::npos);
    const std::string shown = doc.substr(a + begin.size(), b - a - begin.size());
    EXPECT_EQ(shown, "\n" + methods_markdown() + "\n")
        << "docs/scene-file.md's method keys differ from the tables: paste `tetrender methods` "
           "between the markers";
}

}  // namespace
}  // namespace tr
