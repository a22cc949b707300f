# Options that change what sierra-render writes.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(sequence EXPECT_OK COMMAND ${RENDER} --generate 129 --size 160x90 --frames 3 --path orbit --out seq/f.png --no-debug)
expect_file(${WORK_DIR}/seq/f_0000.png)
expect_file(${WORK_DIR}/seq/f_0002.png)
expect_no_file(${WORK_DIR}/seq/f_0003.png)
run_app(full EXPECT_OK COMMAND ${RENDER} --generate 129 --size 160x90 --lod full --wireframe --msaa 0 --out full.png --debug-out dbg.png)
expect_file(${WORK_DIR}/full.png)
expect_file(${WORK_DIR}/dbg.png)
run_app(camera EXPECT_OK COMMAND ${RENDER} --generate 65 --size 160x90 --camera-pos 0 60 0 --camera-target 32 0 32 --fov 60 --tau 2 --sea-level 0 --out cam.png --no-debug)
expect_file(${WORK_DIR}/cam.png)
# A heightmap written by the library loads back and renders.
file(WRITE ${WORK_DIR}/small.pgm "P2\n3 2\n255\n0 10 20\n30 40 250\n")
run_app(pgm EXPECT_OK COMMAND ${RENDER} --heightmap small.pgm --size 160x90 --out pgm.png --no-debug)
expect_file(${WORK_DIR}/pgm.png)

# An overlay that would draw nothing says so: curvature has world units, so a
# preset's scale made for unit spacing finds no line on a grid spaced 1000
# apart; the warning names the scale that would, and with it there is no
# warning; nor at unit spacing on a 257 grid.
run_app(faint EXPECT_OK MESSAGE "no curvature line reaches the threshold 0.5" COMMAND ${RENDER}
        --generate 65 --spacing 1000 --preset fig3a --size 160x90 --out faint.png --no-debug)
string(REGEX MATCH "--curvature-scale ([0-9.e+]+) brings the top 5% of samples to 0.5" suggestion
       "${LAST_OUTPUT}")
if(NOT suggestion)
  message(FATAL_ERROR "faint: no suggested scale in\n${LAST_OUTPUT}")
endif()
foreach(run "fixed;--generate;65;--spacing;1000;--curvature-scale;${CMAKE_MATCH_1}"
            "unit;--generate;257")
  list(POP_FRONT run name)
  run_app(faint_${name} EXPECT_OK COMMAND ${RENDER} ${run} --preset fig3a --size 160x90
          --out faint_${name}.png --no-debug)
  if(LAST_OUTPUT MATCHES "curvature field's largest value")
    message(FATAL_ERROR "faint_${name}: warned:\n${LAST_OUTPUT}")
  endif()
endforeach()
