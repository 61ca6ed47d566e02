# footprint_module(NAME SOURCES a.cpp b.cpp DEPS other_module ...)
# One static library per module, include root at src/ (so code writes #include "texture/mip_pyramid.h").
# Unit tests live beside the code as *_test.cpp and are collected into the one gtest binary.
set_property(GLOBAL PROPERTY FOOTPRINT_TEST_SOURCES "")

function(footprint_module name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS;TESTS" ${ARGN})
    add_library(footprint_${name} STATIC ${ARG_SOURCES})
    target_include_directories(footprint_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(footprint_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    foreach(test ${ARG_TESTS})
        set_property(GLOBAL APPEND PROPERTY FOOTPRINT_TEST_SOURCES
                     ${CMAKE_CURRENT_SOURCE_DIR}/${test})
    endforeach()
endfunction()
