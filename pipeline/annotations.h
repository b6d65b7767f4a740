#pragma once
// Annotations on a rendered picture of a scene (overlay/): the colour bar of a volume's
// transfer function, the bounding box of the scene's meshes and an axes triad, drawn with the
// scene's camera. Called after Pipeline::render on its image; the legend is off in scene files
// compared pixel for pixel unless asked for (the caller decides: `tetrender render --legend`).

#include <core/image.h>
#include <core/result.h>
#include <overlay/legend.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>

namespace tr {

struct AnnotationOptions {
    bool legend = true;
    bool bounding_box = false;
    bool axes = false;
    // A legend for every volume of a scene of several (each placed off the volume and off the
    // legends before it), or volume 0's only.
    bool every_volume = true;
    // The legend's settings. Left empty, the title is volume 0's array ("name" or "name[c]" for
    // a component) and the range its transfer function's colour points'; the background is the
    // scene's. The title and range given here are volume 0's; other volumes' legends always
    // take their own. A volume made with a log scale (SceneVolume::log_scale) gets a log axis.
    LegendSpec legend_spec;
    Vec3f box_color{0.85f, 0.85f, 0.85f};
};

// Whether a picture carries the legend when the user did not say (`--legend auto`): a quick
// look of a mesh file does, except in the classic look (whose pictures stay comparable with
// older ones); a scene file's picture does not (compared pixel for pixel with others').
inline bool legend_by_default(bool scene_file, bool classic_look) {
    return !scene_file && !classic_look;
}

// Draws what `options` asks onto `image`, which must be the scene's picture (scene.width x
// scene.height). The bounding box is that of every volume's mesh, taken from `pipeline`'s cache
// (loaded if it is not there). Errors: an image of another size; a legend's (a picture too
// small for it, a log scale over a range that is not positive; "volume i: " in front when the
// scene has several); loading a mesh.
Status annotate(Image& image, const Scene& scene, Pipeline& pipeline,
                const AnnotationOptions& options);

}  // namespace tr
