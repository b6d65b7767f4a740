// `mpirun -np K tetrender-mpi render` against `tetrender render` of the same scene: for K = 1..4
// the distributed picture is the single process's (projected tetrahedra, exact order) on a
// convex and a non-convex real mesh and on a .pvtu read piece by piece, a fused scene; PBVR
// within its own noise; the cut volume conserved; and the ways a distributed run must fail
// (a piece that does not read on one rank ends every rank; more ranks than cells; a rank with
// nothing in view).
#include <io/write_vtu.h>
#include <pipeline/loaded_mesh.h>
#include <tests/apps/cli_runner.h>
#include <tests/io/exodus_writer.h>
#include <tests/support/image_check.h>
#include <tests/support/sanitized.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::CliRun;
using testing::run_captured;
using testing::run_cli;
using testing::shell_quote;

// `tetrender-mpi render ARGS` on `ranks` processes, oversubscribed on this machine's cores,
// killed after two minutes (a hang is a failure, exit 124).
CliRun run_mpi(int ranks, const std::string& args) {
    // Under AddressSanitizer, OpenMPI's own allocations kept to the end are leaks that
    // scripts/lsan.supp names by library; the suppressions match only with full stacks (fast
    // unwinding stops inside OpenMPI's plugins, which have no frame pointers).
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string env =
        "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
        "OMPI_MCA_btl_vader_single_copy_mechanism=none " +
        (asan ? "ASAN_OPTIONS=" + shell_quote(std::string(asan) + ":fast_unwind_on_malloc=0") + " "
              : std::string());
    return run_captured(env + "timeout 120 " + shell_quote(TETRENDER_MPIEXEC) +
                        " --oversubscribe --bind-to none -np " + std::to_string(ranks) + " " +
                        shell_quote(TETRENDER_MPI_CLI) + " render " + args);
}

std::string data(const std::string& relative) {
    return testing::shared_data_dir() + "/" + relative;
}

// A quick-look scene of `mesh` (camera, transfer function chosen by `tetrender render`), written
// to `scene`; `extra` adds quick-look options.
void write_quick_scene(const std::string& mesh, const std::string& scalar, const std::string& scene,
                       const std::string& extra = "") {
    const CliRun run = run_cli("render " + shell_quote(mesh) + " --scalar " + scalar +
                               " --size 128x96 --legend off " + extra + " --write-scene " +
                               shell_quote(scene) + " -o " + shell_quote(scene + ".png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
}

struct Pictures {
    Image single;
    Image distributed;
    nlohmann::json stats;  // tetrender-mpi --stats
};

// The scene drawn by one process and by `ranks` (one thread each: the ranks share 2 cores).
// One process draws it once per scene and options (later calls read that picture back).
Pictures render_both(const std::string& scene, int ranks, const std::string& options = "") {
    Pictures out;
    const std::string single =
        scene + ".single" + std::to_string(std::hash<std::string>{}(options)) + ".pfm";
    const std::string distributed = scene + ".k" + std::to_string(ranks) + ".pfm";
    if (!std::filesystem::exists(single)) {
        const CliRun run =
            run_cli("render " + shell_quote(scene) + " " + options + " -o " + shell_quote(single));
        EXPECT_EQ(run.exit_code, 0) << run.err;
    }
    const CliRun run = run_mpi(ranks, shell_quote(scene) + " --threads 1 --stats " + options +
                                          " -o " + shell_quote(distributed));
    EXPECT_EQ(run.exit_code, 0) << run.err << run.out;
    out.single = testing::read_pfm(single);
    out.distributed = testing::read_pfm(distributed);
    if (run.exit_code == 0) out.stats = nlohmann::json::parse(run.out);
    return out;
}

// Lines of stderr that tetrender-mpi wrote.
int count_lines_from_us(const std::string& err) {
    int lines = 0;
    for (std::size_t at = err.find("tetrender-mpi:"); at != std::string::npos;
         at = err.find("tetrender-mpi:", at + 1)) {
        ++lines;
    }
    return lines;
}

double sum(const nlohmann::json& values) {
    double total = 0;
    for (double v : values) total += v;
    return total;
}

// The mesh's volume as one process tetrahedralizes it (`tetrender info`).
double mesh_volume(const std::string& mesh) {
    const CliRun run = run_cli("info " + shell_quote(mesh) + " --json");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["tetrahedralization"]["volume"];
}

// The rank counts of a test: `all`, or in the sanitizer build (tests/support/sanitized.h) those
// of them in {2, 3}: an even and an uneven split take every code path of the cut, the sort and
// the compositing; K = 1 and 4 add numbers, which the Release build checks.
std::vector<int> rank_counts(std::initializer_list<int> all) {
    return testing::sanitized_subset(std::vector<int>(all), [](int k) { return k == 2 || k == 3; });
}

// K = 1..4 against one process: at least 60 dB over the foreground (the issue's bound) and at
// most 2 levels anywhere; every rank's share of the volume adds up to the mesh's.
void expect_same_pictures(const std::string& scene, const std::string& mesh,
                          const std::string& name, double min_db, double max_difference) {
    const double volume = mesh_volume(mesh);
    for (int ranks : rank_counts({1, 2, 3, 4})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        ASSERT_FALSE(p.distributed.pixels.empty());
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f),
                                          {min_db, max_difference},
                                          name + "_k" + std::to_string(ranks)));
        EXPECT_EQ(p.stats["ranks"], ranks);
        EXPECT_EQ(p.stats["sort_exact"], true);
        // Every rank's share conformed: none fell back to merging per pixel (a share whose cut
        // left unmatched faces cannot be convexified: TetGen sees its boundary cross itself).
        EXPECT_EQ(p.stats["ranks_merged"], 0);
        EXPECT_NEAR(sum(p.stats["volume"]), volume, 1e-12 * volume);
        EXPECT_EQ(p.stats["cells"].size(), static_cast<std::size_t>(ranks));
    }
}

