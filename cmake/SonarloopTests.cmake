# Tests: one Catch2 executable per test folder, one CTest entry per test file.
#
# sonarloop_add_test(SOURCE LIBS...) adds SOURCE to its folder's executable, named after the
# folder below tests/ (tests/sim/seabed/*_test.cpp -> test_sim_seabed), and links LIBS to it. The
# file's cases run as the CTest entry named after the file (tests/sim/seabed/noise_layer_test.cpp ->
# test_sim_seabed_noise_layer): the executable selects them by the tag Catch2 gives every case with
# -# (--filenames-as-tags), "[#noise_layer_test]", and --warn NoTests makes an entry that selects no
# case fail instead of passing empty. Why one executable per folder: 20 links instead of 120, and
# one precompiled header (Catch2, Eigen and the standard library, tests/support/test_pch.h)
# parsed once per build instead of once per test file.
#
# Test cases tagged [may_skip] (tests/support/skip.h) run as an entry of their own
# (test_NAME_may_skip), so that their skip (exit 77) shows as skipped without ending the file's
# other cases.
#
# Test cases tagged [realtime] mostly wait on real time (a paced mission of three processes):
# they too run as an entry of their own (test_NAME_realtime), which CTest's resource allocation
# (scripts/test.sh: ctest -j N+1 --resource-spec-file build/ctest_resources.json) gives a "waits"
# slot instead of one of the N "cores" slots every other entry takes. So a core is not left idle
# while it waits: N busy entries run beside it. (Without the resource file, plain `ctest -j N`
# runs every entry as one of N, as before.)

# The precompiled header every test executable reuses: compiled once, with the flags of the tests
# (and in the ASan build once more at -O0, for the folders compiled at -O0: a PCH serves only
# the optimisation level it was made with).
function(sonarloop_add_test_pch)
  set(pchs sonarloop_test_pch)
  if(SONARLOOP_SANITIZE)
    list(APPEND pchs sonarloop_test_pch_o0)
  endif()
  foreach(pch ${pchs})
    add_library(${pch} OBJECT ${PROJECT_SOURCE_DIR}/tests/support/test_pch.cpp)
    target_link_libraries(${pch} PRIVATE Catch2::Catch2 Eigen3::Eigen)
    sonarloop_include_scope(${pch} PRIVATE tests)
    sonarloop_test_settings(${pch})
    target_precompile_headers(${pch} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support/test_pch.h)
  endforeach()
  if(SONARLOOP_SANITIZE)
    target_compile_options(sonarloop_test_pch_o0 PRIVATE -O0)
  endif()
endfunction()

# Test folders whose code the ASan build compiles at -O0 (SONARLOOP_O0_TEST_FOLDERS,
# tests/CMakeLists.txt): Catch2's assertions make large functions that clang takes 3-4x longer to
# compile at -O1 under ASan (36 s against 10 s for one batch). Not every folder: a test
# executable keeps one copy of each inline function (of Eigen, the standard library, the project's
# headers) and the linker takes the first, the test code's; at -O0 that copy also serves the
# libraries' calls, and tests that run the libraries in-process slowed 3-16x. So only the folders
# whose tests run the sonarloop binary or parse small inputs (measured: the 130 entries ran as
# fast, 453 s against 474 s, and the test objects took 171 s to compile instead of 247 s). (-O0
# comes after the build type's -O1, so it wins.)

# The compile settings shared by the test executables and their precompiled header (a PCH is
# used only with the flags it was made with).
function(sonarloop_test_settings target)
  target_compile_definitions(${target} PRIVATE
    SONARLOOP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SONARLOOP_BINARY_DIR="${PROJECT_BINARY_DIR}"
    SONARLOOP_PYTHON="/usr/bin/python3")
  sonarloop_target_defaults(${target})
  # test code does a lot of intentional int/double arithmetic
  target_compile_options(${target} PRIVATE -Wno-conversion)
endfunction()

