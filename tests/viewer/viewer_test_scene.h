#pragma once
// The viewer tests' scene: a cube of Freudenthal tets with a smooth scalar, an opaque cylinder
// inside it, and the scene file that draws both (a small picture, so that each test runs in
// seconds under llvmpipe).

#include <core/math.h>
#include <tests/support/temp_dir.h>

#include <memory>
#include <string>

namespace tr::testing {

// Where make_test_scene wrote its files: a fresh temporary folder, removed with the last copy of
// the TestScene (also when an assertion ends the test early).
struct TestScene {
    std::shared_ptr<const TempDir> folder = std::make_shared<const TempDir>();
    std::string dir = folder->string(), mesh, scene, cylinder;
};

// The opacity points of the default scene (scalar, opacity) as JSON.
inline constexpr const char* kTestOpacity = "[[-0.25, 0.0], [0.4, 0.15], [1.2, 0.6]]";

// A cube [-1, 1]^3 of n^3 cells, each split into 6 tets around its main diagonal, with a smooth
// scalar "blob" (cube.vtu); a closed cylinder (r 0.3, |z| < 0.6) as cylinder.off; and
// scene.json drawing both at 240 x 180 over kTestBackground with `opacity` (JSON opacity
// points) and, when not empty, `method` (a JSON object) as the scene's method key.
TestScene make_test_scene(int n = 14, const std::string& opacity = kTestOpacity,
                          const std::string& method = "");

// Writes another scene file beside `t.scene`, the same but with `opacity` and `method`; returns
// its path.
std::string write_test_scene_variant(const TestScene& t, const std::string& name,
                                     const std::string& opacity, const std::string& method = "");

// The scene's background: the foreground is what differs from it.
inline const Vec3f kTestBackground(0.05f, 0.05f, 0.08f);

}  // namespace tr::testing
