# cmake -DSOURCE_DIR=... [-DINJECT=FILE:HEADER] -P CheckLayering.cmake: fails when a source file
# includes across a wall of docs/architecture.md. Two tables:
#  - which of our rooms each room may include (`#include <room/...>`; a room is a folder, or
#    project/pbvr and project/splat inside project/): dependencies point one way, core <- mesh <-
#    {io, sort, project, flowvol} <- {project/pbvr, project/splat, flowtex, overlay} <- pipeline
#    <- distributed <- apps, python; sort and project never include each other, nor the particle
#    and the splatting renderers, and project/'s shared optics include neither;
#  - which third-party headers each folder may include: VTK only in io/, CGAL and TetGen only in
#    mesh/copyleft/, GL only in project/gl/, GLFW and ImGui only in apps/viewer/, MPI and IceT
#    only in distributed/, FreeType only in overlay/.
# INJECT adds one include to one file (paths relative to SOURCE_DIR), for the test that proves a
# forbidden edge fails the check.

set(folders core mesh io sort project flowvol flowtex overlay pipeline distributed apps python
            bench fuzz tests)
# Rooms inside a folder, named with _ for / in the tables below.
set(subrooms project/pbvr project/splat)
# Our rooms each may include (itself always).
set(allow_core core)
set(allow_mesh core mesh)
set(allow_io core mesh io)
set(allow_sort core mesh sort)
set(allow_project core mesh project)
set(allow_project_pbvr core mesh project)
set(allow_project_splat core mesh project)
set(allow_flowvol core mesh flowvol)
set(allow_flowtex core mesh project flowvol flowtex)
set(allow_overlay core mesh project overlay)
set(allow_pipeline core mesh io sort project project_pbvr project_splat flowvol flowtex overlay
                   pipeline)
set(allow_distributed ${allow_pipeline} distributed)
set(allow_apps ${allow_distributed} apps)
set(allow_python ${allow_distributed} python)
set(allow_bench ${folders} project_pbvr project_splat)
set(allow_fuzz ${allow_bench})
set(allow_tests ${allow_bench})

# The room of a path (a source file or an included header): its sub-room or its top folder, with
# _ for /; empty when the path is in none of our folders.
function(room_of path out)
  set(room "")
  foreach(sub ${subrooms})
    string(FIND "${path}" "${sub}/" at)
    if(at EQUAL 0)
      string(REPLACE "/" "_" room "${sub}")
    endif()
  endforeach()
  if(NOT room)
    string(REGEX MATCH "^([a-z_]+)/" top "${path}")
    string(REGEX REPLACE "/$" "" top "${top}")
    list(FIND folders "${top}" ours)
    if(top AND NOT ours EQUAL -1)
      set(room ${top})
    endif()
  endif()
  set(${out} "${room}" PARENT_SCOPE)
endfunction()

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
      # Our own rooms.
      room_of("${source}" from)
      room_of("${header}" to)
      if(to AND NOT to STREQUAL from)
        list(FIND allow_${from} ${to} allowed)
        if(allowed EQUAL -1)
          string(REPLACE ";" " " may "${allow_${from}}")
          string(REPLACE "project_" "project/" may "${may}")
          string(REPLACE "project_" "project/" from "${from}")
          list(APPEND violations "${source}: includes <${header}> (${from}/ may include ${may})")
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
    endforeach()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "includes across the layers of docs/architecture.md:\n  ${text}")
endif()
message(STATUS "layering: ${checked} files, every include within its layer")
