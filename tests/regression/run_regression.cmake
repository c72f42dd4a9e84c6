# Runs one regression case: the driver on PRM into OUT, then compares
# OUT/summary.csv against REF with rockdda-compare.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${DRIVER} --quiet ${PRM}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rockdda failed (exit ${rc}) on ${PRM}:\n${out}\n${err}")
endif()
# The case's output directory is set in the .prm relative to the working
# directory; find summary.csv there.
get_filename_component(name ${PRM} NAME_WE)
set(summary ${CMAKE_CURRENT_BINARY_DIR}/output-${name}/summary.csv)
foreach(f parameters.prm statistics.csv log.txt summary.csv)
  if(NOT EXISTS ${CMAKE_CURRENT_BINARY_DIR}/output-${name}/${f})
    message(FATAL_ERROR "missing output file ${f}")
  endif()
endforeach()
execute_process(COMMAND ${COMPARE} ${summary} ${REF}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "regression values differ from ${REF}")
endif()
