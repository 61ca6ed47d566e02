# cmake --install BUILD --prefix P: the libraries, the public headers under P/include/footprint/,
# the CLI, and the CMake package P/lib/cmake/footprint (find_package(footprint CONFIG), target
# footprint::footprint; examples/consumer/ is a project that uses it).
include(CMakePackageConfigHelpers)

get_property(footprint_modules GLOBAL PROPERTY FOOTPRINT_MODULES)
install(TARGETS footprint_all ${footprint_modules}
        EXPORT footprintTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS footprint RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

foreach(header ${FOOTPRINT_PUBLIC_HEADERS})
    get_filename_component(folder ${header} DIRECTORY)
    install(FILES ${PROJECT_SOURCE_DIR}/src/${header}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/footprint/${folder})
endforeach()
install(FILES ${FOOTPRINT_GENERATED_ROOT}/footprint/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/footprint)
# The GLSL library (docs/engine.md): share/footprint/glsl/footprint/*.glsl with its version.glsl,
# included as "footprint/texture.glsl" from share/footprint/glsl.
set(FOOTPRINT_GLSL_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/footprint/glsl)  # footprint_GLSL_DIR
install(DIRECTORY ${PROJECT_SOURCE_DIR}/glsl/footprint
        DESTINATION ${FOOTPRINT_GLSL_INSTALL_DIR} FILES_MATCHING PATTERN "*.glsl")
install(FILES ${FOOTPRINT_GENERATED_ROOT}/glsl/footprint/version.glsl
        DESTINATION ${FOOTPRINT_GLSL_INSTALL_DIR}/footprint)

set(package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/footprint)
install(EXPORT footprintTargets NAMESPACE footprint:: DESTINATION ${package_dir})
configure_package_config_file(cmake/footprintConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/footprintConfig.cmake
                              INSTALL_DESTINATION ${package_dir}
                              PATH_VARS FOOTPRINT_GLSL_INSTALL_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/footprintConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/footprintConfig.cmake
              ${PROJECT_BINARY_DIR}/footprintConfigVersion.cmake
        DESTINATION ${package_dir})

# The installed package, tried as a user would: installed once into a fresh prefix (the fixture
# footprint-package), then examples/consumer and examples/oiio-drop-in (cmake/test_consumer.cmake)
# and the C++ snippets of README.md and docs/library.md (examples/snippets/,
# cmake/test_snippets.cmake) configured, built and run against it. Release builds only: a
# sanitizer build's libraries need the sanitizer runtimes in every program that links them.
if(NOT FOOTPRINT_SANITIZE AND NOT FOOTPRINT_TESTS_ONLY)
    set(package_prefix ${PROJECT_BINARY_DIR}/package-test/prefix)
    add_test(NAME footprint-package-install
             COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DPREFIX=${package_prefix}
                     -P ${PROJECT_SOURCE_DIR}/cmake/test_install.cmake)
    set_tests_properties(footprint-package-install PROPERTIES FIXTURES_SETUP footprint-package)
    # package_test(NAME SCRIPT PART): cmake/SCRIPT against the installed package.
    function(package_test name script part)
        add_test(NAME ${name}
                 COMMAND ${CMAKE_COMMAND} -DPREFIX=${package_prefix}
                         -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
                         -DWORK_DIR=${PROJECT_BINARY_DIR}/package-test/${part}
                         -P ${PROJECT_SOURCE_DIR}/cmake/${script})
        set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED footprint-package)
    endfunction()
    package_test(footprint-package-consumer test_consumer.cmake consumer)
    package_test(footprint-doc-snippets test_snippets.cmake snippets)
endif()
# Every C++ block of README.md and docs/library.md is, line for line, a region of one of those
# snippet programs (no build needed: it runs in every configuration).
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
    add_test(NAME footprint-doc-snippets-match
             COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/examples/snippets/check_snippets.py
                     ${PROJECT_SOURCE_DIR})
endif()
