# cmake -DSOURCE_DIR=... [-DINJECT=FILE:HEADER] -P CheckLayering.cmake: fails when a source file
# includes across a wall of docs/architecture.md. Two tables:
#  - which of our folders each folder may include (`#include <folder/...>`): dependencies point
#    one way, core <- mesh <- {io, sort, project, flowvol} <- flowtex, overlay <- pipeline <-
#    distributed <- apps, python; sort and project never include each other;
#  - which third-party headers each folder may include: VTK only in io/, CGAL and TetGen only in
#    mesh/copyleft/, GL only in project/gl/, GLFW and ImGui only in apps/viewer/, MPI and IceT
#    only in distributed/, FreeType only in overlay/;
# and one rule inside project/: the particle renderers (pbvr_*) and the splatting renderers
# (splat_*, vector_splat, point_spacing) never include each other.
# INJECT adds one include to one file (paths relative to SOURCE_DIR), for the test that proves a
# forbidden edge fails the check.

set(folders core mesh io sort project flowvol flowtex overlay pipeline distributed apps python
            bench fuzz tests)
# Our folders each may include (itself always).
set(allow_core core)
set(allow_mesh core mesh)
set(allow_io core mesh io)
set(allow_sort core mesh sort)
set(allow_project core mesh project)
set(allow_flowvol core mesh flowvol)
set(allow_flowtex core mesh project flowvol flowtex)
set(allow_overlay core mesh project overlay)
set(allow_pipeline core mesh io sort project flowvol flowtex overlay pipeline)
set(allow_distributed core mesh io sort project flowvol flowtex overlay pipeline distributed)
set(allow_apps core mesh io sort project flowvol flowtex overlay pipeline distributed apps)
set(allow_python core mesh io sort project flowvol flowtex overlay pipeline distributed python)
set(allow_bench ${folders})
set(allow_fuzz ${folders})
set(allow_tests ${folders})

# Third-party headers (a regex on the included path) and the folders (path prefixes) they may be
# included from; tests may include none of them but gtest's.
set(third_party vtk CGAL tetgen epoxy GL GLFW imgui mpi IceT ft2build freetype)
set(where_vtk io/)
set(where_CGAL mesh/copyleft/)
set(where_tetgen mesh/copyleft/)
set(where_epoxy project/gl/)
set(where_GL project/gl/)
set(where_GLFW apps/viewer/)
set(where_imgui apps/viewer/)
set(where_mpi distributed/)
set(where_IceT distributed/)
set(where_ft2build overlay/)
set(where_freetype overlay/)

set(violations "")
set(checked 0)
foreach(folder ${folders})
  file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/${folder}/*.h
       ${SOURCE_DIR}/${folder}/*.cpp)
  foreach(source ${sources})
    math(EXPR checked "${checked} + 1")
    file(STRINGS ${SOURCE_DIR}/${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*<")
    if(INJECT)
      string(REPLACE ":" ";" inject "${INJECT}")
      list(GET inject 0 inject_file)
      list(GET inject 1 inject_header)
      if(source STREQUAL inject_file)
        list(APPEND includes "#include <${inject_header}>")
      endif()
    endif()
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*<([^>]*)>.*" "\\1" header "${line}")
      # Our own folders.
      string(REGEX MATCH "^([a-z_]+)/" top "${header}")
      if(top)
        string(REGEX REPLACE "/$" "" top "${top}")
        list(FIND folders ${top} ours)
        if(NOT ours EQUAL -1)
          list(FIND allow_${folder} ${top} allowed)
          if(allowed EQUAL -1 AND NOT top STREQUAL folder)
            string(REPLACE ";" " " may "${allow_${folder}}")
            list(APPEND violations "${source}: includes <${header}> (${folder}/ may include ${may})")
          endif()
        endif()
      endif()
      # Third-party headers.
      foreach(library ${third_party})
        if(header MATCHES "^${library}[/._-]" OR header MATCHES "^${library}\\.h$"
           OR (library STREQUAL "vtk" AND header MATCHES "^vtk[A-Z]"))
          string(FIND "${source}" "${where_${library}}" at)
          if(NOT at EQUAL 0)
            list(APPEND violations "${source}: includes <${header}>, which only ${where_${library}} may")
          endif()
        endif()
      endforeach()
      # Inside project/: the particle and splatting rooms.
      if(source MATCHES "^project/pbvr_" AND header MATCHES "^project/(splat_|vector_splat|point_spacing)")
        list(APPEND violations "${source}: includes <${header}> (PBVR and splatting never include each other)")
      endif()
      if(source MATCHES "^project/(splat_|vector_splat|point_spacing)" AND header MATCHES "^project/pbvr_")
        list(APPEND violations "${source}: includes <${header}> (PBVR and splatting never include each other)")
      endif()
    endforeach()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "includes across the layers of docs/architecture.md:\n  ${text}")
endif()
message(STATUS "layering: ${checked} files, every include within its layer")
