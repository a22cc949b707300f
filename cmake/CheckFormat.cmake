# Fails when a C++ source of the tree differs from what .clang-format makes of
# it, naming the files. Run by ctest as style.clang_format:
#   cmake -DCLANG_FORMAT=clang-format -DSOURCE_DIR=<repo> -P CheckFormat.cmake
file(GLOB_RECURSE sources RELATIVE ${SOURCE_DIR}
     ${SOURCE_DIR}/engine/*.cpp ${SOURCE_DIR}/engine/*.h ${SOURCE_DIR}/apps/*.cpp
     ${SOURCE_DIR}/apps/*.h ${SOURCE_DIR}/tests/*.cpp ${SOURCE_DIR}/tests/*.h)
list(LENGTH sources count)
if(count LESS 100)
  message(FATAL_ERROR "found only ${count} sources under ${SOURCE_DIR}: wrong SOURCE_DIR?")
endif()
set(unformatted "")
foreach(f IN LISTS sources)
  execute_process(COMMAND ${CLANG_FORMAT} --dry-run -Werror --style=file ${f}
                  WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    list(APPEND unformatted ${f})
  endif()
endforeach()
if(unformatted)
  list(JOIN unformatted "\n  " names)
  message(FATAL_ERROR "not formatted by .clang-format (run clang-format -i on them):\n  ${names}")
endif()
message(STATUS "${count} sources follow .clang-format")
