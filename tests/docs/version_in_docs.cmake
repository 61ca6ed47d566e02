# What docs/cli.md says `footprint --version` prints is what it prints (ctest footprint-docs-version).
# Usage: cmake -DFOOTPRINT=<binary> -DDOC=<docs/cli.md> -P version_in_docs.cmake
execute_process(COMMAND ${FOOTPRINT} --version OUTPUT_VARIABLE printed
                OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "footprint --version exited with ${status}")
endif()
file(READ ${DOC} doc)
string(FIND "${doc}" "`footprint --version` prints `${printed}`" at)
if(at EQUAL -1)
    message(FATAL_ERROR "${DOC} does not say that `footprint --version` prints `${printed}`")
endif()
