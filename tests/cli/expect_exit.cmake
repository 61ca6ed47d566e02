# Runs a command and checks its exit status and the first line of its stderr (ctest tests of the
# `footprint` binary's command-line errors).
# Usage: cmake "-DCOMMAND=prog;arg;…" -DEXIT=N "-DSTDERR=regex" -P expect_exit.cmake
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT status STREQUAL "${EXIT}")
    message(FATAL_ERROR "exit status ${status}, expected ${EXIT}; stderr: ${err}")
endif()
if(NOT err MATCHES "${STDERR}")
    message(FATAL_ERROR "stderr does not match '${STDERR}': ${err}")
endif()
