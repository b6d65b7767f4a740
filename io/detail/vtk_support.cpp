#include <io/detail/common.h>
#include <io/detail/vtk_support.h>

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>
#include <vtk_exodusII.h>

#include <mutex>
#include <vector>

namespace tr::io_detail {

namespace {

struct ThreadCapture {
    int depth = 0;
    std::vector<std::string> errors;
};

ThreadCapture& thread_capture() {
    thread_local ThreadCapture capture;
    return capture;
}

// An output window that records errors and warnings of the calling thread and prints nothing.
class CaptureOutputWindow : public vtkOutputWindow {
  public:
    static CaptureOutputWindow* New();
    vtkTypeMacro(CaptureOutputWindow, vtkOutputWindow);

    void DisplayText(const char*) override {}
    void DisplayErrorText(const char* text) override { record_vtk_error(text); }
    void DisplayWarningText(const char*) override {}
    void DisplayGenericWarningText(const char*) override {}
    void DisplayDebugText(const char*) override {}

  protected:
    CaptureOutputWindow() = default;
    ~CaptureOutputWindow() override = default;

  private:
    CaptureOutputWindow(const CaptureOutputWindow&) = delete;
    void operator=(const CaptureOutputWindow&) = delete;
};

vtkStandardNewMacro(CaptureOutputWindow);

void install_output_window() {
    static std::once_flag once;
    std::call_once(once, [] {
        vtkSmartPointer<CaptureOutputWindow> window = vtkSmartPointer<CaptureOutputWindow>::New();
        vtkOutputWindow::SetInstance(window);
        // VTK also logs errors through vtkLogger (loguru) to stderr; a library must not print.
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
        // The Exodus library prints its own errors to stderr in verbose mode.
        ex_opts(EX_DEFAULT);
    });
}

}  // namespace

void record_vtk_error(const char* text) {
    ThreadCapture& capture = thread_capture();
    if (capture.depth > 0 && text != nullptr) capture.errors.emplace_back(text);
}

std::string clean_vtk_message(const std::string& text) {
    std::string body = text;
    // Drop the "ERROR: In file, line N" line.
    if (body.rfind("ERROR:", 0) == 0 || body.rfind("Warning:", 0) == 0) {
        const std::size_t nl = body.find('\n');
        if (nl != std::string::npos) body = body.substr(nl + 1);
    }
    // Drop the "vtkClass (0x...): " prefix.
    const std::size_t paren = body.find("): ");
    if (paren != std::string::npos && paren < 80 && body.rfind("vtk", 0) == 0) {
        body = body.substr(paren + 3);
    }
    std::string line = one_line(body);
    if (line.size() > 400) line = line.substr(0, 400) + "...";
    return line;
}

VtkErrorCapture::VtkErrorCapture() {
    install_output_window();
    ThreadCapture& capture = thread_capture();
    if (capture.depth++ == 0) capture.errors.clear();
}

VtkErrorCapture::~VtkErrorCapture() {
    ThreadCapture& capture = thread_capture();
    if (--capture.depth == 0) capture.errors.clear();
}

bool VtkErrorCapture::has_error() const { return !thread_capture().errors.empty(); }

std::string VtkErrorCapture::first_error() const {
    const ThreadCapture& capture = thread_capture();
    return capture.errors.empty() ? std::string() : clean_vtk_message(capture.errors.front());
}

}  // namespace tr::io_detail
