#pragma once
// The quick look of a mesh file, as `tetrender render MESH` and `tetrender-view MESH` make it:
// the mesh loaded through a Pipeline (which keeps it for the render), the array chosen when
// none is named, a name that is both point and cell data resolved, more volumes loaded, then
// make_quick_scene (pipeline/quick_scene.h).

#include <core/result.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <pipeline/scene.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tr {

struct QuickFileOptions {
    // Which of the two a name that is both point and cell data means (the point data unless
    // cell_data); a flag for a kind the name lacks is an error.
    bool point_data = false, cell_data = false;
    // More volumes in the same space: a mesh file and its array each.
    std::vector<std::pair<std::filesystem::path, std::string>> more;
    // Every time step will be drawn with this scene (`--time-step all`): each volume's other
    // steps are loaded too, and its range, opacity and unit distance cover them all
    // (QuickSceneOptions::series); a note says so.
    bool every_time_step = false;
};

// The scene of `path` (made absolute) at options.time_step. Without options.scalar: the mesh's
// first point array, else its first cell array, else (a mesh without arrays) a field of ones
// handed over in memory (SceneVolume::tets), showing where the mesh is. With cell_data for a
// name that is point data too, the mesh is handed over without that point array. `notes`
// receives what was chosen and make_quick_scene's notes. Errors: loading (the file named, or a
// step of its series), no such array of the kind asked, make_quick_scene's.
Result<Scene> quick_scene_of_file(Pipeline& pipeline, const std::filesystem::path& path,
                                  QuickSceneOptions options, const QuickFileOptions& file,
                                  std::vector<std::string>* notes = nullptr);

}  // namespace tr
