# doc/parameters.md must be what 'rockdda --print-parameters' prints now.
# Regenerate it with: build/rockdda --print-parameters > doc/parameters.md
execute_process(COMMAND ${DRIVER} --print-parameters
  OUTPUT_VARIABLE now RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rockdda --print-parameters failed (${rc})")
endif()
file(READ ${DOC} stored)
if(NOT now STREQUAL stored)
  message(FATAL_ERROR "${DOC} is stale: regenerate it with\n"
    "  build/rockdda --print-parameters > doc/parameters.md")
endif()
