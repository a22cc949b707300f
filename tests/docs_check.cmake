# Fails when the committed docs/scene.md differs from what sierra-scene-docs
# generates from docs/scene.md.in and the option table.
# -DGENERATOR=... -DTEMPLATE=docs/scene.md.in -DDOCS=docs/scene.md -DOUT=build file
execute_process(COMMAND ${GENERATOR} ${TEMPLATE} OUTPUT_FILE ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} ${TEMPLATE} failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${DOCS} RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "docs/scene.md is not the generated text; see the difference with\n"
                      "  diff -u ${DOCS} ${OUT}\n"
                      "and regenerate it with\n"
                      "  ${GENERATOR} ${TEMPLATE} > ${DOCS}")
endif()
