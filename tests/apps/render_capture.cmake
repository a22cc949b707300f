# Frame formats by name (PNG, JPEG), their options, and the errors of bad ones.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(base --generate 65 --size 160x90 --msaa 0 --no-debug)

# The first bytes of a file as hex.
function(magic file count out)
  file(READ ${file} head LIMIT ${count} HEX)
  set(${out} ${head} PARENT_SCOPE)
endfunction()

# A JPEG sequence: every frame a JPEG, slices the same bytes as the whole run.
run_app(jpeg_all EXPECT_OK COMMAND ${RENDER} ${base} --path orbit --frames 4 --out jpg/f.jpg)
run_app(jpeg_part EXPECT_OK COMMAND ${RENDER} ${base} --path orbit --frame-count 4 --frames 2:3 --out part/f.jpg)
foreach(k 0000 0001 0002 0003)
  expect_file(${WORK_DIR}/jpg/f_${k}.jpg)
  magic(${WORK_DIR}/jpg/f_${k}.jpg 3 head)
  if(NOT head STREQUAL "ffd8ff")
    message(FATAL_ERROR "jpg/f_${k}.jpg is not a JPEG (starts ${head})")
  endif()
endforeach()
expect_same(${WORK_DIR}/jpg/f_0003.jpg ${WORK_DIR}/part/f_0003.jpg)
expect_no_file(${WORK_DIR}/part/f_0000.jpg)
# Quality changes the file; .jpeg in any case is JPEG too.
run_app(jpeg_q90 EXPECT_OK COMMAND ${RENDER} ${base} --out q90.JPEG)
run_app(jpeg_q30 EXPECT_OK COMMAND ${RENDER} ${base} --jpeg-quality 30 --out q30.jpeg)
magic(${WORK_DIR}/q90.JPEG 3 head)
if(NOT head STREQUAL "ffd8ff")
  message(FATAL_ERROR "q90.JPEG is not a JPEG (starts ${head})")
endif()
file(SIZE ${WORK_DIR}/q90.JPEG big)
file(SIZE ${WORK_DIR}/q30.jpeg small)
if(NOT small LESS big)
  message(FATAL_ERROR "--jpeg-quality 30 (${small} bytes) is not smaller than 90 (${big} bytes)")
endif()

# PNG levels: the same picture (png_stats' summary of it; the encoders are lossless, see
# tests/capture), best no larger than fast.
run_app(png_fast EXPECT_OK COMMAND ${RENDER} ${base} --out fast.png)
run_app(png_best EXPECT_OK COMMAND ${RENDER} ${base} --png-compression best --out best.png)
expect_different(${WORK_DIR}/fast.png ${WORK_DIR}/best.png "--png-compression best")
run_app(stats_fast EXPECT_OK COMMAND ${PNG_STATS} ${WORK_DIR}/fast.png 0 0 160 90)
set(fastStats "${LAST_OUTPUT}")
run_app(stats_best EXPECT_OK COMMAND ${PNG_STATS} ${WORK_DIR}/best.png 0 0 160 90)
if(NOT fastStats STREQUAL LAST_OUTPUT)
  message(FATAL_ERROR "fast and best PNGs hold different pixels:\n${fastStats}\n${LAST_OUTPUT}")
endif()
file(SIZE ${WORK_DIR}/fast.png fastBytes)
file(SIZE ${WORK_DIR}/best.png bestBytes)
if(bestBytes GREATER fastBytes)
  message(FATAL_ERROR "best (${bestBytes} bytes) is larger than fast (${fastBytes} bytes)")
endif()

# Bad requests: one message naming the option, exit 2, nothing written.
run_app(jpeg_alpha EXPECT_FAIL EXIT 2 MESSAGE "JPEG has no alpha channel" COMMAND ${RENDER} ${base} --alpha --out a.jpg)
run_app(jpeg_quality EXPECT_FAIL EXIT 2 MESSAGE "--jpeg-quality" COMMAND ${RENDER} ${base} --jpeg-quality 101 --out b.jpg)
run_app(png_level EXPECT_FAIL EXIT 2 MESSAGE "--png-compression: 'max' is not one of fast, default, best"
        COMMAND ${RENDER} ${base} --png-compression max --out c.png)
run_app(queue_bound EXPECT_FAIL EXIT 2 MESSAGE "--max-queued-frames" COMMAND ${RENDER} ${base} --max-queued-frames -2 --out d.png)
run_app(other_format EXPECT_FAIL EXIT 2 MESSAGE ".png, .jpg or .jpeg" COMMAND ${RENDER} ${base} --out e.webp)
foreach(f a.jpg b.jpg c.png d.png e.webp)
  expect_no_file(${WORK_DIR}/${f})
endforeach()
