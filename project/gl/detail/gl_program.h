#pragma once
// Compiling and linking the renderer's GLSL programs (project/gl/shaders/, embedded at build
// time by embed_glsl.cmake). Needs a current OpenGL >= 3.3 core context.

#include <core/result.h>

#include <initializer_list>

namespace tr::gl::detail {

// The GLSL sources, one per file of project/gl/shaders/ (k + the file's name in UpperCamel),
// defined in the generated glsl_sources.cpp. None carries a #version line.
namespace glsl {
extern const char* const kShade;
extern const char* const kVolumeVs;
extern const char* const kVolumeFs;
extern const char* const kExactVs;
extern const char* const kExactFs;
extern const char* const kOpaqueVs;
extern const char* const kOpaqueFs;
extern const char* const kImageVs;
extern const char* const kImageFs;
}  // namespace glsl

// Links a program of a vertex and a fragment stage, each compiled from `#version 330 core`
// followed by its parts in order. Returns the program's GL name. Errors: kUnsupported with the
// driver's log and `name` when a stage does not compile or the program does not link (nothing
// is left allocated then).
Result<unsigned int> link_program(std::initializer_list<const char*> vertex_parts,
                                  std::initializer_list<const char*> fragment_parts,
                                  const char* name);

}  // namespace tr::gl::detail
