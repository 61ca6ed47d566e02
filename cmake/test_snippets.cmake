# cmake -DPREFIX=… -DSOURCE_DIR=… -DWORK_DIR=… -P test_snippets.cmake
# Configures and builds examples/snippets against the package installed in PREFIX
# (cmake/test_install.cmake), as a user's project would (only find_package(footprint) and the
# installed files), and runs each program: the C++ snippets of README.md and docs/library.md
# compile and run as written (examples/snippets/check_snippets.py holds the documents to those
# programs).
include(${CMAKE_CURRENT_LIST_DIR}/package_test_run.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/snippets -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build --parallel 2)
file(STRINGS ${WORK_DIR}/build/snippet_programs.txt programs)
set(failed)
foreach(program ${programs})
    message(STATUS "running ${program}")
    # Each in a folder of its own: the snippets write their files into the working directory,
    # and the texture system's default cache folder ($XDG_CACHE_HOME/footprint) is under it too.
    set(folder ${WORK_DIR}/run/${program})
    file(MAKE_DIRECTORY ${folder})
    execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=${folder}/cache
                            ${WORK_DIR}/build/${program}
                    WORKING_DIRECTORY ${folder} RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        list(APPEND failed "${program} (${status})")
    endif()
endforeach()
if(failed)
    list(JOIN failed ", " failed)
    message(FATAL_ERROR "snippet programs failed: ${failed}")
endif()
