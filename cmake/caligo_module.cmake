# Warnings and code generation for Caligo's own targets (never applied to third-party code).
function(caligo_target_options target)
  # -fno-semantic-interposition: position-independent code (for the Python module) would
  # otherwise let every global function be replaced at load time, and gcc would not inline them.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-missing-field-initializers -march=x86-64-v3
                                           -fno-semantic-interposition)
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()

# caligo_library(name SOURCES ... DEPS ...): one static library per src/ folder.
function(caligo_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(caligo_${name} STATIC ${ARG_SOURCES})
  add_library(caligo::${name} ALIAS caligo_${name})
  set_property(GLOBAL APPEND PROPERTY CALIGO_LIBRARIES caligo_${name})
  target_include_directories(caligo_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(caligo_${name} PUBLIC ${ARG_DEPS})
  caligo_target_options(caligo_${name})
endfunction()

# caligo_test(name SOURCES ... DEPS ...): one gtest binary per folder, one CTest entry each
# (process start-up is paid once per binary, not once per test case).
function(caligo_test name)
  if(NOT CALIGO_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name}_test ${ARG_SOURCES})
  target_link_libraries(${name}_test PRIVATE ${ARG_DEPS} GTest::gtest_main)
  caligo_target_options(${name}_test)
  add_test(NAME ${name} COMMAND ${name}_test)
endfunction()

# caligo_plugin(name SOURCES ... DEPS ...): a module (name.so, no "lib" prefix) that keeps a
# heavy optional library (OpenImageIO, OpenVDB, assimp) out of every process that does not use
# it; core/module_loader.h loads it on first use. All plugins go next to the caligo executable;
# that folder is also compiled into the loader as a fallback, so test binaries elsewhere in the
# build tree find them. Static libraries linked in (position-independent ones) stay private
# to the plugin (--exclude-libs). Symbols keep default visibility: with -fvisibility=hidden the
# plugin's instantiations of OpenVDB templates would hide some static members (once flags)
# while others, under OPENVDB_API classes, are still bound by libopenvdb, and
# openvdb::initialize() then crashes on the mix.
set(CALIGO_PLUGIN_DIR "${PROJECT_BINARY_DIR}/apps/caligo")
function(caligo_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES PREFIX "" LIBRARY_OUTPUT_DIRECTORY "${CALIGO_PLUGIN_DIR}")
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  target_link_options(${name} PRIVATE -Wl,--exclude-libs,ALL)
  caligo_target_options(${name})
endfunction()
