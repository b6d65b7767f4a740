#pragma once
// Image assertions for tests: PSNR over the foreground and the largest difference, each against
// a bound the test states (the measured value minus a margin), and a diff picture on failure.

#include <core/image.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace tr::testing {

struct ImageBounds {
    double min_psnr_foreground_db = 0;  // dB over the pixels either picture covers
    double max_difference = 1;          // largest absolute channel difference (of 1)
};

// Compares `actual` with `expected` (core/image.h: compare_images) and prints the measured
// values on one line tagged `name`. On failure also writes `name`_actual.ppm, _expected.ppm and
// _diff.ppm (the difference times 8) into test_output_dir() and says where.
::testing::AssertionResult images_match(const Image& actual, const Image& expected,
                                        const Vec3f& background, const ImageBounds& bounds,
                                        const std::string& name);

// Where failing tests leave pictures: $TETRENDER_TEST_OUTPUT, else ./test-output (ctest runs
// each test in its build folder). Created on first use.
std::filesystem::path test_output_dir();

// Writes a binary PPM (8 bits, clamped): viewable anywhere, no library needed.
bool write_ppm(const Image& image, const std::filesystem::path& path);

// Reads a PFM as tetrender writes it (little-endian RGB floats, bottom row first). An empty
// image when the file is not one.
Image read_pfm(const std::filesystem::path& path);

}  // namespace tr::testing
