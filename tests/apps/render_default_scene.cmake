# sierra-render with no arguments writes the default scene and debug snapshot.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(default EXPECT_OK COMMAND ${RENDER})
expect_png_size(${WORK_DIR}/out/frame.png 1280 720)
# The default scene's panel fits beside its frame: the snapshot is the frame's size.
expect_png_size(${WORK_DIR}/out/debug.png 1280 720)

# png_stats(PREFIX FILE X0 Y0 X1 Y1): sierra_png_stats of that rectangle as
# PREFIX_not_corner, PREFIX_dark and PREFIX_bright (shares 0..1, see png_stats.cpp).
function(png_stats prefix file x0 y0 x1 y1)
  execute_process(COMMAND ${PNG_STATS} ${file} ${x0} ${y0} ${x1} ${y1}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "sierra_png_stats ${file}: exit ${rc}\n${err}")
  endif()
  message(STATUS "${file} [${x0},${x1})x[${y0},${y1}): ${out}")
  foreach(key not_corner dark bright)
    string(REGEX MATCH "${key} ([0-9.]+)" _ "${out}")
    set(${prefix}_${key} ${CMAKE_MATCH_1} PARENT_SCOPE)
  endforeach()
endfunction()
# expect_share(VALUE OP LIMIT WHAT): VALUE (a share) LESS or GREATER than LIMIT.
function(expect_share value op limit what)
  if(NOT value ${op} limit)
    message(FATAL_ERROR "${what}: ${value}, expected ${op} ${limit}")
  endif()
endfunction()

# The frame shows the terrain, not sky alone: the default camera frames the
# whole terrain (seen obliquely from the south-west, a 5% margin), which
# covers 25.5% of the 1280x720 frame (measured: the same share for any
# threshold from 0 to 24 levels, the sky being one flat colour); a floor of
# 20% also fails a camera that has lost a fifth of it. The top-left pixel is sky.
png_stats(frame ${WORK_DIR}/out/frame.png 0 0 1280 720)
expect_share(${frame_not_corner} GREATER 0.2 "out/frame.png: share of pixels off the sky colour")
# The snapshot holds the panel on its right: the columns from x = 800 (the
# panel starts near 704) are the panel's dark background with light text,
# none of them sky (measured: 100% off the sky, 80% dark, 3.7% text); the
# frame beside it still shows the terrain (25.1% of its first 700 columns).
png_stats(panel ${WORK_DIR}/out/debug.png 800 0 1280 720)
expect_share(${panel_not_corner} GREATER 0.98 "out/debug.png panel: share of pixels off the sky colour")
expect_share(${panel_dark} GREATER 0.5 "out/debug.png panel: share of dark background pixels")
expect_share(${panel_bright} GREATER 0.01 "out/debug.png panel: share of text pixels")
png_stats(beside ${WORK_DIR}/out/debug.png 0 0 700 720)
expect_share(${beside_not_corner} GREATER 0.2 "out/debug.png frame: share of pixels off the sky colour")
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
