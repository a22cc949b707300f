# Bad input: one clear message, a non-zero exit, no output written.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(missing EXPECT_FAIL MESSAGE "nope.png" COMMAND ${RENDER} --heightmap nope.png --out a.png)
file(WRITE ${WORK_DIR}/corrupt.png "this is not a png at all")
run_app(corrupt EXPECT_FAIL MESSAGE "corrupt.png" COMMAND ${RENDER} --heightmap corrupt.png --out b.png --no-debug)
file(WRITE ${WORK_DIR}/nan.pgm "P2\n2 2\n255\n1 2 3\n")
run_app(truncated EXPECT_FAIL MESSAGE "nan.pgm" COMMAND ${RENDER} --heightmap nan.pgm --out c.png --no-debug)
run_app(unknown_option EXPECT_FAIL MESSAGE "--bogus" COMMAND ${RENDER} --bogus)
run_app(bad_size EXPECT_FAIL MESSAGE "--size" COMMAND ${RENDER} --generate 65 --size 12by5 --out d.png)
run_app(bad_generate EXPECT_FAIL MESSAGE "2^n" COMMAND ${RENDER} --generate 100 --out e.png)
run_app(bad_tau EXPECT_FAIL MESSAGE "tau" COMMAND ${RENDER} --generate 65 --tau -1 --out f.png)
run_app(bad_lod EXPECT_FAIL MESSAGE "lod" COMMAND ${RENDER} --lod medium)
foreach(f a.png b.png c.png d.png e.png f.png out/frame.png)
  expect_no_file(${WORK_DIR}/${f})
endforeach()
# No EGL vendor at all (GLVND finds no driver): the cause and the packages.
run_app(no_egl EXPECT_FAIL MESSAGE "libegl-mesa0"
        COMMAND ${CMAKE_COMMAND} -E env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json
                ${RENDER} --generate 65 --out g.png)
expect_no_file(${WORK_DIR}/g.png)
# One format and two exit codes in every program: 2 for usage, 1 for runtime.
run_app(usage_format EXPECT_FAIL EXIT 2 MESSAGE "sierra-render: error: " COMMAND ${RENDER} --bogus)
run_app(runtime_format EXPECT_FAIL EXIT 1 MESSAGE "sierra-render: error: corrupt.png"
        COMMAND ${RENDER} --heightmap corrupt.png --out h.png --no-debug)
run_app(bench_usage EXPECT_FAIL EXIT 2 MESSAGE "sierra-bench: error: " COMMAND ${BENCH} frames --tau 0)
run_app(bench_runtime EXPECT_FAIL EXIT 1 MESSAGE "sierra-bench: error: corrupt.png"
        COMMAND ${BENCH} static --heightmap corrupt.png --max-error 1)
run_app(version EXPECT_OK MESSAGE "sierra-render 0." COMMAND ${RENDER} --version)
run_app(bench_version EXPECT_OK MESSAGE "sierra-bench 0." COMMAND ${BENCH} --version)
expect_no_file(${WORK_DIR}/h.png)
# An output location that cannot be written fails before any work: no frame is rendered first.
file(WRITE ${WORK_DIR}/blocker "a file where a directory is needed")
run_app(bad_out_dir EXPECT_FAIL EXIT 1 MESSAGE "blocker" COMMAND ${RENDER} --generate 65 --out blocker/f.png --no-debug)
run_app(bad_json_dir EXPECT_FAIL EXIT 1 MESSAGE "blocker"
        COMMAND ${BENCH} frames --generate 65 --size 64x36 --frames 2 --json blocker/x.json)
