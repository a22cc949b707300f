# Shows that cmake/CheckModuleIncludes.cmake catches wrong includes: each case
# writes a small engine tree under WORK_DIR, runs the checker on it and expects
# success, or failure with the given text. The module table comes from
# docs/architecture.md unless a case sets case_architecture to a table of its own;
# case_extra_file and case_extra_content plant a second file.
#   cmake -DCHECKER=<CheckModuleIncludes.cmake> -DWORK_DIR=<dir> -P checker_fixture.cmake

function(run_case name file content expected)
  set(root "${WORK_DIR}/${name}")
  file(REMOVE_RECURSE "${root}")
  # A clean base: core with std and POSIX headers, terrain using core and spng,
  # gpu's EGL file, render using everything.
  file(WRITE "${root}/include/sierra/core/Error.h" "#pragma once\n#include <string>\n#include <sys/stat.h>\n")
  file(WRITE "${root}/src/core/Files.cpp" "#include <sierra/core/Error.h>\n#include <unistd.h>\n")
  file(WRITE "${root}/src/terrain/Load.cpp" "#include <sierra/core/Error.h>\n#include <spng.h>\n")
  file(WRITE "${root}/src/gpu/EglContext.cpp" "#include <EGL/egl.h>\n#include <GL/glcorearb.h>\n")
  file(WRITE "${root}/src/render/Pass.cpp"
       "#include \"render/Private.h\"\n#include <sierra/gpu/Gl.h>\n#include <glm/glm.hpp>\n#include <imgui.h>\n")
  if(file)
    file(WRITE "${root}/${file}" "${content}")
  endif()
  if(case_extra_file)
    file(WRITE "${root}/${case_extra_file}" "${case_extra_content}")
  endif()
  set(architecture_arg "")
  if(case_architecture)
    set(architecture_arg "-DARCHITECTURE=${case_architecture}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -DENGINE_DIR=${root} ${architecture_arg} -P ${CHECKER}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(APPEND out "${err}")
  if(expected STREQUAL "")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "case ${name}: the checker refused a clean tree:\n${out}")
    endif()
  else()
    if(rc EQUAL 0)
      message(FATAL_ERROR "case ${name}: the checker passed a wrong include (${file})")
    endif()
    string(FIND "${out}" "${expected}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "case ${name}: expected \"${expected}\" in:\n${out}")
    endif()
  endif()
  message(STATUS "case ${name}: ok")
endfunction()

run_case(clean "" "" "")
run_case(terrain_includes_render src/terrain/Bad.cpp "#include <sierra/render/Camera.h>\n"
         "src/terrain/Bad.cpp:1: module terrain may not include <sierra/render/Camera.h> (it belongs to render; terrain may use: core stb spng gdal zlib)")
run_case(core_includes_terrain include/sierra/core/Log.h "#pragma once\n\n#include <sierra/terrain/Heightfield.h>\n"
         "include/sierra/core/Log.h:3: module core may not include <sierra/terrain/Heightfield.h>")
run_case(sbt_includes_gl src/sbt/Refiner.cpp "#include <sierra/terrain/Heightfield.h>\n#include <GL/glcorearb.h>\n"
         "src/sbt/Refiner.cpp:2: module sbt may not include <GL/glcorearb.h> (it belongs to gl")
run_case(gpu_egl_outside_context src/gpu/Objects.cpp "#include <EGL/egl.h>\n"
         "module gpu may not include <EGL/egl.h> (it belongs to egl, which only src/gpu/EglContext.cpp may include")
run_case(render_includes_egl src/render/Frame.cpp "#include <EGL/egl.h>\n"
         "module render may not include <EGL/egl.h>")
run_case(scene_includes_gpu src/scene/Scene.cpp "#include <nlohmann/json.hpp>\n#include <sierra/gpu/Gl.h>\n"
         "src/scene/Scene.cpp:2: module scene may not include <sierra/gpu/Gl.h>")
run_case(terrain_includes_glm src/terrain/Ramp.cpp "#include <glm/glm.hpp>\n"
         "module terrain may not include <glm/glm.hpp> (it belongs to glm")
run_case(quoted_cross_module src/sbt/Bridge.cpp "#include \"render/SbtBridge.h\"\n"
         "module sbt may not include <render/SbtBridge.h>")
run_case(unknown_module src/physics/Body.cpp "#include <string>\n"
         "module physics is not in the table")

