# Shadows, sky light and the sun from a time on the real DEM; automatic fog
# that leaves a far camera's terrain clear; bad values refused clearly.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(dem /usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz)
if(NOT EXISTS ${dem})
  message(FATAL_ERROR "the sample DEMs are missing: apt-get install python-matplotlib-data")
endif()
set(small --size 160x90 --msaa 0 --no-debug)
# On by default: both fields computed once, each with its time.
run_app(relief EXPECT_OK MESSAGE "relief: sky light of 403x344 samples"
        COMMAND ${RENDER} --heightmap ${dem} ${small} --out lit.png)
if(NOT LAST_OUTPUT MATCHES "relief: shadows of the sun at azimuth [0-9.]+, altitude [0-9.]+ \\(0.53 degrees wide\\) computed in [0-9.]+ ms")
  message(FATAL_ERROR "the shadows' computation is logged with its time:\n${LAST_OUTPUT}")
endif()
run_app(plain EXPECT_OK COMMAND ${RENDER} --heightmap ${dem} ${small} --shadows off --sky-light off --out plain.png)
if(LAST_OUTPUT MATCHES "relief:")
  message(FATAL_ERROR "with both fields off none is computed:\n${LAST_OUTPUT}")
endif()
expect_different(${WORK_DIR}/lit.png ${WORK_DIR}/plain.png "--shadows off --sky-light off")
# The sun from a time over the DEM's centre (its .npz bounds), or a given place.
run_app(sun_time EXPECT_OK MESSAGE "sun: 2026-06-21T17:30:00Z over 36."
        COMMAND ${RENDER} --heightmap ${dem} ${small} --sun-time 2026-06-21T19:30:00+02:00 --out timed.png)
if(NOT LAST_OUTPUT MATCHES " N, 84\\.[0-9]+ W: azimuth [0-9.]+, altitude [0-9.]+ degrees")
  message(FATAL_ERROR "the DEM's centre is near 36.4 N, 84.2 W:\n${LAST_OUTPUT}")
endif()
run_app(night EXPECT_OK MESSAGE "below the horizon in every frame"
        COMMAND ${RENDER} --heightmap ${dem} ${small} --sun-time 2026-06-21T04:00:00Z --out night.png)
run_app(sun_step EXPECT_OK MESSAGE "sun of frame 2: "
        COMMAND ${RENDER} --heightmap ${dem} --size 64x36 --msaa 0 --no-debug --path orbit --frames 3
                --sun-time 2026-06-21T14:00:00Z --sun-step 3600 --out step.png)
run_app(place EXPECT_OK MESSAGE "over 10.0000 S, 20.0000 E"
        COMMAND ${RENDER} --generate 65 ${small} --sun-time 2026-06-21T12:00:00Z --latitude -10 --longitude 20 --out place.png)
# Bad values: one clear message each, nothing written.
run_app(no_georeference EXPECT_FAIL EXIT 1 MESSAGE "no georeference"
        COMMAND ${RENDER} --generate 65 ${small} --sun-time 2026-06-21T12:00:00Z --out bad1.png)
run_app(sun_size EXPECT_FAIL EXIT 2 MESSAGE "lighting.sun_size (--sun-size) must be an angular diameter"
        COMMAND ${RENDER} --generate 65 ${small} --sun-size 0 --out bad2.png)
run_app(shadows_maybe EXPECT_FAIL EXIT 2 MESSAGE "--shadows 'maybe': expected on or off"
        COMMAND ${RENDER} --generate 65 ${small} --shadows maybe --out bad3.png)
run_app(bad_time EXPECT_FAIL EXIT 2 MESSAGE "--sun-time '2026-06-31T12:00Z': day out of range"
        COMMAND ${RENDER} --generate 65 ${small} --sun-time 2026-06-31T12:00Z --out bad4.png)
foreach(f bad1.png bad2.png bad3.png bad4.png)
  expect_no_file(${WORK_DIR}/${f})
endforeach()
# A camera seven extents away sees the terrain through no more haze than a
# near one (automatic fog is relative to the framed terrain).
find_program(PYTHON3 python3)
if(PYTHON3)
  set(grid --heightmap ${dem} --height-units none --spacing 1 --size 160x90 --msaa 0 --no-debug)
  run_app(near EXPECT_OK COMMAND ${RENDER} ${grid} --out near.png --depth-out near.npy)
  run_app(far EXPECT_OK COMMAND ${RENDER} ${grid} --camera-pos 200 2500 1500 --out far.png --depth-out far.npy)
  foreach(name near far)
    execute_process(COMMAND ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/terrain_share.py ${WORK_DIR}/${name}.png
                            ${WORK_DIR}/${name}.npy 158.1 188.7 219.3
                    OUTPUT_VARIABLE out RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "terrain_share.py ${name}: ${rc}\n${out}")
    endif()
    string(REGEX MATCH "^[0-9]+" ${name}_clear "${out}")
  endforeach()
  message(STATUS "the terrain's distance from the sky colour: near ${near_clear}, far ${far_clear}")
  math(EXPR limit "${near_clear} * 7 / 10")
  if(near_clear LESS 60 OR far_clear LESS limit)
    message(FATAL_ERROR "the far camera's terrain is mostly fog: its pixels are ${far_clear} from "
                        "the sky colour, the near camera's ${near_clear}")
  endif()
else()
  message(STATUS "python3 not found: the far camera's fog is checked by the GL tests only")
endif()
# sierra-bench frames times frames with and without the relief fields.
run_app(bench_lighting EXPECT_OK MESSAGE "lighting costs (frame medians"
        COMMAND ${BENCH} frames --generate 65 --size 160x90 --frames 2 --lighting-costs --json costs.json)
file(READ ${WORK_DIR}/costs.json costs)
if(NOT costs MATCHES "\"lighting_costs\"")
  message(FATAL_ERROR "the JSON lacks the lighting costs:\n${costs}")
endif()
run_app(bench_lighting_off EXPECT_FAIL EXIT 2 MESSAGE "--lighting-costs compares frames with shadows"
        COMMAND ${BENCH} frames --generate 65 --size 160x90 --frames 2 --lighting-costs --shadows off --sky-light off)
