# cmake -D EXECUTABLE=… -D OUTPUT=… -P gtest_suites_list.cmake (gtest_suites.cmake runs it after
# each build): writes OUTPUT, an add_test() per GoogleTest suite that EXECUTABLE lists.
execute_process(COMMAND "${EXECUTABLE}" --gtest_list_tests
                OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT 60)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests failed (${status}): ${errors}")
endif()
# A suite's line starts in column one ("Suite." or "Prefix/Suite/0.  # TypeParam = …"); its
# tests' lines are indented. Semicolons (in parameter values) would split CMake's list.
string(REPLACE ";" "" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(tests "")
foreach(line IN LISTS lines)
    if(line MATCHES "^([^ #][^ ]*)\\.")
        set(suite "${CMAKE_MATCH_1}")
        string(APPEND tests "add_test([=[${suite}]=] \"${EXECUTABLE}\" [=[--gtest_filter=${suite}.*]=])\n")
    endif()
endforeach()
if(tests STREQUAL "")
    message(FATAL_ERROR "${EXECUTABLE} --gtest_list_tests listed no suite")
endif()
file(WRITE "${OUTPUT}" "${tests}")
