#pragma once
// ParaView's camera files (.pvcc, "Save Camera" / "Load Camera" in ParaView): an XML document
// <PVCameraConfiguration> holding one <Proxy> whose <Property name="..."> elements carry
// CameraPosition, CameraFocalPoint, CameraViewUp (3 <Element index value> each),
// CameraViewAngle, CameraParallelScale and CameraParallelProjection (one each). Read into the
// scene's camera, so that a picture can be made from the view a ParaView user saved, and
// written back for ParaView to load.

#include <core/camera.h>
#include <core/result.h>

#include <filesystem>
#include <string>

namespace tr {

// Parses the text of a .pvcc file. Position and focal point are required; view up defaults to
// +y, the angle to 30, parallel projection to off (ParaView's defaults). `source` names the text
// in errors, which say what is missing or wrong ("no CameraPosition", "CameraViewUp element 1:
// 'x' is not a number") and end with check_camera's verdict on the result.
Result<Camera> parse_paraview_camera(const std::string& text, const std::string& source);
Result<Camera> read_paraview_camera(const std::filesystem::path& path);

// The .pvcc text of `camera` (ParaView 5 loads it), and that text written to `path` through a
// temporary file renamed at the end.
std::string paraview_camera_xml(const Camera& camera);
Status write_paraview_camera(const Camera& camera, const std::filesystem::path& path);

}  // namespace tr
