# Cut-to-DDA scene (issue 11, item 1), ctest regression.cut_to_dda: run
# 'cut' on PRM in OUT, then the dda.prm it wrote beside blocks.dda (1 s of
# dynamic DDA), and check from the DDA summary that the run completed, the
# energy ledger created no energy beyond 1e-6 of the energy in play
# (Newmark with gamma = 1 only dissipates; the ledger's inexactness at
# lock/slide changes is far below this on a settling wall, measured 0) and
# no block moved more than 1e-3 m (1e-4 x the 10 m domain; elastic settling
# is 2.7e-5 m).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${DRIVER} --quiet ${PRM} WORKING_DIRECTORY ${OUT}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${OUT}/output-cut/dda.prm)
  message(FATAL_ERROR "cut failed (exit ${rc}) or wrote no dda.prm:\n${out}\n${err}")
endif()
file(READ ${OUT}/output-cut/blocks.dda blocks)
if(NOT blocks MATCHES "fixed-block")
  message(FATAL_ERROR "blocks.dda has no fixed block")
endif()
execute_process(COMMAND ${DRIVER} --quiet ${OUT}/output-cut/dda.prm
  WORKING_DIRECTORY ${OUT}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "dda on the cut scene failed (exit ${rc}):\n${out}\n${err}")
endif()
file(STRINGS ${OUT}/output-dda/summary.csv rows)
foreach(row ${rows})
  string(REPLACE "," ";" f "${row}")
  list(GET f 0 key)
  list(LENGTH f n)
  if(n GREATER 1)
    list(GET f 1 value)
    set(v_${key} ${value})
  endif()
endforeach()
message("completed ${v_completed}, final time ${v_final_time} s, steps ${v_steps}, "
  "energy created ${v_energy_created_relative} of the energy in play, "
  "largest block displacement ${v_max_block_displacement} m")
if(NOT v_completed EQUAL 1 OR v_final_time LESS 0.999999)
  message(FATAL_ERROR "the run did not reach 1 s")
endif()
if(v_energy_created_relative GREATER 1e-6)
  message(FATAL_ERROR "energy created: ${v_energy_created_relative} of the energy in play")
endif()
if(v_max_block_displacement GREATER 1e-3)
  message(FATAL_ERROR "a block moved ${v_max_block_displacement} m")
endif()
