#pragma once
// Setting up a flow volume for `tetrender flowvol` and for scene files: the velocity (steady,
// or over all of a file's time steps) and the seed and options a FlowVolumeSpec describes.

#include <apps/cli_common.h>
#include <flowvol/flow_volume.h>
#include <flowvol/velocity_field.h>
#include <project/scene.h>

#include <string>

namespace tr::apps {

// The 3-component point array `vectors` of `loaded` (read from `path`) as a velocity: steady,
// or with `unsteady` the array at every time step of `path` (.pvd, Exodus), linear in time.
// Errors: no such array (the message lists the vector arrays), `unsteady` on a file with one
// time step, a time step whose mesh differs from the first. Cost: one read per time step.
Result<VelocityField> load_velocity(const std::string& path, const LoadedMesh& loaded,
                                    const std::string& vectors, bool unsteady);

// The seed polygon and growth options a spec describes.
DyeSeed dye_seed(const FlowVolumeSpec& spec);
FlowVolumeOptions flow_volume_options(const FlowVolumeSpec& spec);

}  // namespace tr::apps
