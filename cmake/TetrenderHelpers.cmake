# tr_add_module(name SOURCES a.cpp ... HEADERS a.h ... DEPS tetrender::x ... [PRIVATE_DEPS ...])
# Adds library tetrender_<name> with alias tetrender::<name>, warnings on, headers installed
# under include/tetrender/<folder of the first header>.
function(tr_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;HEADERS;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(tetrender_${name} ${ARG_SOURCES})
  add_library(tetrender::${name} ALIAS tetrender_${name})
  set_target_properties(tetrender_${name} PROPERTIES EXPORT_NAME ${name}
                                                     POSITION_INDEPENDENT_CODE ON)
  target_include_directories(tetrender_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
    $<INSTALL_INTERFACE:include/tetrender>)
  target_link_libraries(tetrender_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS}
                                                                   tetrender_warnings)
  target_compile_features(tetrender_${name} PUBLIC cxx_std_20)
  foreach(header ${ARG_HEADERS})
    get_filename_component(dir ${header} DIRECTORY)
    file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/${dir})
    install(FILES ${header} DESTINATION include/tetrender/${rel})
  endforeach()
  install(TARGETS tetrender_${name} EXPORT tetrenderTargets
          ARCHIVE DESTINATION lib LIBRARY DESTINATION lib RUNTIME DESTINATION bin)
endfunction()

# tr_front_end_code(target): a test's or a front end's own code (the apps' command lines, the
# Python bindings) drives the libraries and computes little itself, so it is compiled for a short
# build rather than for speed: in the sanitizer build at -O0 under AddressSanitizer alone (the
# libraries keep -O1 and both sanitizers, which is where the checks matter), in an optimized
# build at -O1 (the libraries keep the build type's -O3). The optimizer's passes (over
# instrumented code, with UBSan's checks) are most of such a file's compile time (measured:
# sanitizer cli_pipeline_test.cpp 28.7 s -> 12.4 s, apps/cmd_info.cpp 44 s -> 17 s; Release
# pipeline_test.cpp 15.7 s -> 10.9 s, cmd_info.cpp 22.6 s -> 14.0 s) and little of the tests' run
# time (README, "Tests").
function(tr_front_end_code target)
  if(TETRENDER_SANITIZE)
    target_compile_options(${target} PRIVATE -O0 -fno-sanitize=undefined)
  elseif(CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo|MinSizeRel)$")
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

# tr_add_test(name SOURCES ... DEPS ... LABELS ... [PROCESSORS n]): a GoogleTest executable
# registered with ctest, every test case labelled; PROCESSORS: the cores one test case keeps
# busy (ctest -j counts them, so a test of several processes does not share its cores).
function(tr_add_test name)
  cmake_parse_arguments(ARG "" "PROCESSORS" "SOURCES;DEPS;LABELS" ${ARGN})
  if(NOT ARG_PROCESSORS)
    set(ARG_PROCESSORS 1)
  endif()
  # The real-data picture sweeps (labels realdata and render, one process) check accuracy on
  # ../shared/data's meshes in the Release stage; the code they run is under the sanitizers in
  # the synthetic tests, and the real files' reading in io_realdata. Left out of the sanitizer
  # build for CI time (README, "Tests").
  if(TETRENDER_SANITIZE AND "realdata" IN_LIST ARG_LABELS AND "render" IN_LIST ARG_LABELS
     AND NOT "mpi" IN_LIST ARG_LABELS)
    return()
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main
                                        tetrender_warnings)
  target_compile_definitions(${name} PRIVATE
    TETRENDER_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    TETRENDER_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data"
    TETRENDER_SANITIZED=$<BOOL:${TETRENDER_SANITIZE}>)
  tr_front_end_code(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
  # Labels go on the discovered tests from a script ctest reads after the discovery's own:
  # passed through gtest_discover_tests' PROPERTIES, a list keeps only its first label.
  set(label_script ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  file(WRITE ${label_script}
       "if(NOT \"\${${name}_TESTS}\" STREQUAL \"\")\n"
       "  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${ARG_LABELS}\"\n"
       "                       PROCESSORS ${ARG_PROCESSORS})\n"
       "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${label_script})
endfunction()
