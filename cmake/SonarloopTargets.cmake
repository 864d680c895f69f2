# Shared compile settings, applied per target (no global flags).

# sonarloop_target_defaults(TARGET): warnings, -Werror and sanitizers as the options ask.
function(sonarloop_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
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

# sonarloop_add_library(NAME SOURCES...): one static library per top-level folder.
function(sonarloop_add_library name)
  add_library(${name} STATIC ${ARGN})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  sonarloop_target_defaults(${name})
endfunction()
