# sierra-render with no arguments writes the default scene and debug snapshot.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(default EXPECT_OK COMMAND ${RENDER})
expect_png_size(${WORK_DIR}/out/frame.png 1280 720)
# The default scene's panel fits beside its frame: the snapshot is the frame's size.
expect_png_size(${WORK_DIR}/out/debug.png 1280 720)
# A frame too short for the panel gets a taller snapshot (the whole panel, no
# scroll bar) of the frame's width; the frame itself keeps its size.
run_app(short_frame EXPECT_OK COMMAND ${RENDER} --generate 129 --size 480x160 --out short.png --debug-out short_debug.png)
expect_png_size(${WORK_DIR}/short.png 480 160)
png_size(w h ${WORK_DIR}/short_debug.png)
if(NOT w EQUAL 480 OR NOT h GREATER 400)
  message(FATAL_ERROR "short_debug.png is ${w}x${h}: expected 480 wide and taller than the 160-pixel frame")
endif()
run_app(short_ui_only EXPECT_OK COMMAND ${RENDER} --generate 129 --size 480x160 --out short2.png --no-debug --snapshot-only short_ui.png)
png_size(w h ${WORK_DIR}/short_ui.png)
if(NOT h GREATER 400)
  message(FATAL_ERROR "short_ui.png is ${w}x${h}: expected taller than the 160-pixel frame")
endif()
run_app(help EXPECT_OK MESSAGE "--heightmap" COMMAND ${RENDER} --help)