class DistributedRender : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!testing::require_shared_data()) GTEST_SKIP() << "no ../shared/data";
        dir_ = testing::make_temp_dir();
    }
    void TearDown() override {
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }
    std::string dir_;
};

TEST_F(DistributedRender, ConvexMeshEqualsOneProcess) {
    // office: a convex structured grid (hexahedra): the planes fall between its cell layers.
    const std::string mesh = data("office/office.binary.vtk");
    const std::string scene = dir_ + "/office.json";
    write_quick_scene(mesh, "scalars", scene);
    // Measured: identical for one rank; 115-148 dB over the foreground for 2-4 ranks, the
    // largest difference 7e-5 (the issue asks for 60 dB and 2 levels at most).
    expect_same_pictures(scene, mesh, "office", 100.0, 3e-4);
}

TEST_F(DistributedRender, NonConvexMeshEqualsOneProcess) {
    // disk_out_ref: non-convex (a disc with a hole), its hexahedra cut at the planes; each rank
    // convexifies its share, or merges it per pixel.
    const std::string mesh = data("disk_out_ref/disk_out_ref.ex2");
    const std::string scene = dir_ + "/disk.json";
    write_quick_scene(mesh, "Temp", scene, "--azimuth 30 --elevation 20");
    // Measured: identical for one rank; 115-151 dB for 2-4 ranks, the largest difference 2e-5.
    expect_same_pictures(scene, mesh, "disk", 100.0, 3e-4);
}

// `mesh`'s tets in `pieces` .vtu files of consecutive tets (as a simulation's ranks write them)
// and a .pvtu listing them; returns the .pvtu's path.
std::string write_pvtu(const std::string& mesh, const std::string& dir, int pieces) {
    auto loaded = load_tet_mesh(mesh, LoadOptions{});
    EXPECT_TRUE(loaded.ok());
    const TetMesh& tets = loaded->tets;
    std::ofstream pvtu(dir + "/pieces.pvtu");
    pvtu << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
            "byte_order=\"LittleEndian\">\n<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData>\n";
    for (const Field& f : tets.point_fields()) {
        pvtu << "<PDataArray type=\"" << (f.is_double() ? "Float64" : "Float32") << "\" Name=\""
             << f.name << "\" NumberOfComponents=\"" << f.num_components << "\"/>\n";
    }
    pvtu << "</PPointData>\n<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>"
            "</PPoints>\n";
    const std::size_t n = tets.num_real_tets();
    for (int p = 0; p < pieces; ++p) {
        // The piece's tets, its own points (renumbered), its point fields.
        std::vector<PointId> id(tets.num_points(), kNoCell);
        std::vector<Vec3> points;
        std::vector<PointId> used;
        std::vector<Tet> cells;
        for (std::size_t t = n * p / pieces; t < n * (p + 1) / pieces; ++t) {
            Tet cell = tets.tet(static_cast<CellId>(t));
            for (PointId& v : cell) {
                if (id[v] == kNoCell) {
                    id[v] = static_cast<PointId>(points.size());
                    points.push_back(tets.point(v));
                    used.push_back(v);
                }
                v = id[v];
            }
            cells.push_back(cell);
        }
        auto piece = TetMesh::create(std::move(points), std::move(cells));
        EXPECT_TRUE(piece.ok());
        for (const Field& f : tets.point_fields()) {
            std::vector<double> values;
            for (PointId v : used) {
                for (int c = 0; c < f.num_components; ++c) values.push_back(f.get(v, c));
            }
            EXPECT_TRUE(
                piece->add_point_field(make_double_field(f.name, f.num_components, values)).ok());
        }
        const std::string name = "piece" + std::to_string(p) + ".vtu";
        EXPECT_TRUE(write_vtu(*piece, dir + "/" + name).ok());
        pvtu << "<Piece Source=\"" << name << "\"/>\n";
    }
    pvtu << "</PUnstructuredGrid>\n</VTKFile>\n";
    return dir + "/pieces.pvtu";
}

