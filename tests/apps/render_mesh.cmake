# sierra-render --mesh: a TIN from sierra-tin drawn instead of the SBT (the
# same terrain options for both); a mesh of another terrain, or none, fails
# with one message and writes no frame.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(base --generate 65 --size 160x90 --msaa 0 --no-debug)
run_app(tin EXPECT_OK COMMAND ${TIN} --generate 65 --max-error-rel 0.02 --out tin.obj --json tin.json)
file(READ ${WORK_DIR}/tin.json stats)
string(JSON tin_triangles GET "${stats}" triangles)
run_app(mesh EXPECT_OK MESSAGE "${tin_triangles} triangles" COMMAND ${RENDER} ${base} --mesh tin.obj --out mesh.png)
expect_file(${WORK_DIR}/mesh.png)
run_app(sbt EXPECT_OK COMMAND ${RENDER} ${base} --tau 4 --out sbt.png)
expect_different(${WORK_DIR}/mesh.png ${WORK_DIR}/sbt.png "--mesh")
# The scene file carries the mesh.
run_app(print_config EXPECT_OK MESSAGE "\"mesh\": \"tin.obj\"" COMMAND ${RENDER} ${base} --mesh tin.obj --print-config)

run_app(other_terrain EXPECT_FAIL EXIT 1 MESSAGE "same terrain options"
        COMMAND ${RENDER} ${base} --seed 5 --mesh tin.obj --out other.png)
run_app(missing_mesh EXPECT_FAIL EXIT 1 MESSAGE "nope.obj" COMMAND ${RENDER} ${base} --mesh nope.obj --out missing.png)
file(WRITE ${WORK_DIR}/bad.obj "v 0 0 0\nf 1 2 3\n")
run_app(bad_mesh EXPECT_FAIL EXIT 1 MESSAGE "bad.obj" COMMAND ${RENDER} ${base} --mesh bad.obj --out bad.png)
foreach(f other.png missing.png bad.png)
  expect_no_file(${WORK_DIR}/${f})
endforeach()
