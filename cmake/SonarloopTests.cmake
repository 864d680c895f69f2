# sonarloop_add_test(SOURCE LIBS...): one Catch2 executable per test file, named after its path
# below tests/ (tests/sim/seabed/fractal_test.cpp -> test_sim_seabed_fractal), registered with CTest.
function(sonarloop_add_test source)
  set_property(GLOBAL APPEND PROPERTY SONARLOOP_TEST_SOURCES
                                      ${CMAKE_CURRENT_SOURCE_DIR}/${source})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR}/tests ${CMAKE_CURRENT_SOURCE_DIR}/${source})
  string(REGEX REPLACE "_test\\.cpp$" "" stem ${rel})
  string(REPLACE "/" "_" stem ${stem})
  set(name test_${stem})
  add_executable(${name} ${source})
  target_link_libraries(${name} PRIVATE sonarloop_catch_main ${ARGN})
  target_compile_definitions(${name} PRIVATE
    SONARLOOP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SONARLOOP_BINARY_DIR="${PROJECT_BINARY_DIR}"
    SONARLOOP_PYTHON="/usr/bin/python3")
  sonarloop_target_defaults(${name})
  # test code does a lot of intentional int/double arithmetic
  target_compile_options(${name} PRIVATE -Wno-conversion)
  # test cases tagged [may_skip] (tests/support/skip.h) run as an entry of their own, so that
  # their skip (exit 77) shows as skipped without ending the file's other cases
  file(READ ${CMAKE_CURRENT_SOURCE_DIR}/${source} text)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${source})
  string(FIND "${text}" "[may_skip]" may_skip)
  if(may_skip EQUAL -1)
    add_test(NAME ${name} COMMAND ${name} WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
  else()
    add_test(NAME ${name} COMMAND ${name} "~[may_skip]"
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    add_test(NAME ${name}_may_skip COMMAND ${name} "[may_skip]"
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(${name} ${name}_may_skip PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
  endif()
endfunction()

# sonarloop_check_all_tests_registered(): fails the configuration when a *_test.cpp under tests/
# is not built by any sonarloop_add_test (a test cannot vanish by a forgotten CMake line).
function(sonarloop_check_all_tests_registered)
  get_property(registered GLOBAL PROPERTY SONARLOOP_TEST_SOURCES)
  file(GLOB_RECURSE found ${PROJECT_SOURCE_DIR}/tests/*_test.cpp)
  set(missing "")
  foreach(f ${found})
    if(NOT f IN_LIST registered)
      list(APPEND missing ${f})
    endif()
  endforeach()
  if(missing)
    message(FATAL_ERROR "test sources not registered with sonarloop_add_test: ${missing}")
  endif()
endfunction()
