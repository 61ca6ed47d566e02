# footprint_gtest_suites(TARGET [SLOW SUITE SECONDS ...]): one CTest test per GoogleTest suite of
# the test executable TARGET, named after the suite and running `TARGET --gtest_filter=<suite>.*`.
# Each SLOW suite gets its typical SECONDS as its CTest COST, so that `ctest -j` starts it first:
# a clean clone has no timing data (Testing/Temporary/CTestCostData.txt) and would otherwise start
# tests in the order listed, leaving a slow suite listed late running alone at the end.
#
# Not gtest_discover_tests(), which makes a test, and so a process, of every test: each process
# first loads OpenImageIO's few hundred shared libraries (most of a short test's time,
# docs/testing.md#how-the-tests-are-organised), while a suite's tests share one process. The list is made when
# TARGET is built (it runs `TARGET --gtest_list_tests`), as gtest_discover_tests() makes its.
set(FOOTPRINT_GTEST_SUITES_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/gtest_suites_list.cmake")

function(footprint_gtest_suites target)
    cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SLOW")
    set(list_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
    set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake")
    set(costs "")
    while(arg_SLOW)
        list(POP_FRONT arg_SLOW suite seconds)
        string(APPEND costs "    set_tests_properties([=[${suite}]=] PROPERTIES COST ${seconds})\n")
    endwhile()
    add_custom_command(TARGET ${target} POST_BUILD
        COMMAND "${CMAKE_COMMAND}" -D "EXECUTABLE=$<TARGET_FILE:${target}>"
                -D "OUTPUT=${list_file}" -P "${FOOTPRINT_GTEST_SUITES_SCRIPT}"
        COMMENT "Listing the test suites of ${target}"
        VERBATIM)
    # Before the first build there is no list: CTest then reports one test that cannot run.
    file(WRITE "${include_file}"
         "if(EXISTS \"${list_file}\")\n"
         "    include(\"${list_file}\")\n"
         "${costs}"
         "else()\n"
         "    add_test(${target}_NOT_BUILT ${target}_NOT_BUILT)\n"
         "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
