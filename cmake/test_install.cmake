# cmake -DBUILD_DIR=… -DPREFIX=… -P test_install.cmake
# Installs the build into a fresh PREFIX, the package the consumer and snippet tests build
# against (the fixture footprint-package in cmake/install.cmake), and checks that the GLSL library
# and its version defines are where docs/engine.md says they are.
include(${CMAKE_CURRENT_LIST_DIR}/package_test_run.cmake)
file(REMOVE_RECURSE ${PREFIX})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
foreach(part version common texture bump highlight environment)
    if(NOT EXISTS ${PREFIX}/share/footprint/glsl/footprint/${part}.glsl)
        message(FATAL_ERROR "not installed: share/footprint/glsl/footprint/${part}.glsl")
    endif()
endforeach()
