# Finds IceT, the sort-last image compositing library of ParaView and VisIt, for the distributed
# renderer (distributed/). Defines IceT_FOUND and the imported target IceT::IceT (IceT's core
# and MPI layers; its OpenGL layer is not used).
#
# Looked for, in order:
#  1. An IceT CMake package (IceTConfig.cmake, as an HPC site installs IceT or a module loads
#     it: -DIceT_DIR=... or CMAKE_PREFIX_PATH), whose targets are IceTCore and IceTMPI.
#  2. ParaView's own copy (Debian 12: the `paraview` package's libvtkIceTCore-pv5.11.so and
#     libvtkIceTMPI-pv5.11.so, the headers of `paraview-dev` under
#     include/paraview-5.11/vtkicet/src/include). Only these two libraries are linked: they need
#     libc, libm and the MPI library, never ParaView's VTK (whose symbols clash with Debian's VTK).
# ICET_INCLUDE_DIR and ICET_CORE_LIBRARY / ICET_MPI_LIBRARY may be set by hand instead.

if(TARGET IceT::IceT)
  set(IceT_FOUND TRUE)
  return()
endif()

find_package(IceT CONFIG QUIET)
if(IceT_FOUND AND TARGET IceTCore AND TARGET IceTMPI)
  add_library(IceT::IceT INTERFACE IMPORTED)
  target_link_libraries(IceT::IceT INTERFACE IceTCore IceTMPI)
  if(ICET_INCLUDE_DIRS)
    target_include_directories(IceT::IceT INTERFACE ${ICET_INCLUDE_DIRS})
  endif()
  message(STATUS "Found IceT: its CMake package (${IceT_DIR})")
  return()
endif()

file(GLOB _icet_paraview_dirs LIST_DIRECTORIES true
     /usr/include/paraview-*/vtkicet/src/include /usr/local/include/paraview-*/vtkicet/src/include)
find_path(ICET_INCLUDE_DIR IceT.h HINTS ${_icet_paraview_dirs}
          PATH_SUFFIXES include/IceT include)
find_library(ICET_CORE_LIBRARY NAMES IceTCore vtkIceTCore-pv5.11 vtkIceTCore-pv5.12
             vtkIceTCore-pv5.10 vtkIceTCore)
find_library(ICET_MPI_LIBRARY NAMES IceTMPI vtkIceTMPI-pv5.11 vtkIceTMPI-pv5.12
             vtkIceTMPI-pv5.10 vtkIceTMPI)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(IceT
  REQUIRED_VARS ICET_CORE_LIBRARY ICET_MPI_LIBRARY ICET_INCLUDE_DIR)
if(IceT_FOUND)
  add_library(IceT::IceT INTERFACE IMPORTED)
  target_link_libraries(IceT::IceT INTERFACE ${ICET_CORE_LIBRARY} ${ICET_MPI_LIBRARY})
  target_include_directories(IceT::IceT SYSTEM INTERFACE ${ICET_INCLUDE_DIR})
endif()
mark_as_advanced(ICET_INCLUDE_DIR ICET_CORE_LIBRARY ICET_MPI_LIBRARY)
