#include <core/result.h>

namespace tr {

const char* error_code_name(ErrorCode code) {
    switch (code) {
        case ErrorCode::kInvalidArgument:
            return "invalid argument";
        case ErrorCode::kNotFound:
            return "not found";
        case ErrorCode::kParse:
            return "parse error";
        case ErrorCode::kUnsupported:
            return "unsupported";
        case ErrorCode::kInvalidMesh:
            return "invalid mesh";
        case ErrorCode::kIo:
            return "i/o error";
        case ErrorCode::kInternal:
            return "internal error";
    }
    return "error";
}

std::string Error::to_string() const {
    std::string line = where.empty() ? std::string() : where + ": ";
    line += "error: ";
    line += message;
    // Keep it one line whatever a third-party library put in the message.
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    return line;
}

}  // namespace tr
