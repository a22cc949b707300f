# The installed package works on its own: `cmake --install` into a fresh
# prefix, the examples built as a separate CMake project against it
# (find_package(Sierra)), hello_terrain run, and the installed programs finding
# their assets under the prefix. Run by CTest as install.package with
#   -DBUILD_DIR=<build> -DSOURCE_DIR=<repo> -DWORK_DIR=<scratch> [-DCXX_FLAGS=...]
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${WORK_DIR} TIMEOUT 600)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit ${rc}\n${out}\n${err}")
  endif()
  set(LAST_OUTPUT "${out}${err}" PARENT_SCOPE)
endfunction()

run(install ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f include/sierra/facade/SceneRenderer.h include/sierra/core/Error.h lib/libsierra_core.a
          lib/libsierra_render.a lib/libsierra_facade.a lib/cmake/Sierra/SierraConfig.cmake
          lib/cmake/Sierra/SierraConfigVersion.cmake lib/cmake/Sierra/SierraTargets.cmake
          lib/pkgconfig/sierra.pc share/sierra/assets/palettes/default.json bin/sierra-render
          bin/sierra-gen bin/sierra-tin bin/sierra-tile bin/sierra-bench include/sierra/sbt/TileFile.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "the install lacks ${f}")
  endif()
endforeach()

# pkg-config reads the relocatable .pc file.
find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${prefix}/lib/pkgconfig
                          ${PKG_CONFIG} --cflags --libs sierra
                  RESULT_VARIABLE rc OUTPUT_VARIABLE flags ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT flags MATCHES "-lsierra_facade.*-lsierra_render")
    message(FATAL_ERROR "pkg-config --libs sierra: ${rc} ${flags} ${err}")
  endif()
  string(FIND "${flags}" "${prefix}/lib/pkgconfig/../../include" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "sierra.pc does not point into its prefix: ${flags}")
  endif()
endif()

# The example, as an embedding project builds it.
set(example_build ${WORK_DIR}/examples)
run(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${example_build}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CXX_FLAGS}")
run(build ${CMAKE_COMMAND} --build ${example_build} -j 2)
set(dem /usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz)
run(hello ${example_build}/hello_terrain ${dem} ${WORK_DIR}/hello.png)
if(NOT EXISTS ${WORK_DIR}/hello.png OR NOT LAST_OUTPUT MATCHES "[1-9][0-9]* triangles")
  message(FATAL_ERROR "hello_terrain drew nothing:\n${LAST_OUTPUT}")
endif()
file(SIZE ${WORK_DIR}/hello.png size)
if(size LESS 20000)
  message(FATAL_ERROR "hello.png is ${size} bytes: a frame of sky alone?")
endif()

# An installed program looks for its assets under its own prefix first: with
# the palette removed there it names that path, not the source tree's.
file(REMOVE ${prefix}/share/sierra/assets/palettes/default.json)
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=SIERRA_ASSETS ${prefix}/bin/sierra-render
                        --zones auto --size 64x36 --generate 65 --no-debug --out ${WORK_DIR}/z.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${out}${err}" "${prefix}/share/sierra/assets" at)
if(rc EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "the installed sierra-render did not look in its prefix (exit ${rc}):\n${out}${err}")
endif()
# The Python module, where it was built: importable from the prefix's site-packages.
file(GLOB site_packages ${prefix}/lib/python3*/site-packages)
if(site_packages AND PYTHON)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${site_packages} ${PYTHON} -c
                          "import sierra; print(sierra.Renderer().render(generate=65, width=32, height=18).shape)"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err WORKING_DIRECTORY ${WORK_DIR})
  if(NOT rc EQUAL 0 OR NOT out MATCHES "\\(18, 32, 4\\)")
    message(FATAL_ERROR "the installed Python module does not render (exit ${rc}):\n${out}${err}")
  endif()
endif()
message(STATUS "install.package: ok")
