// tetrender compare A B: how far one picture is from another (PNG or PFM), over the pixels that
// matter: PSNR over the foreground (where either differs from the background), the largest
// difference, and a difference picture on request.
#include <apps/cli_checks.h>
#include <apps/cli_common.h>
#include <apps/commands.h>
#include <io/write_image.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>

namespace tr::apps {
namespace {

struct CompareArgs {
    std::string a, b;
    std::vector<double> background = {0, 0, 0};
    std::string diff;
    double scale = 8;
    bool json = false;
};

int run_compare(const CompareArgs& args) {
    if (!args.diff.empty()) {
        if (const Status ok = check_output_path(args.diff, {".png", ".pfm"}); !ok.ok()) {
            return report_usage(ok.error());
        }
    }
    auto a = read_image(args.a);
    if (!a.ok()) return report_error(a.error());
    auto b = read_image(args.b);
    if (!b.ok()) return report_error(b.error());
    if (a->width != b->width || a->height != b->height) {
        return report_error(make_error(ErrorCode::kInvalidArgument,
                                       "the pictures differ in size: " + std::to_string(a->width) +
                                           "x" + std::to_string(a->height) + " and " +
                                           std::to_string(b->width) + "x" +
                                           std::to_string(b->height)));
    }
    const Vec3f background(static_cast<float>(args.background[0]),
                           static_cast<float>(args.background[1]),
                           static_cast<float>(args.background[2]));
    const ImageComparison c = compare_images(*a, *b, background);
    if (args.json) {
        nlohmann::ordered_json j = {
            {"psnr_foreground", c.psnr_foreground},
            {"psnr_all", c.psnr_all},
            {"max_difference", c.max_difference},
            {"max_levels", c.max_levels},
            {"foreground_pixels", c.foreground_pixels},
            {"pixels_off_by_more_than_one_level", c.pixels_off_by_more_than_one_level},
            {"worst_x", c.worst_x},
            {"worst_y", c.worst_y}};
        std::printf("%s\n", j.dump().c_str());
    } else {
        std::printf(
            "foreground PSNR %.2f dB over %zu pixels (all pixels %.2f dB); largest difference "
            "%.5f (%d levels of 255) at %d,%d; %zu pixels off by more than one level\n",
            c.psnr_foreground, c.foreground_pixels, c.psnr_all, c.max_difference, c.max_levels,
            c.worst_x, c.worst_y, c.pixels_off_by_more_than_one_level);
    }
    if (!args.diff.empty()) {
        Image diff(a->width, a->height);
        for (std::size_t i = 0; i < diff.pixels.size(); ++i) {
            diff.pixels[i] = glm::abs(a->pixels[i] - b->pixels[i]) * static_cast<float>(args.scale);
        }
        const Status written = write_image(diff, args.diff);
        if (!written.ok()) return report_error(written.error());
    }
    return kExitOk;
}

}  // namespace

std::function<int()> add_compare_command(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "How far one picture (PNG or PFM) is from another: PSNR over the foreground, "
        "the largest difference");
    cmd->add_option("a", args->a, "A picture (.png or .pfm)")->required();
    cmd->add_option("b", args->b, "The picture to compare it with")->required();
    cmd->add_option("--background", args->background,
                    "r,g,b of the background (default 0,0,0): pixels where both pictures show it "
                    "are left out of the foreground PSNR")
        ->expected(3)
        ->delimiter(',');
    cmd->add_option("--diff", args->diff, "Write |a - b| times --scale as a picture");
    cmd->add_option("--scale", args->scale, "Difference picture gain (default 8)")
        ->check(kPositive);
    cmd->add_flag("--json", args->json, "One JSON line");
    return [args] { return run_compare(*args); };
}

}  // namespace tr::apps
