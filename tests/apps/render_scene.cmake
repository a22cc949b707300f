# Scene files, frame ranges, options that must change the frame, RGBA and depth.
cmake_policy(SET CMP0053 NEW)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(base --generate 65 --size 160x90 --msaa 0 --no-debug)

# --print-config, fed back with --config, renders the same bytes.
run_app(render_direct EXPECT_OK COMMAND ${RENDER} ${base} --tau 2 --sun-azimuth 100 --azimuth 300 --out direct.png)
run_app(print_config EXPECT_OK MESSAGE "\"tau\"" COMMAND ${RENDER} ${base} --tau 2 --sun-azimuth 100 --azimuth 300 --print-config)
file(WRITE ${WORK_DIR}/scene.json "${LAST_OUTPUT}")
expect_no_file(${WORK_DIR}/out/frame.png)
run_app(render_config EXPECT_OK COMMAND ${RENDER} --config scene.json --out config.png)
expect_same(${WORK_DIR}/direct.png ${WORK_DIR}/config.png)
# Options beside --config override it.
run_app(render_override EXPECT_OK COMMAND ${RENDER} --config scene.json --tau 8 --out override.png)
expect_different(${WORK_DIR}/direct.png ${WORK_DIR}/override.png "--tau beside --config")
# Bad scene files: the key, the file and the expected type.
file(WRITE ${WORK_DIR}/unknown.json "{\"camera\": {\"fvo\": 30}}")
run_app(unknown_key EXPECT_FAIL MESSAGE "fvo" COMMAND ${RENDER} --config unknown.json --out u.png)
file(WRITE ${WORK_DIR}/wrongtype.json "{\"lod\": {\"tau\": \"fine\"}}")
run_app(wrong_type EXPECT_FAIL MESSAGE "lod.tau" COMMAND ${RENDER} --config wrongtype.json --out w.png)
expect_no_file(${WORK_DIR}/u.png)
expect_no_file(${WORK_DIR}/w.png)

# --frames A:B writes exactly frames A..B of the whole run, same names, same bytes.
run_app(orbit_all EXPECT_OK COMMAND ${RENDER} ${base} --path orbit --frames 6 --out all/f.png)
run_app(orbit_part EXPECT_OK COMMAND ${RENDER} ${base} --path orbit --frame-count 6 --frames 3:5 --out part/f.png)
foreach(k 0003 0004 0005)
  expect_same(${WORK_DIR}/all/f_${k}.png ${WORK_DIR}/part/f_${k}.png)
endforeach()
foreach(k 0000 0001 0002 0006)
  expect_no_file(${WORK_DIR}/part/f_${k}.png)
endforeach()
expect_different(${WORK_DIR}/all/f_0000.png ${WORK_DIR}/all/f_0003.png "orbit frames")
# A fixed camera over several frames needs a path.
run_app(still_sequence EXPECT_FAIL MESSAGE "--path" COMMAND ${RENDER} ${base} --camera-pos 0 60 0 --frames 3 --out s.png)
expect_no_file(${WORK_DIR}/s_0000.png)

# Each option changes the frame where it should.
run_app(plain EXPECT_OK COMMAND ${RENDER} ${base} --out plain.png)
set(cases "tau|--tau|8" "wireframe|--wireframe" "sea|--sea-level|none" "sun|--sun-azimuth|60"
          "fog|--fog|0" "azimuth|--azimuth|45" "ortho|--ortho" "elevation|--elevation|60")
foreach(case ${cases})
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 name)
  list(SUBLIST parts 1 -1 args)
  run_app(option_${name} EXPECT_OK COMMAND ${RENDER} ${base} ${args} --out opt_${name}.png)
  expect_different(${WORK_DIR}/plain.png ${WORK_DIR}/opt_${name}.png "${args}")
endforeach()

# --alpha writes an RGBA PNG (IHDR colour type 6), the default RGB (type 2).
run_app(alpha EXPECT_OK COMMAND ${RENDER} ${base} --alpha --out alpha.png)
file(READ ${WORK_DIR}/alpha.png type HEX OFFSET 25 LIMIT 1)
file(READ ${WORK_DIR}/plain.png plainType HEX OFFSET 25 LIMIT 1)
if(NOT type STREQUAL "06" OR NOT plainType STREQUAL "02")
  message(FATAL_ERROR "PNG colour types: --alpha ${type}, default ${plainType} (expected 06 and 02)")
endif()

# --depth-out writes float32 .npy of the frame's shape.
run_app(depth EXPECT_OK COMMAND ${RENDER} ${base} --depth-out depth.npy --out d.png)
file(READ ${WORK_DIR}/depth.npy header OFFSET 10 LIMIT 70)
string(FIND "${header}" "'descr': '<f4'" f4)
string(FIND "${header}" "'shape': (90, 160)" shape)
if(f4 EQUAL -1 OR shape EQUAL -1)
  message(FATAL_ERROR "depth.npy header: ${header}")
endif()
file(SIZE ${WORK_DIR}/depth.npy size)
math(EXPR payload "160 * 90 * 4")
if(size LESS payload)
  message(FATAL_ERROR "depth.npy holds ${size} bytes, fewer than ${payload}")
endif()
