#pragma once
// Private: captures what VTK reports (errors, warnings) instead of letting it print. std only;
// the VTK side lives in vtk_support.cpp.

#include <string>

namespace tr::io_detail {

// While alive, VTK error and warning text raised on this thread is recorded (never printed).
// The first construction installs, once and thread-safely, an output window that captures.
class VtkErrorCapture {
  public:
    VtkErrorCapture();
    ~VtkErrorCapture();
    VtkErrorCapture(const VtkErrorCapture&) = delete;
    VtkErrorCapture& operator=(const VtkErrorCapture&) = delete;

    bool has_error() const;
    // The first error recorded since construction, cleaned to one line ("" when none).
    std::string first_error() const;
};

// Records VTK error text (as VTK formats it: "ERROR: In file, line N\nClass (0x..): text") on
// this thread; called by the output window and by ErrorEvent observers.
void record_vtk_error(const char* text);

// "ERROR: In x.cxx, line 12\nvtkFoo (0x1234): Bad thing\n\n" -> "Bad thing".
std::string clean_vtk_message(const std::string& text);

}  // namespace tr::io_detail
