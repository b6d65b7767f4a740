# cmake -DOUTPUT=glsl_sources.cpp -DSOURCES=a.glsl|b.glsl|... -P embed_glsl.cmake: writes a C++
# source defining, for each GLSL file NAME.glsl, tr::gl::detail::glsl::kName (NAME in UpperCamel,
# e.g. volume_vs.glsl -> kVolumeVs) as a raw string holding the file's text. Declared in
# detail/gl_program.h. Nothing is downloaded; project/gl/CMakeLists.txt reruns it when a file
# changes.
string(REPLACE "|" ";" sources "${SOURCES}")
set(text "// Generated from project/gl/shaders/ by project/gl/embed_glsl.cmake: edit the .glsl files.\n")
string(APPEND text "#include <project/gl/detail/gl_program.h>\n\nnamespace tr::gl::detail::glsl {\n")
foreach(source IN LISTS sources)
  get_filename_component(stem "${source}" NAME_WE)
  # snake_case -> kUpperCamel
  string(REPLACE "_" ";" words "${stem}")
  set(name "k")
  foreach(word IN LISTS words)
    string(SUBSTRING "${word}" 0 1 first)
    string(SUBSTRING "${word}" 1 -1 others)
    string(TOUPPER "${first}" first)
    string(APPEND name "${first}${others}")
  endforeach()
  file(READ "${source}" glsl)
  string(FIND "${glsl}" ")glsl\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${source} contains the raw-string delimiter )glsl\"")
  endif()
  string(APPEND text "\n// ${stem}.glsl\nextern const char* const ${name};\n")
  string(APPEND text "const char* const ${name} = R\"glsl(${glsl})glsl\";\n")
endforeach()
string(APPEND text "\n}  // namespace tr::gl::detail::glsl\n")
file(WRITE "${OUTPUT}" "${text}")
