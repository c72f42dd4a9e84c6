# One MPI case: the driver on PRM serially (one process, no MPI) and with
# MPIEXEC -np RANKS (the distributed heat solver, or the distributed DDA
# solver; on one rank with the linear solver 'amg' (heat) or 'distributed'
# (DDA), which selects it), each in its own folder
# under OUT; every numeric quantity of the serial summary.csv (except wall
# times and counters of the method) must be matched by the parallel run
# within the tolerances of the first '# compare: REL ABS' line of PRM, and
# the files listed on '# files:' lines must exist in the parallel output.
get_filename_component(name ${PRM} NAME_WE)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/serial ${OUT}/mpi)
file(STRINGS ${PRM} compare_lines REGEX "^# compare: ")
list(GET compare_lines 0 compare)
string(REGEX REPLACE "^# compare: +" "" compare "${compare}")
separate_arguments(compare)
list(GET compare 0 rel)
list(GET compare 1 abs)

execute_process(COMMAND ${DRIVER} --quiet ${PRM}
  WORKING_DIRECTORY ${OUT}/serial
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "serial run failed (exit ${rc}):\n${out}\n${err}")
endif()
# On one rank the distributed solver runs only if asked for ('amg' for
# heat, 'distributed' for DDA): a copy of PRM (same name, so the same output
# folder) asks for it.
set(mpi_prm ${PRM})
if(RANKS EQUAL 1)
  file(READ ${PRM} text)
  set(solver amg)
  set(section "subsection Time stepping")
  if(text MATCHES "set Analysis type *= *dda")
    set(solver distributed)
    set(section "subsection DDA")
    # The copy lives elsewhere: the block file by its absolute path.
    get_filename_component(prm_dir ${PRM} DIRECTORY)
    string(REGEX REPLACE "set Block file( *)= *([^\n]+)"
      "set Block file\\1= ${prm_dir}/\\2" text "${text}")
  endif()
  if(text MATCHES "set Linear solver *= *[a-z]+")
    string(REGEX REPLACE "set Linear solver( *)= *[a-z]+"
      "set Linear solver\\1= ${solver}" text "${text}")
  else()
    string(REPLACE "${section}"
      "${section}\n    set Linear solver = ${solver}" text "${text}")
  endif()
  set(mpi_prm ${OUT}/mpi/${name}.prm)
  file(WRITE ${mpi_prm} "${text}")
endif()
execute_process(COMMAND ${MPIEXEC} --allow-run-as-root --oversubscribe
    -np ${RANKS} ${DRIVER} --quiet ${mpi_prm}
  WORKING_DIRECTORY ${OUT}/mpi
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpirun -np ${RANKS} failed (exit ${rc}):\n${out}\n${err}")
endif()

# Reference from the serial summary.
file(STRINGS ${OUT}/serial/output-${name}/summary.csv rows)
set(ref "# quantity value rel_tol abs_tol (from the serial run)\n")
set(n 0)
foreach(row ${rows})
  string(REPLACE "," ";" fields "${row}")
  list(LENGTH fields nf)
  if(NOT nf EQUAL 3)
    continue()
  endif()
  list(GET fields 0 q)
  list(GET fields 1 v)
  list(GET fields 2 u)
  if(u STREQUAL "text")
    continue()
  endif()
  # Provenance is not a result (a commit hash such as 0881970...e can look
  # like a number); counters of the linear solver's own iterations differ
  # between the serial and the distributed preconditioners; the strength
  # audit's ratio is a contact force's excess over its strength (a
  # difference of nearly equal forces) over a tolerance of 1e-4 of a
  # block's weight, so the solvers' round-off moves it by ~1e-7 relative.
  if(q MATCHES "^(quantity|method|wall_time|solver_wall_time|factorizations|solver_iterations|contact_strength_ratio_max|rockdda_version|git_commit|build_type|run_date|command_line|host)$")
    continue()
  endif()
  if(NOT v MATCHES "^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$")
    continue()
  endif()
  string(APPEND ref "${q} ${v} ${rel} ${abs}\n")
  math(EXPR n "${n} + 1")
endforeach()
file(WRITE ${OUT}/serial.ref "${ref}")
message("comparing ${n} quantities of ${RANKS} ranks against the serial run")
execute_process(COMMAND ${COMPARE} ${OUT}/mpi/output-${name}/summary.csv
    ${OUT}/serial.ref
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${RANKS} ranks differ from the serial run")
endif()

file(STRINGS ${PRM} file_lines REGEX "^# files: ")
foreach(line ${file_lines})
  string(REGEX REPLACE "^# files: +" "" files "${line}")
  separate_arguments(files)
  foreach(f ${files})
    # The piece of a rank beyond the run's ranks is not expected.
    if(f MATCHES "\\.([0-9]+)\\.vtu$" AND CMAKE_MATCH_1 GREATER_EQUAL RANKS)
      continue()
    endif()
    if(NOT EXISTS ${OUT}/mpi/output-${name}/${f})
      message(FATAL_ERROR "missing output file ${f} of the MPI run")
    endif()
  endforeach()
endforeach()
