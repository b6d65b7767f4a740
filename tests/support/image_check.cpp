#include <tests/support/image_check.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace tr::testing {

std::filesystem::path test_output_dir() {
    const char* env = std::getenv("TETRENDER_TEST_OUTPUT");
    std::filesystem::path dir =
        env && *env ? std::filesystem::path(env) : std::filesystem::current_path() / "test-output";
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    return dir;
}

bool write_ppm(const Image& image, const std::filesystem::path& path) {
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << image.width << " " << image.height << "\n255\n";
    const std::vector<std::uint8_t> rgb = to_rgb8(image);
    out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
    return static_cast<bool>(out);
}

Image read_pfm(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    in.get();
    if (!in || magic != "PF" || w <= 0 || h <= 0 || scale >= 0) return {};
    Image image(w, h);
    std::vector<float> row(static_cast<std::size_t>(w) * 3);
    for (int y = h - 1; y >= 0; --y) {  // PFM rows run bottom to top
        in.read(reinterpret_cast<char*>(row.data()),
                static_cast<std::streamsize>(row.size() * sizeof(float)));
        if (!in) return {};
        for (int x = 0; x < w; ++x) {
            image.at(x, y) = Vec3f(row[3 * x], row[3 * x + 1], row[3 * x + 2]);
        }
    }
    return image;
}

::testing::AssertionResult images_match(const Image& actual, const Image& expected,
                                        const Vec3f& background, const ImageBounds& bounds,
                                        const std::string& name) {
    if (actual.width != expected.width || actual.height != expected.height) {
        return ::testing::AssertionFailure()
               << name << ": sizes differ (" << actual.width << "x" << actual.height << " vs "
               << expected.width << "x" << expected.height << ")";
    }
    const ImageComparison c = compare_images(actual, expected, background);
    std::printf(
        "[ %s ] foreground PSNR %.2f dB over %zu pixels (all %.2f dB), max diff %.5f (%d levels) "
        "at %d,%d\n",
        name.c_str(), c.psnr_foreground, c.foreground_pixels, c.psnr_all, c.max_difference,
        c.max_levels, c.worst_x, c.worst_y);
    const bool ok = c.psnr_foreground >= bounds.min_psnr_foreground_db &&
                    c.max_difference <= bounds.max_difference;
    if (ok) return ::testing::AssertionSuccess();
    const std::filesystem::path dir = test_output_dir();
    Image diff(actual.width, actual.height);
    for (std::size_t i = 0; i < diff.pixels.size(); ++i) {
        diff.pixels[i] = glm::abs(actual.pixels[i] - expected.pixels[i]) * 8.0f;
    }
    write_ppm(actual, dir / (name + "_actual.ppm"));
    write_ppm(expected, dir / (name + "_expected.ppm"));
    write_ppm(diff, dir / (name + "_diff.ppm"));
    return ::testing::AssertionFailure()
           << name << ": foreground PSNR " << c.psnr_foreground << " dB (at least "
           << bounds.min_psnr_foreground_db << " required), max difference " << c.max_difference
           << " at " << c.worst_x << "," << c.worst_y << " (at most " << bounds.max_difference
           << " allowed); pictures in " << dir.string() << "/" << name
           << "_{actual,expected,diff}.ppm";
}

}  // namespace tr::testing
