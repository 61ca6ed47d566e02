# cmake -DPREFIX=… -DSOURCE_DIR=… -DWORK_DIR=… -P test_consumer.cmake
# Configures, builds and runs examples/consumer and examples/oiio-drop-in against the package
# installed in PREFIX (cmake/test_install.cmake), as a user's project would: only
# find_package(footprint) and the installed files.
include(${CMAKE_CURRENT_LIST_DIR}/package_test_run.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)

# examples/oiio-drop-in: a renderer written against OpenImageIO's TextureSystem alone, built
# against the installed package both ways (OpenImageIO's texture system, then footprint's behind
# the same interface) and run both ways.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/oiio-drop-in -B ${WORK_DIR}/drop-in -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${PREFIX})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/drop-in)
run(${WORK_DIR}/drop-in/oiio-drop-in-oiio ${WORK_DIR}/drop-in/oiio.exr)
run(${WORK_DIR}/drop-in/oiio-drop-in-footprint ${WORK_DIR}/drop-in/footprint.exr)
