# A bad-input case: the driver must exit with status 1, print one message
# that contains the text of the first '# expect:' line in PRM, and write no
# output directory; 'rockdda --validate' must reject it with the same
# message.
file(STRINGS ${PRM} expect_lines REGEX "^# expect: ")
list(GET expect_lines 0 expect)
string(REGEX REPLACE "^# expect: " "" expect "${expect}")
get_filename_component(name ${PRM} NAME_WE)
file(REMOVE_RECURSE ${CMAKE_CURRENT_BINARY_DIR}/output-${name})
execute_process(COMMAND ${DRIVER} ${PRM}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit ${rc}: ${err}")
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got ${rc}")
endif()
string(FIND "${err}" "${expect}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "message does not contain '${expect}'")
endif()
if(EXISTS ${CMAKE_CURRENT_BINARY_DIR}/output-${name})
  message(FATAL_ERROR "a rejected run wrote output-${name}")
endif()
execute_process(COMMAND ${DRIVER} --validate ${PRM}
  WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "--validate: expected exit status 1, got ${rc}")
endif()
string(FIND "${err}" "${expect}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "--validate: message does not contain '${expect}'")
endif()
