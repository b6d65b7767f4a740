#include <pipeline/quick_file_scene.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace tr {
namespace {

// The steps of `volume`'s series other than its own (none when the file is not a series), as
// the quick look takes them: without the point array `drop` when it is named.
struct SeriesSteps {
    std::vector<std::shared_ptr<const LoadedMesh>> loaded;
    std::vector<std::shared_ptr<const TetMesh>> copies;  // without `drop`
    std::vector<const TetMesh*> meshes;
};

Result<SeriesSteps> other_steps(Pipeline& pipeline, SceneVolume volume, const LoadedMesh& loaded,
                                const std::string& drop = {}) {
    SeriesSteps steps;
    const int count = static_cast<int>(loaded.input.time_values.size());
    const int own = volume.time_step;
    for (int step = 0; step < count; ++step) {
        if (step == own) continue;
        volume.time_step = step;
        TR_TRY(std::shared_ptr<const LoadedMesh> mesh, pipeline.mesh(volume));
        if (!drop.empty()) {
            steps.copies.push_back(without_point_field(mesh->tets, drop));
            steps.meshes.push_back(steps.copies.back().get());
        } else {
            steps.meshes.push_back(&mesh->tets);
        }
        steps.loaded.push_back(std::move(mesh));
    }
    return steps;
}

}  // namespace

Result<Scene> quick_scene_of_file(Pipeline& pipeline, const std::filesystem::path& path,
                                  QuickSceneOptions options, const QuickFileOptions& file,
                                  std::vector<std::string>* notes) {
    SceneVolume volume;
    volume.mesh = std::filesystem::absolute(path);
    volume.time_step = options.time_step;
    TR_TRY(const std::shared_ptr<const LoadedMesh> loaded, pipeline.mesh(volume));
    const TetMesh& mesh = loaded->tets;
    std::vector<std::string> said;
    // No scalar named: the first array, or where the mesh is when it has none.
    std::shared_ptr<const TetMesh> handed_over;
    if (options.scalar.empty()) {
        options.scalar = default_quick_scalar(mesh);
        if (options.scalar.empty()) {
            options.scalar = "constant";
            handed_over = with_constant_field(mesh, options.scalar);
            said.push_back(
                "the mesh has no arrays: showing where it is (give --scalar NAME for a mesh "
                "with arrays)");
        } else {
            said.push_back("no --scalar: showing '" + options.scalar + "', the mesh's first " +
                           (mesh.point_fields().empty() ? "cell" : "point") + " array");
        }
    }
    // A name that is both point and cell data: the point data unless cell_data says.
    const auto has = [&](const std::vector<Field>& fields) {
        return std::any_of(fields.begin(), fields.end(),
                           [&](const Field& f) { return f.name == options.scalar; });
    };
    const bool as_point = has(mesh.point_fields());
    const bool as_cell = has(mesh.cell_fields());
    if ((file.point_data && !as_point) || (file.cell_data && !as_cell)) {
        return make_error(ErrorCode::kNotFound,
                          "no " + std::string(file.point_data ? "point" : "cell") + " array '" +
                              options.scalar + "'",
                          path.string());
    }
    if (file.cell_data && as_point) {
        handed_over = without_point_field(mesh, options.scalar);
        said.push_back("--cell-data: '" + options.scalar +
                       "' from the cell data (a scene written now would read the point data)");
    } else if (as_point && as_cell && !file.point_data) {
        said.push_back("'" + options.scalar +
                       "' is both point and cell data: showing the point data (--cell-data for "
                       "the other)");
    }
    // Every step drawn with one scene: its range covers them all.
    std::vector<SeriesSteps> series;
    if (file.every_time_step) {
        TR_TRY(SeriesSteps steps,
               other_steps(pipeline, volume, *loaded,
                           file.cell_data && as_point ? options.scalar : std::string()));
        options.series = steps.meshes;
        if (!steps.meshes.empty()) {
            said.push_back("--time-step all: the range covers all " +
                           std::to_string(steps.meshes.size() + 1) + " time steps of '" +
                           options.scalar + "'");
        }
        series.push_back(std::move(steps));
    }
    // More volumes in the same space, each loaded at the same time step.
    std::vector<std::shared_ptr<const LoadedMesh>> others;
    std::vector<QuickVolume> more;
    for (const auto& [other_path, array] : file.more) {
        SceneVolume other;
        other.mesh = std::filesystem::absolute(other_path);
        other.time_step = options.time_step;
        TR_TRY(std::shared_ptr<const LoadedMesh> other_mesh, pipeline.mesh(other));
        more.push_back({other.mesh, &other_mesh->tets, array, -1, "", {}});
        if (file.every_time_step) {
            TR_TRY(SeriesSteps steps, other_steps(pipeline, other, *other_mesh));
            more.back().series = steps.meshes;
            series.push_back(std::move(steps));
        }
        others.push_back(std::move(other_mesh));
    }
    // Of a field of ones, the note that it is constant says nothing new.
    std::vector<std::string> scene_notes;
    const TetMesh& shown = handed_over ? *handed_over : mesh;
    auto scene = make_quick_scene(volume.mesh, shown, options, more, &scene_notes);
    if (!scene.ok()) {
        Error e = scene.error();
        if (e.where.empty()) e.where = path.string();  // else it names the file already
        return e;
    }
    const bool ones = handed_over && !as_point && !as_cell;
    if (!ones) said.insert(said.end(), scene_notes.begin(), scene_notes.end());
    if (handed_over) scene->volumes[0].tets = handed_over;  // the file has no such array
    if (notes) notes->insert(notes->end(), said.begin(), said.end());
    return scene;
}

}  // namespace tr