# test_<folder> for the current source folder below tests/, created on first use.
function(sonarloop_test_executable out_var)
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR}/tests ${CMAKE_CURRENT_SOURCE_DIR})
  string(REPLACE "/" "_" name ${folder})
  set(exe test_${name})
  if(NOT TARGET ${exe})
    add_executable(${exe})
    target_link_libraries(${exe} PRIVATE sonarloop_catch_main)
    sonarloop_test_settings(${exe})
    if(SONARLOOP_SANITIZE AND folder IN_LIST SONARLOOP_O0_TEST_FOLDERS)
      target_compile_options(${exe} PRIVATE -O0)
      target_precompile_headers(${exe} REUSE_FROM sonarloop_test_pch_o0)
    else()
      target_precompile_headers(${exe} REUSE_FROM sonarloop_test_pch)
    endif()
  endif()
  set(${out_var} ${exe} PARENT_SCOPE)
endfunction()

function(sonarloop_add_test source)
  set_property(GLOBAL APPEND PROPERTY SONARLOOP_TEST_SOURCES
                                      ${CMAKE_CURRENT_SOURCE_DIR}/${source})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR}/tests ${CMAKE_CURRENT_SOURCE_DIR}/${source})
  string(REGEX REPLACE "_test\\.cpp$" "" stem ${rel})
  string(REPLACE "/" "_" stem ${stem})
  set(name test_${stem})
  if(SONARLOOP_TSAN AND NOT name IN_LIST SONARLOOP_TSAN_TESTS)
    return()  # the ThreadSanitizer build has only the concurrent code's tests
  endif()
  get_filename_component(file_tag ${source} NAME_WE)
  sonarloop_test_executable(exe)
  target_sources(${exe} PRIVATE ${source})
  if(ARGN)
    target_link_libraries(${exe} PRIVATE ${ARGN})
  endif()
  set(select ${exe} "-#" --warn NoTests)
  file(READ ${CMAKE_CURRENT_SOURCE_DIR}/${source} text)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${source})
  # the file's own entry: every case but those that run as an entry of their own
  set(main_filter "[#${file_tag}]")
  set(own_entries)
  foreach(tag may_skip realtime)
    string(FIND "${text}" "[${tag}]" found)
    if(NOT found EQUAL -1)
      string(APPEND main_filter "~[${tag}]")
      list(APPEND own_entries ${tag})
    endif()
  endforeach()
  add_test(NAME ${name} COMMAND ${select} "${main_filter}"
           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 RESOURCE_GROUPS "cores:1")
  if(name IN_LIST SONARLOOP_LONG_TESTS)
    set_tests_properties(${name} PROPERTIES COST 100)
  endif()
  foreach(tag ${own_entries})
    add_test(NAME ${name}_${tag} COMMAND ${select} "[#${file_tag}][${tag}]"
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(${name}_${tag} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600
                                                   RESOURCE_GROUPS "cores:1")
  endforeach()
  if(realtime IN_LIST own_entries)
    # it waits: a "waits" slot, and it starts first (the longest entry)
    set_tests_properties(${name}_realtime PROPERTIES RESOURCE_GROUPS "waits:1" COST 1000)
  endif()
endfunction()

# sonarloop_write_ctest_resources(): the resource file of scripts/test.sh's ctest run,
# build/ctest_resources.json: as many "cores" slots as the machine has logical cores, and one
# "waits" slot ([realtime] entries). An entry added with add_test outside sonarloop_add_test
# (a script, a Python or browser test) sets RESOURCE_GROUPS "cores:1" itself where it is added.
function(sonarloop_write_ctest_resources)
  cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
  file(WRITE ${PROJECT_BINARY_DIR}/ctest_resources.json
       "{\"version\": {\"major\": 1, \"minor\": 0}, \"local\": [{\"cores\": [{\"id\": \"0\", "
       "\"slots\": ${cores}}], \"waits\": [{\"id\": \"0\", \"slots\": 1}]}]}\n")
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