TEST_F(DistributedRender, PvtuPiecesAreReadByTheRanksThemselves) {
    const std::string pvtu = write_pvtu(data("disk_out_ref/disk_out_ref.ex2"), dir_, 5);
    const std::string scene = dir_ + "/pieces.json";
    write_quick_scene(pvtu, "Temp", scene, "--azimuth 30 --elevation 20");
    for (int ranks : rank_counts({1, 2, 3, 4})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        // Measured: as the same mesh from one file (identical, then 115-151 dB, 2e-5).
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f), {100.0, 3e-4},
                                          "pvtu_k" + std::to_string(ranks)));
        EXPECT_EQ(p.stats["reading"], "pieces");
        EXPECT_EQ(sum(p.stats["files_read"]), 5.0);
        // The pieces were dealt out: every rank read its run (5 pieces, up to 4 ranks).
        for (double files : p.stats["files_read"]) EXPECT_GE(files, 1.0);
    }
}

TEST_F(DistributedRender, AnExodusFileSetIsReadByTheRanksThemselves) {
    // mesh.e.4.0 .. mesh.e.4.3, two tets each, moved 1.2 apart along x: one process reads the
    // whole set; two ranks read two files each.
    for (int k = 0; k < 4; ++k) {
        test::ExodusSpec spec;
        for (double& x : spec.x) x += 1.2 * k;
        test::write_exodus(dir_ + "/mesh.e.4." + std::to_string(k), spec);
    }
    const std::string scene = dir_ + "/set.json";
    write_quick_scene(dir_ + "/mesh.e.4.0", "temp", scene, "--opacity 0.8");
    for (int ranks : rank_counts({2, 3})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        // Measured: 172-178 dB.
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f), {100.0, 3e-4},
                                          "exodus_set_k" + std::to_string(ranks)));
        EXPECT_EQ(p.stats["reading"], "pieces");
        EXPECT_EQ(sum(p.stats["files_read"]), 4.0);
    }
}

TEST_F(DistributedRender, FusedVolumesEqualOneProcess) {
    // Two volumes in one space (disk_out_ref's temperature and pressure), merged per pixel.
    const std::string mesh = data("disk_out_ref/disk_out_ref.ex2");
    const std::string scene = dir_ + "/fused.json";
    write_quick_scene(mesh, "Temp", scene,
                      "--volume " + shell_quote(mesh + ":Pres") + " --azimuth 30 --elevation 20");
    for (int ranks : rank_counts({1, 2, 3})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        // Measured: identical for one rank; 155-157 dB for 2 and 3, the largest difference 4e-6.
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f), {140.0, 5e-5},
                                          "fused_k" + std::to_string(ranks)));
    }
}

