# Warnings and code generation for Caligo's own targets (never applied to third-party code).
function(caligo_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-missing-field-initializers -march=x86-64-v3)
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()

# caligo_library(name SOURCES ... DEPS ...): one static library per src/ folder.
function(caligo_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(caligo_${name} STATIC ${ARG_SOURCES})
  add_library(caligo::${name} ALIAS caligo_${name})
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
