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

# The scale a faint overlay's warning suggests (the one that brings the top 5%
# of the samples to `target`) into `suggested`; fails without one.
function(suggested_scale name target)
  string(REGEX MATCH
         "--curvature-scale ([0-9.e+]+), which 'auto' picks, brings the top 5% of samples to ${target}"
         suggestion "${LAST_OUTPUT}")
  if(NOT suggestion)
    message(FATAL_ERROR "${name}: no suggested scale in\n${LAST_OUTPUT}")
  endif()
  set(suggested ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

# --curvature-scale auto chose `scale` (bringing the top 5% to `what`) and
# warned of nothing.
function(expect_auto_scale name scale what)
  string(FIND "${LAST_OUTPUT}" "curvature scale auto: ${scale} (the top 5% of samples at ${what})"
         at)
  if(at EQUAL -1 OR LAST_OUTPUT MATCHES "warning: overlays")
    message(FATAL_ERROR "${name}: warned or chose another scale than ${scale}:\n${LAST_OUTPUT}")
  endif()
endfunction()

# An overlay that would draw nothing says so, with the scale that would show
# it. Curvature has world units, so a preset's scale made for unit spacing
# finds no sample over the threshold on a grid spaced 1000 apart; on the
# generator's smooth 257 grid at unit spacing a few samples pass but no path
# through them reaches fig3a's minimum length. With the suggested scale each
# draws lines and says nothing, and so does --curvature-scale auto, which
# picks that scale itself.
foreach(case "faint;no curvature line reaches the threshold 0.5;--generate;65;--spacing;1000"
             "short;but no path through them has the minimum length of 6 vertices;--generate;257")
  list(POP_FRONT case name message)
  run_app(${name} EXPECT_OK MESSAGE "${message}" COMMAND ${RENDER} ${case} --preset fig3a
          --size 160x90 --out ${name}.png --no-debug)
  if(NOT LAST_OUTPUT MATCHES "overlays: 0 lines")
    message(FATAL_ERROR "${name}: lines drawn beside the warning:\n${LAST_OUTPUT}")
  endif()
  suggested_scale(${name} 0.5)
  run_app(${name}_fixed EXPECT_OK COMMAND ${RENDER} ${case} --preset fig3a --curvature-scale
          ${suggested} --size 160x90 --out ${name}_fixed.png --no-debug)
  if(LAST_OUTPUT MATCHES "warning: overlays" OR NOT LAST_OUTPUT MATCHES "overlays: [1-9][0-9]* lines")
    message(FATAL_ERROR "${name}_fixed: warned or drew no line:\n${LAST_OUTPUT}")
  endif()
  run_app(${name}_auto EXPECT_OK COMMAND ${RENDER} ${case} --preset fig3a --curvature-scale auto
          --size 160x90 --out ${name}_auto.png --no-debug)
  expect_auto_scale(${name}_auto ${suggested} "the line threshold 0.5")
  if(NOT LAST_OUTPUT MATCHES "overlays: [1-9][0-9]* lines")
    message(FATAL_ERROR "${name}_auto: drew no line:\n${LAST_OUTPUT}")
  endif()
endforeach()

# Hatches whose strokes are nearly all transparent say so too (95% of the
# samples under 0.1, their opacity): fig4a's reinforced field on the
# generator's 257 grid, and fig4b on a grid spaced 1000 apart. With the
# suggested scale, or auto, there is no warning.
foreach(case "reinforced;--generate;257;--preset;fig4a"
             "spaced;--generate;65;--spacing;1000;--preset;fig4b")
  list(POP_FRONT case name)
  run_app(hatch_${name} EXPECT_OK MESSAGE "the hatches are all but transparent" COMMAND ${RENDER}
          ${case} --size 160x90 --out hatch_${name}.png --no-debug)
  suggested_scale(hatch_${name} 1)
  run_app(hatch_${name}_fixed EXPECT_OK COMMAND ${RENDER} ${case} --curvature-scale
          ${suggested} --size 160x90 --out hatch_${name}_fixed.png --no-debug)
  if(LAST_OUTPUT MATCHES "warning: overlays")
    message(FATAL_ERROR "hatch_${name}_fixed: warned:\n${LAST_OUTPUT}")
  endif()
  run_app(hatch_${name}_auto EXPECT_OK COMMAND ${RENDER} ${case} --curvature-scale auto
          --size 160x90 --out hatch_${name}_auto.png --no-debug)
  expect_auto_scale(hatch_${name}_auto ${suggested} "full hatch opacity")
endforeach()

# auto from a scale of 0 (an all-zero field) starts from scale 1 instead.
run_app(auto_from_zero EXPECT_OK COMMAND ${RENDER} --generate 257 --preset fig3a --curvature-scale 0
        --curvature-scale auto --size 160x90 --out auto_from_zero.png --no-debug)
if(LAST_OUTPUT MATCHES "warning: overlays" OR NOT LAST_OUTPUT MATCHES "overlays: [1-9][0-9]* lines")
  message(FATAL_ERROR "auto_from_zero: warned or drew no line:\n${LAST_OUTPUT}")
endif()

# auto with level control is refused (levels remap the values it would measure).
run_app(auto_levels EXPECT_FAIL MESSAGE "--curvature-scale) is auto, which picks the scale from the values"
        COMMAND ${RENDER} --generate 65 --preset fig3a --curvature-scale auto --levels 0.1,0.9,1
        --size 160x90 --out auto_levels.png --no-debug)
expect_no_file(${WORK_DIR}/auto_levels.png)