TEST_F(DistributedRender, AnOpaqueSurfaceStopsEveryRanksRays) {
    // A plate across the middle of the office, half the volume behind it: each rank's rays stop
    // at its depth, and rank 0 puts the blend over the plate's picture.
    const std::string mesh = data("office/office.binary.vtk");
    const std::string scene = dir_ + "/plate.json";
    write_quick_scene(mesh, "scalars", scene);
    const CliRun info = run_cli("info " + shell_quote(mesh) + " --json");
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const nlohmann::json b = nlohmann::json::parse(info.out)["bounds"];
    const double x = 0.5 * (b[0][0].get<double>() + b[0][1].get<double>());
    std::ofstream plate(dir_ + "/plate.obj");
    const double y0 = b[1][0].get<double>() - 1, y1 = b[1][1].get<double>() + 1;
    const double z0 = b[2][0].get<double>() - 1, z1 = b[2][1].get<double>() + 1;
    plate << "v " << x << " " << y0 << " " << z0 << "\nv " << x << " " << y1 << " " << z0 << "\nv "
          << x << " " << y1 << " " << z1 << "\nv " << x << " " << y0 << " " << z1
          << "\nf 1 2 3\nf 1 3 4\n";
    plate.close();
    nlohmann::json j = nlohmann::json::parse(std::ifstream(scene));
    j["opaque"] = {{{"file", "plate.obj"}, {"color", {0.8, 0.5, 0.3}}}};
    std::ofstream(scene) << j.dump();
    for (int ranks : rank_counts({2, 3})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        // Measured: 116-146 dB, the largest difference 7e-5.
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f), {100.0, 3e-4},
                                          "plate_k" + std::to_string(ranks)));
    }
}

TEST_F(DistributedRender, PbvrImageWithinItsOwnNoise) {
    // The expected picture is the exact one (projected tetrahedra); each rank averages its own
    // particles. The distributed picture must be as close to it as one process's is.
    const std::string mesh = data("office/office.binary.vtk");
    const std::string scene = dir_ + "/office.json";
    write_quick_scene(mesh, "scalars", scene);
    const std::string exact = dir_ + "/exact.pfm";
    ASSERT_EQ(run_cli("render " + shell_quote(scene) + " -o " + shell_quote(exact)).exit_code, 0);
    const Image reference = testing::read_pfm(exact);
    const Vec3f black(0.0f);
    for (int ranks : rank_counts({2, 4})) {
        SCOPED_TRACE(ranks);
        const Pictures p =
            render_both(scene, ranks, "--method pbvr-image --repetitions 16 --seed 3");
        const ImageComparison single = compare_images(p.single, reference, black);
        const ImageComparison distributed = compare_images(p.distributed, reference, black);
        std::printf("pbvr k=%d: single %.2f dB, distributed %.2f dB\n", ranks,
                    single.psnr_foreground, distributed.psnr_foreground);
        // Measured: single 33.3 dB, distributed 34.3 (2 ranks) and 35.2 dB (4 ranks): each
        // rank's estimate is unbiased and the ranks' noise is independent.
        EXPECT_GE(distributed.psnr_foreground, single.psnr_foreground - 1.0);
        EXPECT_GE(distributed.psnr_foreground, 32.0);
    }
}

