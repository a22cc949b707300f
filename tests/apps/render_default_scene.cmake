# sierra-render with no arguments writes the default scene and debug snapshot.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(default EXPECT_OK COMMAND ${RENDER})
expect_file(${WORK_DIR}/out/frame.png)
expect_file(${WORK_DIR}/out/debug.png)
run_app(help EXPECT_OK MESSAGE "--heightmap" COMMAND ${RENDER} --help)
