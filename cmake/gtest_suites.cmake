# footprint_gtest_suites(TARGET): one CTest test per GoogleTest suite of the test executable
# TARGET, named after the suite and running `TARGET --gtest_filter=<suite>.*`.
#
# Not gtest_discover_tests(), which makes a test, and so a process, of every test: each process
# first loads OpenImageIO's few hundred shared libraries (most of a short test's time,
# docs/testing.md#how-the-tests-are-organised), while a suite's tests share one process. The list is made when
# TARGET is built (it runs `TARGET --gtest_list_tests`), as gtest_discover_tests() makes its.
set(FOOTPRINT_GTEST_SUITES_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/gtest_suites_list.cmake")

function(footprint_gtest_suites target)
    set(list_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
    set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites_include.cmake")
    add_custom_command(TARGET ${target} POST_BUILD
        COMMAND "${CMAKE_COMMAND}" -D "EXECUTABLE=$<TARGET_FILE:${target}>"
                -D "OUTPUT=${list_file}" -P "${FOOTPRINT_GTEST_SUITES_SCRIPT}"
        COMMENT "Listing the test suites of ${target}"
        VERBATIM)
    # Before the first build there is no list: CTest then reports one test that cannot run.
    file(WRITE "${include_file}"
         "if(EXISTS \"${list_file}\")\n"
         "    include(\"${list_file}\")\n"
         "else()\n"
         "    add_test(${target}_NOT_BUILT ${target}_NOT_BUILT)\n"
         "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
