# Shared compile settings, applied per target (no global flags).

# sonarloop_target_defaults(TARGET): warnings, -Werror and sanitizers as the options ask.
function(sonarloop_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  # Nothing reads errno after a math call. Without this, each std::sqrt carries a branch to
  # libm's for negative arguments (to set errno), and loops with a square root do not vectorise
  # (docs/rendering.md, "Where the time goes"). The results are the same: IEEE square roots.
  target_compile_options(${target} PRIVATE -fno-math-errno)
  if(SONARLOOP_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(SONARLOOP_FUZZ)
    # coverage for libFuzzer in every library, and the sanitizers that turn bugs into findings
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(SONARLOOP_TSAN)
    target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=thread)
  endif()
  if(SONARLOOP_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# The libraries whose code reads outside data (files, datagrams, TCP lines, YAML, images): in the
# sanitizer build with clang they carry libFuzzer's coverage instrumentation (CMakeLists.txt,
# SONARLOOP_FUZZ_IN_TESTS), so that the harnesses of tests/fuzz built there are guided by it.
set(SONARLOOP_FUZZ_COVERED_LIBRARIES sonarloop_common sonarloop_drivers sonarloop_config
    sonarloop_emulator sonarloop_atr sonarloop_study sonarloop_autonomy)

# Include scopes: a target sees the headers of the folders it links, not the whole source tree.
# Every #include of the project names its folder ("atr/detector.h"), so the include path of a
# target cannot be the source root (that would show it every folder). Instead each folder gets a
# directory of its own in the build tree, include_scopes/FOLDER, holding one symbolic link,
# FOLDER -> the source folder; a library adds its folder's directory to its PUBLIC include path,
# so that it and what links it, and nothing else, resolve "FOLDER/...". A header of a layer a
# library does not link is then "not found": the build enforces the layers of
# scripts/check_layers.sh (design.md, "Layers").
#
# sonarloop_include_scope(TARGET PUBLIC|PRIVATE|INTERFACE FOLDER): TARGET sees FOLDER's headers
# (FOLDER relative to the source root: atr, tests).
function(sonarloop_include_scope target scope folder)
  set(dir ${PROJECT_BINARY_DIR}/include_scopes/${folder})
  if(NOT IS_SYMLINK ${dir}/${folder})
    file(MAKE_DIRECTORY ${dir})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${dir}/${folder} SYMBOLIC)
  endif()
  target_include_directories(${target} ${scope} ${dir})
endfunction()

# sonarloop_add_library(NAME SOURCES...): one static library per top-level folder (the folder of
# the calling CMakeLists.txt's first path component: sim/render's sources are sonarloop_sim's).
function(sonarloop_add_library name)
  add_library(${name} STATIC ${ARGN})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  string(REGEX REPLACE "/.*" "" folder ${rel})
  sonarloop_include_scope(${name} PUBLIC ${folder})
  target_link_libraries(${name} PUBLIC sonarloop_units)
  sonarloop_target_defaults(${name})
  if(SONARLOOP_SANITIZE)
    # The ASan build's -O1 (its build type, for the test code and the tools) is raised to -O2 for
    # the libraries, the code under test: the tests spend their time there, and with clang it
    # compiles as fast at -O2 and runs up to twice as fast under ASan (seabed model test 41 ->
    # 21 s, profile renderer 42 -> 29 s), whereas the test code compiles a fifth slower at -O2.
    # (Not in the ThreadSanitizer build: GCC compiles a fifth slower at -O2 there, and its few
    # tests are short.)
    target_compile_options(${name} PRIVATE -O2)
  endif()
  if(SONARLOOP_FUZZ_IN_TESTS AND name IN_LIST SONARLOOP_FUZZ_COVERED_LIBRARIES)
    # coverage only (the sanitizers' runtime has the no-op hooks a test executable needs)
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
