# sierra-render --zones with bad zone maps and palettes: one clear
# "sierra-render: error:" message naming the file, exit 1 for bad files and 2
# for bad option values (as apps/common/AppMain), and no frame written.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)

set(MAP ${ASSETS_DIR}/zones/default_zones.png)
set(PALETTE ${ASSETS_DIR}/palettes/default.json)
# A small terrain and frame: the errors come before any frame is drawn.
set(SMALL --generate 65 --size 64x36 --no-debug)

# run_bad(NAME EXIT MESSAGE args...): fails with that exit code and message,
# the message on one "sierra-render: error:" line, and writes no frame.
function(run_bad name code message)
  run_app(${name} EXPECT_FAIL EXIT ${code} MESSAGE "${message}" COMMAND ${RENDER} ${SMALL} ${ARGN} --out ${name}.png)
  string(REGEX MATCHALL "sierra-render: error: " lines "${LAST_OUTPUT}")
  list(LENGTH lines count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "${name}: expected one error line, got ${count}:\n${LAST_OUTPUT}")
  endif()
  string(FIND "${LAST_OUTPUT}" "sierra-render: error: " at)
  string(SUBSTRING "${LAST_OUTPUT}" ${at} -1 errorLine)
  string(FIND "${errorLine}" "${message}" found)
  if(found EQUAL -1)
    message(FATAL_ERROR "${name}: '${message}' is not on the error line:\n${LAST_OUTPUT}")
  endif()
  expect_no_file(${WORK_DIR}/${name}.png)
  set(LAST_OUTPUT "${LAST_OUTPUT}" PARENT_SCOPE)
endfunction()

# Zone maps.
run_bad(map_missing 1 "none.png" --zones none.png)
file(WRITE ${WORK_DIR}/notimage.png "this is not a png at all")
run_bad(map_corrupt 1 "is not an image" --zones notimage.png)
# A truncated PNG: the real header, half the data.
file(SIZE ${MAP} mapSize)
math(EXPR half "${mapSize} / 2")
execute_process(COMMAND head -c ${half} ${MAP} OUTPUT_FILE ${WORK_DIR}/truncated.png)
run_bad(map_truncated 1 "truncated.png" --zones truncated.png)
# A colour the palette does not name: the colour and its first pixel.
file(MAKE_DIRECTORY ${WORK_DIR}/p)
file(COPY ${ASSETS_DIR}/tiles/grass.png ${ASSETS_DIR}/tiles/sand.png DESTINATION ${WORK_DIR}/p)
file(WRITE ${WORK_DIR}/p/short.json "{\"zones\": [{\"name\": \"grass\", \"colour\": \"#4f8f37\", \"tile\": \"grass.png\"}]}")
run_bad(map_unknown_colour 1 "is not in the palette" --zones ${MAP} --palette p/short.json)
if(NOT LAST_OUTPUT MATCHES "colour #[0-9a-f]+ at pixel \\([0-9]+, [0-9]+\\)")
  message(FATAL_ERROR "unknown colour message lacks the colour or the pixel: ${LAST_OUTPUT}")
endif()
# Wrong size: a Figure 1 map (its one pixel is the borderline colour, grey
# 0x20 here) smaller than the 2x2 its borderlines need.
file(WRITE ${WORK_DIR}/p/grey.json
     "{\"borderline\": \"#202020\", \"zones\": [{\"name\": \"grass\", \"colour\": \"#4f8f37\", \"tile\": \"grass.png\"}]}")
file(WRITE ${WORK_DIR}/tiny.pgm "P5\n1 1\n255\n ")
run_bad(map_too_small 1 "tiny.pgm" --zones tiny.pgm --palette p/grey.json)

# Palettes.
file(WRITE ${WORK_DIR}/bad.json "{\"zones\": [oops")
run_bad(palette_not_json 1 "not a JSON file" --zones auto --palette bad.json)
run_bad(palette_missing 1 "nowhere.json" --zones auto --palette nowhere.json)
file(WRITE ${WORK_DIR}/p/missing_tile.json "{\"zones\": [{\"name\": \"a\", \"colour\": \"#ff0000\", \"tile\": \"none.png\"}]}")
run_bad(palette_missing_tile 1 "does not exist" --zones auto --palette p/missing_tile.json)
# Tiles of two sizes cannot share the tile array. The map: two grey zones
# (0x20, 0x21), two pixels.
file(WRITE ${WORK_DIR}/grey2.pgm "P5\n2 1\n255\n !")
run_app(small_tile EXPECT_OK COMMAND ${GEN} tiles --out p/small --size 64 --only sand)
file(WRITE ${WORK_DIR}/p/sizes.json "{\"zones\": [{\"name\": \"a\", \"colour\": \"#202020\", \"tile\": \"grass.png\"},
  {\"name\": \"b\", \"colour\": \"#212121\", \"tile\": \"small/sand.png\"}]}")
run_bad(palette_tile_sizes 1 "must be 256x256" --zones grey2.pgm --palette p/sizes.json)
file(WRITE ${WORK_DIR}/p/notile.json "{\"zones\": [{\"name\": \"a\", \"colour\": \"#202020\", \"tile\": \"grass.png\"},
  {\"name\": \"b\", \"colour\": \"#212121\", \"tile\": \"../notimage.png\"}]}")
run_bad(palette_tile_not_image 1 "notimage.png" --zones grey2.pgm --palette p/notile.json)

# Option values: usage errors.
run_bad(blend_unknown 2 "--blend" --zones auto --blend smooth)
run_bad(debug_view_unknown 2 "--debug-view" --zones auto --debug-view ids)
run_bad(band_too_wide 2 "--band" --zones auto --band 5000)
run_bad(band_not_number 2 "--band" --zones auto --band wide)
run_bad(epsilon_negative 2 "--zone-epsilon" --zones auto --zone-epsilon -1)
