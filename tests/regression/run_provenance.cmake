# Provenance check (issue 11, item 6), ctest provenance.NAME: 'rockdda
# --version'; a run of PRM records version, commit, build type, date,
# command line and host in log.txt and summary.csv; its parameters.prm
# names the input files by absolute path with their SHA-256 and, copied to
# another folder, runs as it stands to the same results.
execute_process(COMMAND ${DRIVER} --version
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^rockdda [0-9]+\\.[0-9]+\\.[0-9]+\n"
   OR NOT out MATCHES "git commit: [^\n]+\n" OR NOT out MATCHES "build type: ")
  message(FATAL_ERROR "rockdda --version: exit ${rc}:\n${out}${err}")
endif()
string(REGEX MATCH "git commit: ([^\n]+)" _ "${out}")
set(commit ${CMAKE_MATCH_1})
message("--version: ${out}")
# The commit is the one the binary was built from, not the one of the last
# CMake configure: HEAD of the source tree (when it is a git checkout and the
# test runs on the build it belongs to, as ctest does).
if(GIT AND EXISTS ${SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT} rev-parse --short=12 HEAD
    WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE head
    OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
  if(rc EQUAL 0 AND NOT commit MATCHES "^${head}(-dirty)?$")
    message(FATAL_ERROR "rockdda --version says commit ${commit}, the source "
      "tree is at ${head}: the binary records a stale commit")
  endif()
endif()

file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/first ${OUT}/again)
get_filename_component(name ${PRM} NAME_WE)
execute_process(COMMAND ${DRIVER} --quiet ${PRM}
  WORKING_DIRECTORY ${OUT}/first
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rockdda failed (exit ${rc}) on ${PRM}:\n${out}\n${err}")
endif()
set(first ${OUT}/first/output-${name})

# log.txt: version, commit, build type, date, host, command line.
file(READ ${first}/log.txt log)
foreach(pattern "rockdda [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit ${commit}, [A-Za-z]+ build"
    "run [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9:]+Z on [^ ]+ in "
    "--quiet ${PRM}")
  if(NOT log MATCHES "${pattern}")
    message(FATAL_ERROR "log.txt does not match '${pattern}':\n${log}")
  endif()
endforeach()
# summary.csv: the same as text rows.
file(READ ${first}/summary.csv summary)
foreach(key rockdda_version git_commit build_type run_date command_line host)
  if(NOT summary MATCHES "\n${key},[^\n]+,text\n")
    message(FATAL_ERROR "summary.csv has no '${key}' row:\n${summary}")
  endif()
endforeach()

# parameters.prm: every input file by absolute path, with its checksum.
file(READ ${first}/parameters.prm resolved)
file(STRINGS ${PRM} file_keys REGEX "^ *set [A-Za-z ]* file *=")
if(NOT file_keys)
  message(FATAL_ERROR "${PRM} names no input file: choose another case")
endif()
get_filename_component(prm_dir ${PRM} DIRECTORY)
foreach(line ${file_keys})
  string(REGEX REPLACE "^ *set ([A-Za-z ]*file) *= *([^ #]*).*$" "\\1" key "${line}")
  string(REGEX REPLACE "^ *set ([A-Za-z ]*file) *= *([^ #]*).*$" "\\2" value "${line}")
  get_filename_component(absolute ${value} ABSOLUTE BASE_DIR ${prm_dir})
  file(SHA256 ${absolute} sum)
  if(NOT resolved MATCHES "set ${key} *= ${absolute}\n")
    message(FATAL_ERROR "parameters.prm does not set '${key}' to ${absolute}:\n${resolved}")
  endif()
  if(NOT resolved MATCHES "# input file '[^']*${key}' = ${absolute}  sha256 ${sum}\n")
    message(FATAL_ERROR "parameters.prm lacks the SHA-256 ${sum} of ${absolute}:\n${resolved}")
  endif()
endforeach()

# Re-run the written parameters.prm as it stands, from another folder.
file(COPY ${first}/parameters.prm DESTINATION ${OUT}/again)
execute_process(COMMAND ${DRIVER} --quiet parameters.prm
  WORKING_DIRECTORY ${OUT}/again
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "parameters.prm does not run again (exit ${rc}):\n${out}\n${err}")
endif()
file(GLOB again_summary ${OUT}/again/*/summary.csv)
file(STRINGS ${first}/summary.csv rows_first)
file(STRINGS ${again_summary} rows_again)
set(skip "^(wall_time|run_date|command_line|working_directory),")
list(FILTER rows_first EXCLUDE REGEX "${skip}")
list(FILTER rows_again EXCLUDE REGEX "${skip}")
if(NOT "${rows_first}" STREQUAL "${rows_again}")
  message(FATAL_ERROR "the re-run of parameters.prm differs:\nfirst: ${rows_first}\nagain: ${rows_again}")
endif()
list(LENGTH rows_first n)
message("parameters.prm re-runs to the same ${n} summary rows")
