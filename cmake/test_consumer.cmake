# cmake -DBUILD_DIR=… -DSOURCE_DIR=… -DWORK_DIR=… -P test_consumer.cmake
# Installs the build into WORK_DIR/prefix, then configures, builds and runs examples/consumer and
# examples/oiio-drop-in
# against it, as a user's project would: only find_package(footprint) and the installed files.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        list(JOIN ARGN " " command)
        message(FATAL_ERROR "failed (${status}): ${command}")
    endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
# The GLSL library and its version defines, where docs/engine.md says they are.
foreach(part version common texture bump highlight environment)
    if(NOT EXISTS ${WORK_DIR}/prefix/share/footprint/glsl/footprint/${part}.glsl)
        message(FATAL_ERROR "not installed: share/footprint/glsl/footprint/${part}.glsl")
    endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)

# examples/oiio-drop-in: a renderer written against OpenImageIO's TextureSystem alone, built
# against the installed package both ways (OpenImageIO's texture system, then footprint's behind
# the same interface) and run both ways.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/oiio-drop-in -B ${WORK_DIR}/drop-in -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/drop-in)
run(${WORK_DIR}/drop-in/oiio-drop-in-oiio ${WORK_DIR}/drop-in/oiio.exr)
run(${WORK_DIR}/drop-in/oiio-drop-in-footprint ${WORK_DIR}/drop-in/footprint.exr)
