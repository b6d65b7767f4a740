# cmake -DCLANG_FORMAT=... -DSOURCE_DIR=... -P CheckFormat.cmake: fails when a C++ file in the
# engine's folders is not formatted as .clang-format says.
file(GLOB_RECURSE files
  ${SOURCE_DIR}/core/*.h ${SOURCE_DIR}/core/*.cpp ${SOURCE_DIR}/mesh/*.h ${SOURCE_DIR}/mesh/*.cpp
  ${SOURCE_DIR}/io/*.h ${SOURCE_DIR}/io/*.cpp ${SOURCE_DIR}/sort/*.h ${SOURCE_DIR}/sort/*.cpp
  ${SOURCE_DIR}/project/*.h ${SOURCE_DIR}/project/*.cpp ${SOURCE_DIR}/flowvol/*.h
  ${SOURCE_DIR}/flowvol/*.cpp ${SOURCE_DIR}/distributed/*.h ${SOURCE_DIR}/distributed/*.cpp
  ${SOURCE_DIR}/apps/*.h ${SOURCE_DIR}/apps/*.cpp
  ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cpp ${SOURCE_DIR}/bench/*.h
  ${SOURCE_DIR}/bench/*.cpp)
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${files}
                RESULT_VARIABLE result ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "not clang-formatted (run clang-format -i on these):\n${errors}")
endif()