TEST_F(DistributedRender, AReadingErrorOnOneRankEndsEveryRank) {
    std::string pvtu = write_pvtu(data("disk_out_ref/disk_out_ref.ex2"), dir_, 3);
    // The last piece truncated: only the last rank reads it.
    const std::string broken = dir_ + "/piece2.vtu";
    std::filesystem::resize_file(broken, std::filesystem::file_size(broken) / 2);
    const std::string scene = dir_ + "/broken.json";
    std::ofstream(scene) << R"({"mesh": "pieces.pvtu", "scalar": "Temp", "transfer_function":
        {"color": [[300, 0, 0, 1], [900, 1, 0, 0]], "opacity": [[300, 0], [900, 0.5]],
        "unit_distance": 1}, "camera": {"position": [30, 0, 0], "focal_point": [0, 0, 0],
        "view_up": [0, 0, 1], "view_angle": 30}, "image": {"width": 64, "height": 48}})";
    const std::string out = dir_ + "/broken.png";
    const CliRun run = run_mpi(3, shell_quote(scene) + " --threads 1 -o " + shell_quote(out));
    EXPECT_EQ(run.exit_code, 1) << run.err;  // not 124: no rank waited for ever
    EXPECT_NE(run.err.find("piece2.vtu"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("(rank 2)"), std::string::npos) << run.err;
    // One line from rank 0, not one per rank (mpirun adds its own banner).
    EXPECT_EQ(count_lines_from_us(run.err), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(DistributedRender, MoreRanksThanCells) {
    // One tet over 2 and 3 ranks.
    const std::string one_tet = dir_ + "/one.vtk";
    std::ofstream(one_tet) << "# vtk DataFile Version 3.0\none tet\nASCII\nDATASET "
                              "UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                              "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS f "
                              "double 1\nLOOKUP_TABLE default\n0\n1\n0.5\n0.25\n";
    const std::string scene = dir_ + "/one.json";
    write_quick_scene(one_tet, "f", scene, "--opacity 0.8");
    for (int ranks : rank_counts({2, 3})) {
        SCOPED_TRACE(ranks);
        const Pictures p = render_both(scene, ranks);
        // Measured: identical (one rank holds the tet whole).
        EXPECT_TRUE(testing::images_match(p.distributed, p.single, Vec3f(0.0f), {140.0, 1e-5},
                                          "one_tet_k" + std::to_string(ranks)));
        // A rank whose box holds nothing draws nothing, and the others' picture is whole.
        int empty = 0;
        for (double cells : p.stats["cells"]) empty += cells == 0.0 ? 1 : 0;
        EXPECT_GE(empty, 1) << p.stats.dump();
    }
}

TEST_F(DistributedRender, ARankWithNothingInViewAddsNothing) {
    // A narrow view down onto one corner of the office: the boxes of the far corners are out of
    // the picture.
    const std::string mesh = data("office/office.binary.vtk");
    const std::string scene = dir_ + "/corner.json";
    write_quick_scene(mesh, "scalars", scene);
    const CliRun info = run_cli("info " + shell_quote(mesh) + " --json");
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const nlohmann::json bounds = nlohmann::json::parse(info.out)["bounds"];
    nlohmann::json j = nlohmann::json::parse(std::ifstream(scene));
    const double x = bounds[0][0].get<double>() +
                     0.1 * (bounds[0][1].get<double>() - bounds[0][0].get<double>());
    const double y = bounds[1][0].get<double>() +
                     0.1 * (bounds[1][1].get<double>() - bounds[1][0].get<double>());
    const double z = bounds[2][1].get<double>();
    j["camera"] = {{"position", {x, y, z + 1.5}},
                   {"focal_point", {x, y, z - 1.0}},
                   {"view_up", {0, 1, 0}},
                   {"view_angle", 25}};
    std::ofstream(scene) << j.dump();
    const Pictures p = render_both(scene, 4);
    // Measured: identical (the one rank in view draws the whole picture).
    EXPECT_TRUE(
        testing::images_match(p.distributed, p.single, Vec3f(0.0f), {140.0, 1e-5}, "corner_k4"));
    int idle = 0;
    for (std::size_t r = 0; r < p.stats["fragments"].size(); ++r) {
        if (p.stats["fragments"][r] == 0.0 && p.stats["cells"][r] > 0.0) ++idle;
    }
    EXPECT_GE(idle, 1) << p.stats.dump();
}

TEST(DistributedRenderBadInput, RefusesWhatIsNotDistributedAndBadArguments) {
    const std::string dir = testing::make_temp_dir();
    const std::string scene = dir + "/s.json";
    std::ofstream(scene) << R"({"mesh": "m.vtu", "scalar": "f", "transfer_function":
        {"color": [[0, 0, 0, 1], [1, 1, 0, 0]], "opacity": [[0, 0], [1, 0.5]],
        "unit_distance": 1}, "camera": {"position": [3, 0, 0], "focal_point": [0, 0, 0],
        "view_up": [0, 0, 1], "view_angle": 30}, "image": {"width": 32, "height": 32},
        "method": {"name": "splat"}})";
    CliRun run = run_mpi(2, shell_quote(scene) + " -o " + shell_quote(dir + "/o.png"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("not drawn across ranks yet"), std::string::npos) << run.err;
    run = run_mpi(2, shell_quote(scene) + " -o " + shell_quote(dir + "/o.txt"));
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(".png"), std::string::npos) << run.err;
    run = run_mpi(2, shell_quote(scene) + " -o " + shell_quote(dir + "/o.png") + " --bogus");
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(count_lines_from_us(run.err), 1) << run.err;
    run = run_mpi(2, shell_quote(dir + "/missing.json") + " -o " + shell_quote(dir + "/o.png"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_EQ(count_lines_from_us(run.err), 1) << run.err;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tr
