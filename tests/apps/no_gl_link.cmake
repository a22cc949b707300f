# Programs that need no GL do not link it (issue 6): sierra-bench (static;
# frames runs sierra-bench-frames), sierra-gen and sierra-tin. sierra-render is
# the control: it must show what the check looks for.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)

# Sets ${out} to TRUE when `program` needs a GL or EGL library or holds ImGui.
function(links_gl program out)
  execute_process(COMMAND readelf -d ${program} OUTPUT_VARIABLE dynamic RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "readelf failed on ${program}")
  endif()
  execute_process(COMMAND nm -C --defined-only ${program} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm failed on ${program}")
  endif()
  if(dynamic MATCHES "lib(EGL|GL|OpenGL|GLX|gbm)\\.so" OR symbols MATCHES "ImGui::")
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()

links_gl(${RENDER} render_gl)
if(NOT render_gl)
  message(FATAL_ERROR "the check sees no GL in sierra-render, so it cannot see it anywhere")
endif()
get_filename_component(bin_dir ${BENCH} DIRECTORY)
links_gl(${bin_dir}/sierra-bench-frames frames_gl)
if(NOT frames_gl)
  message(FATAL_ERROR "sierra-bench-frames should link the renderer")
endif()
foreach(program ${BENCH} ${GEN} ${TIN})
  links_gl(${program} gl)
  if(gl)
    message(FATAL_ERROR "${program} links GL or ImGui, though it needs neither")
  endif()
  message(STATUS "${program}: no GL")
endforeach()

# The GL-free sierra-bench still runs frames, through the program beside it.
run_app(frames_help EXPECT_OK MESSAGE "--compare-full" COMMAND ${BENCH} frames --help)
run_app(static_help EXPECT_OK MESSAGE "--max-error" COMMAND ${BENCH} static --help)
run_app(bench_help EXPECT_OK MESSAGE "frames" COMMAND ${BENCH} --help)