# CLI11, nlohmann-json and the scene module are kept out of the engine modules'
# public headers by the document's table: a planted include is refused in each,
# directly or through another module's public header.
foreach(module core terrain sbt analysis zones tin gpu render)
  foreach(planted "CLI|CLI/CLI.hpp" "scene|sierra/scene/Scene.h")
    string(REPLACE "|" ";" planted "${planted}")
    list(GET planted 0 dep)
    list(GET planted 1 header)
    run_case(${module}_header_reaches_${dep} include/sierra/${module}/Planted.h
             "#pragma once\n#include <${header}>\n"
             "include/sierra/${module}/Planted.h: a public header of ${module} reaches <${header}> (${dep} is kept out of ${module}'s public headers) directly (line 2)")
  endforeach()
endforeach()
foreach(module core terrain sbt tin gpu render)
  run_case(${module}_header_reaches_nlohmann include/sierra/${module}/Planted.h
           "#pragma once\n#include <nlohmann/json.hpp>\n"
           "include/sierra/${module}/Planted.h: a public header of ${module} reaches <nlohmann/json.hpp> (nlohmann is kept out of ${module}'s public headers) directly (line 2)")
endforeach()
set(case_extra_file include/sierra/zones/Palette.h)
set(case_extra_content "#pragma once\n#include <sierra/terrain/Grid.h>\n#include <nlohmann/json_fwd.hpp>\n")
run_case(render_header_reaches_nlohmann_through_zones include/sierra/render/Overlay.h
         "#pragma once\n#include <string>\n#include <sierra/zones/Palette.h>\n"
         "include/sierra/render/Overlay.h: a public header of render reaches <nlohmann/json_fwd.hpp> (nlohmann is kept out of render's public headers) through include/sierra/zones/Palette.h:3")
set(case_extra_file include/sierra/scene/Scene.h)
set(case_extra_content "#pragma once\n#include <CLI/CLI.hpp>\n")
run_case(facade_header_may_reach_scene include/sierra/facade/View.h
         "#pragma once\n#include <sierra/scene/Scene.h>\n#include <sierra/render/Camera.h>\n" "")
unset(case_extra_file)
unset(case_extra_content)

# The table is read from the document: one that lets terrain use render passes the
# include the real table refuses; one without a table, or with a malformed row, is refused.
set(table_head "| module | owns | may include |\n|---|---|---|\n")
set(table_rows "| `core` | errors | the standard library only |\n| `gpu` | GL | `core` `gl` `egl` |\n| `render` | frames | `core` `terrain` `gpu` `gl` `glm` `imgui` `spng` |\n")
set(table_confined "\n| dependency | only in |\n|---|---|\n| `egl` | `src/gpu/EglContext.cpp` |\n")
file(WRITE "${WORK_DIR}/terrain_uses_render.md"
     "# Modules\n\n${table_head}${table_rows}| `terrain` | grids; loaders | `core` `spng` `render` |\n${table_confined}")
set(case_architecture "${WORK_DIR}/terrain_uses_render.md")
run_case(table_from_document src/terrain/Bad.cpp "#include <sierra/render/Camera.h>\n" "")
run_case(table_from_document_refuses src/terrain/Bad.cpp "#include <glm/glm.hpp>\n"
         "module terrain may not include <glm/glm.hpp> (it belongs to glm; terrain may use: core spng render)")
file(WRITE "${WORK_DIR}/no_table.md" "# Modules\n\nNo table here.\n")
set(case_architecture "${WORK_DIR}/no_table.md")
run_case(document_without_table "" "" "has no module table")
file(WRITE "${WORK_DIR}/bad_row.md" "${table_head}${table_rows}| terrain | grids |\n")
set(case_architecture "${WORK_DIR}/bad_row.md")
run_case(document_bad_row "" "" "bad_row.md:6: a row of the modules table must start with a `name` cell")
set(case_architecture "${WORK_DIR}/missing.md")
run_case(document_missing "" "" "missing.md not found")
# A module the kept-out table names may not list the dependency in its row.
string(REPLACE "`imgui` `spng` |" "`imgui` `spng` `CLI` |" render_lists_cli "${table_rows}")
file(WRITE "${WORK_DIR}/render_lists_cli.md"
     "${table_head}${render_lists_cli}| `terrain` | grids | `core` `spng` |\n${table_confined}\n| kept out | of the public headers of |\n|---|---|\n| `CLI` | `core` `render` |\n")
set(case_architecture "${WORK_DIR}/render_lists_cli.md")
run_case(kept_out_row_listed "" "" "module render lists `CLI` in the module table, but CLI is kept out of render's public headers")
