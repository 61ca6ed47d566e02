# Shared by the installed-package tests' scripts (cmake/install.cmake): run(COMMAND...) runs a
# command and fails the test, naming it, if it fails.
function(run)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        list(JOIN ARGN " " command)
        message(FATAL_ERROR "failed (${status}): ${command}")
    endif()
endfunction()
