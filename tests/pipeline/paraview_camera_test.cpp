// ParaView camera files (pipeline/paraview_camera.h): a file laid out as ParaView 5 saves one
// is read to its values, ours is read back bit for bit, and what is not a camera is an error.
#include <pipeline/paraview_camera.h>

#include <gtest/gtest.h>

namespace tr {
namespace {

// As ParaView's "Save Camera" writes it (with the properties we do not use).
const char* const kSaved = R"(<?xml version="1.0"?>
<PVCameraConfiguration description="ParaView camera configuration" version="1.0">
  <Proxy group="views" type="RenderView" id="6395" servers="21">
    <Property name="CameraPosition" id="6395.CameraPosition" number_of_elements="3">
      <Element index="0" value="10.519087611966333"/>
      <Element index="1" value="40.74973775632195"/>
      <Element index="2" value="-20.24019652397463"/>
    </Property>
    <Property name="CameraFocalPoint" id="6395.CameraFocalPoint" number_of_elements="3">
      <Element index="0" value="15.5"/>
      <Element index="1" value="-2.25"/>
      <Element index="2" value="1e-3"/>
    </Property>
    <Property name="CameraViewUp" id="6395.CameraViewUp" number_of_elements="3">
      <Element index="0" value="0"/>
      <Element index="1" value="0.4"/>
      <Element index="2" value="0.9"/>
    </Property>
    <Property name="CenterOfRotation" id="6395.CenterOfRotation" number_of_elements="3">
      <Element index="0" value="1"/>
      <Element index="1" value="2"/>
      <Element index="2" value="3"/>
    </Property>
    <Property name="RotationFactor" id="6395.RotationFactor" number_of_elements="1">
      <Element index="0" value="1"/>
    </Property>
    <Property name="CameraViewAngle" id="6395.CameraViewAngle" number_of_elements="1">
      <Element index="0" value="22.5"/>
    </Property>
    <Property name="CameraFocalDisk" id="6395.CameraFocalDisk" number_of_elements="1">
      <Element index="0" value="1"/>
    </Property>
    <Property name="CameraParallelScale" id="6395.CameraParallelScale" number_of_elements="1">
      <Element index="0" value="12.75"/>
    </Property>
    <Property name="CameraParallelProjection" id="6395.CameraParallelProjection" number_of_elements="1">
      <Element index="0" value="0"/>
    </Property>
  </Proxy>
</PVCameraConfiguration>
)";

TEST(ParaviewCamera, ReadsTheValuesParaviewSaved) {
    const Camera c = parse_paraview_camera(kSaved, "saved.pvcc").value();
    EXPECT_EQ(c.position, Vec3(10.519087611966333, 40.74973775632195, -20.24019652397463));
    EXPECT_EQ(c.focal_point, Vec3(15.5, -2.25, 1e-3));
    EXPECT_EQ(c.view_up, Vec3(0, 0.4, 0.9));
    EXPECT_EQ(c.view_angle, 22.5);
    EXPECT_EQ(c.parallel_scale, 12.75);
    EXPECT_FALSE(c.parallel);
}

TEST(ParaviewCamera, WrittenAndReadBackBitForBit) {
    Camera c;
    c.position = Vec3(0.1, -1.0 / 3.0, 1e-300);
    c.focal_point = Vec3(2.0 / 7.0, 5e7, -3.25);
    c.view_up = Vec3(0.0, 0.0, 1.0);
    c.view_angle = 17.123456789012345;
    c.parallel = true;
    c.parallel_scale = 0.3;
    const Camera back = parse_paraview_camera(paraview_camera_xml(c), "ours").value();
    EXPECT_EQ(back.position, c.position);
    EXPECT_EQ(back.focal_point, c.focal_point);
    EXPECT_EQ(back.view_up, c.view_up);
    EXPECT_EQ(back.view_angle, c.view_angle);
    EXPECT_EQ(back.parallel, c.parallel);
    EXPECT_EQ(back.parallel_scale, c.parallel_scale);
}

TEST(ParaviewCamera, WhatIsNotACameraIsAnError) {
    const auto error = [](const std::string& text) {
        const auto read = parse_paraview_camera(text, "x.pvcc");
        EXPECT_FALSE(read.ok()) << text;
        return read.ok() ? std::string() : read.error().message;
    };
    EXPECT_NE(error("<VTKFile/>").find("not a ParaView camera file"), std::string::npos);
    std::string text = kSaved;
    const auto cut = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        t.replace(t.find(from), from.size(), to);
        return t;
    };
    EXPECT_NE(error(cut("\"CameraPosition\"", "\"Elsewhere\"")).find("no CameraPosition"),
              std::string::npos);
    EXPECT_NE(error(cut("value=\"-2.25\"", "value=\"minus two\"")).find("is not a number"),
              std::string::npos);
    EXPECT_NE(error(cut("value=\"15.5\"/>\n      <Element index=\"1\" value=\"-2.25\"",
                        "value=\"15.5\"/>\n      <Element index=\"7\" value=\"-2.25\""))
                  .find("no element 1"),
              std::string::npos);
    // A camera that cannot make rays: view up zero.
    text = cut("value=\"0.4\"", "value=\"0\"");
    EXPECT_NE(error(cut("value=\"0.9\"", "value=\"0\"")).find("view_up is zero"),
              std::string::npos);
    EXPECT_FALSE(read_paraview_camera("/nonexistent/x.pvcc").ok());
}

}  // namespace
}  // namespace tr
