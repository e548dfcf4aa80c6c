# version.cmake: writes the build's provenance header, run by the restir_version target on every
# build (CMakeLists.txt), so a binary names the commit it was built from, not the one CMake last
# configured at:
#   cmake -DSOURCE_DIR=DIR -DOUTPUT=FILE -DBUILD_TYPE=TYPE -P cmake/version.cmake
# FILE gets RESTIR_GIT_COMMIT (git rev-parse --short=12 HEAD, "unknown" outside git or without git),
# RESTIR_GIT_DIRTY (1 when a tracked file differs from that commit: `git status --porcelain
# --untracked-files=no` prints anything) and RESTIR_BUILD_TYPE. FILE is rewritten only when its
# content changes, so an unchanged tree rebuilds nothing. `--no-optional-locks`: the status never
# takes the index lock, so a build never disturbs a `git add` running beside it.
if(NOT SOURCE_DIR OR NOT OUTPUT)
  message(FATAL_ERROR "version.cmake: give -DSOURCE_DIR=DIR -DOUTPUT=FILE (and -DBUILD_TYPE=TYPE)")
endif()
set(commit "unknown")
set(dirty 0)
find_program(RESTIR_GIT git)
if(RESTIR_GIT)
  execute_process(COMMAND ${RESTIR_GIT} rev-parse --short=12 HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE head RESULT_VARIABLE head_rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(head_rc EQUAL 0 AND head MATCHES "^[0-9a-f]+$")
    set(commit "${head}")
    execute_process(COMMAND ${RESTIR_GIT} --no-optional-locks status --porcelain --untracked-files=no
                    WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE status RESULT_VARIABLE status_rc ERROR_QUIET)
    if(NOT status_rc EQUAL 0 OR NOT status STREQUAL "")
      set(dirty 1) # a status that cannot be read cannot vouch for a clean tree
    endif()
  endif()
endif()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE "unknown")
endif()
set(content "/* restir_version.h: the commit this build was made from (cmake/version.cmake writes it on every
 * build, and rewrites it only when it changes). */
#ifndef RESTIR_VERSION_BUILD_H
#define RESTIR_VERSION_BUILD_H

#define RESTIR_GIT_COMMIT \"${commit}\"
#define RESTIR_GIT_DIRTY ${dirty}
#define RESTIR_BUILD_TYPE \"${BUILD_TYPE}\"

#endif
")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL content)
  file(WRITE "${OUTPUT}.tmp" "${content}")
  file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
endif()
