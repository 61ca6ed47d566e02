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

set(package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/footprint)
install(EXPORT footprintTargets NAMESPACE footprint:: DESTINATION ${package_dir})
configure_package_config_file(cmake/footprintConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/footprintConfig.cmake
                              INSTALL_DESTINATION ${package_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/footprintConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/footprintConfig.cmake
              ${PROJECT_BINARY_DIR}/footprintConfigVersion.cmake
        DESTINATION ${package_dir})

# The installed package, tried as a user would: install into a fresh prefix, then configure,
# build and run examples/consumer against it (cmake/test_consumer.cmake). Release builds only:
# a sanitizer build's libraries need the sanitizer runtimes in every program that links them.
if(NOT FOOTPRINT_SANITIZE AND NOT FOOTPRINT_TESTS_ONLY)
    add_test(NAME footprint-package-consumer
             COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
                     -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DWORK_DIR=${PROJECT_BINARY_DIR}/consumer-test
                     -P ${PROJECT_SOURCE_DIR}/cmake/test_consumer.cmake)
endif()
