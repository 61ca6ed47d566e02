# footprint_module(NAME SOURCES a.cpp b.cpp DEPS other_module ...)
# One static library per module, footprint_NAME, installed and exported as footprint::NAME.
# Unit tests live beside the code as *_test.cpp and are collected into the one gtest binary.
#
# Include roots. The code includes "texture/mip_pyramid.h" (src/); the public headers include each
# other as <footprint/texture/mip_pyramid.h>, which resolves in the build tree through the link
# FOOTPRINT_INCLUDE_ROOT/footprint → src/ (and <footprint/version.h> in FOOTPRINT_GENERATED_ROOT),
# and once installed in <prefix>/include.
set_property(GLOBAL PROPERTY FOOTPRINT_TEST_SOURCES "")
set_property(GLOBAL PROPERTY FOOTPRINT_MODULES "")

function(footprint_module name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS;TESTS" ${ARGN})
    add_library(footprint_${name} STATIC ${ARG_SOURCES})
    set_target_properties(footprint_${name} PROPERTIES EXPORT_NAME ${name})
    target_include_directories(footprint_${name} PUBLIC
        $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>
        $<BUILD_INTERFACE:${FOOTPRINT_INCLUDE_ROOT}>
        $<BUILD_INTERFACE:${FOOTPRINT_GENERATED_ROOT}>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(footprint_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    set_property(GLOBAL APPEND PROPERTY FOOTPRINT_MODULES footprint_${name})
    foreach(test ${ARG_TESTS})
        set_property(GLOBAL APPEND PROPERTY FOOTPRINT_TEST_SOURCES
                     ${CMAKE_CURRENT_SOURCE_DIR}/${test})
    endforeach()
endfunction()
