# sierra-bench's commands run end to end and write what they promise.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
run_app(static EXPECT_OK MESSAGE "indices per triangle" COMMAND ${BENCH} static --generate 129 --max-error 0.5 --repeat 3 --obj mesh.obj --json static.json)
expect_file(${WORK_DIR}/mesh.obj)
expect_file(${WORK_DIR}/static.json)
# The terrain options are the scene registrar's: a printed scene fed back with
# --config loads the same terrain; raw sizes have their own parser and limit.
run_app(static_print_config EXPECT_OK MESSAGE "\"roughness\": 0.5" COMMAND ${BENCH} static --generate 129 --roughness 0.5 --print-config)
file(WRITE ${WORK_DIR}/scene.json "${LAST_OUTPUT}")
run_app(static_config EXPECT_OK MESSAGE "diamond-square 129x129, seed 1, roughness 0.5" COMMAND ${BENCH} static --config scene.json --max-error 0.5 --repeat 1)
run_app(static_bad_raw_size EXPECT_FAIL MESSAGE "1..65537" COMMAND ${BENCH} static --heightmap scene.json --raw-size 70000x3 --max-error 1)
run_app(static_no_max_error EXPECT_FAIL MESSAGE "--max-error" COMMAND ${BENCH} static --generate 65)
run_app(frames EXPECT_OK MESSAGE "PSNR" COMMAND ${BENCH} frames --generate 129 --size 160x90 --frames 3 --compare-full --json frames.json)
expect_file(${WORK_DIR}/frames.json)
run_app(no_command EXPECT_FAIL COMMAND ${BENCH})
run_app(bad_path EXPECT_FAIL MESSAGE "path" COMMAND ${BENCH} frames --generate 65 --path spiral)
