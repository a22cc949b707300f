# sierra-bench's commands run end to end and write what they promise.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(static EXPECT_OK MESSAGE "indices per triangle" COMMAND ${BENCH} static --generate 129 --max-error 0.5 --repeat 3 --obj mesh.obj --json static.json)
expect_file(${WORK_DIR}/mesh.obj)
expect_file(${WORK_DIR}/static.json)
run_app(frames EXPECT_OK MESSAGE "PSNR" COMMAND ${BENCH} frames --generate 129 --size 160x90 --frames 3 --compare-full --json frames.json)
expect_file(${WORK_DIR}/frames.json)
run_app(no_command EXPECT_FAIL COMMAND ${BENCH})
run_app(bad_path EXPECT_FAIL MESSAGE "path" COMMAND ${BENCH} frames --generate 65 --path spiral)
