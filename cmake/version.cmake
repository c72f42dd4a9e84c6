# Writes OUTPUT (version.cc) from cmake/version.cc.in with the source tree's
# git commit at *build* time, so that 'rockdda --version' names the commit the
# binary was built from (configure_file rewrites the file only when its text
# changes: an unchanged commit recompiles nothing). Run by the target
# rockdda_version with -DSOURCE_DIR -DOUTPUT -DGIT_EXECUTABLE -DPROJECT_VERSION
# -DROCKDDA_BUILD_TYPE -DDEAL_II_PACKAGE_VERSION.
set(ROCKDDA_GIT_COMMIT "unknown")
if(GIT_EXECUTABLE AND EXISTS ${SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
    WORKING_DIRECTORY ${SOURCE_DIR}
    OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE rc ERROR_QUIET)
  if(rc EQUAL 0 AND commit)
    set(ROCKDDA_GIT_COMMIT ${commit})
    execute_process(COMMAND ${GIT_EXECUTABLE} diff --quiet HEAD --
      WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE dirty ERROR_QUIET)
    if(NOT dirty EQUAL 0)
      string(APPEND ROCKDDA_GIT_COMMIT "-dirty")
    endif()
  endif()
endif()
configure_file(${SOURCE_DIR}/cmake/version.cc.in ${OUTPUT} @ONLY)
