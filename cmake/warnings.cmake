# Compiler warnings for forensim's own targets (never applied to third-party headers).
add_library(forensim_warnings INTERFACE)
target_compile_options(forensim_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                       -Wcast-align -Wunused -Woverloaded-virtual -Wnull-dereference -Wformat=2)
if(FORENSIM_WARNINGS_AS_ERRORS)
  target_compile_options(forensim_warnings INTERFACE -Werror)
endif()

add_library(forensim_sanitizers INTERFACE)
if(FORENSIM_WITH_SANITIZERS OR FORENSIM_WITH_FUZZERS)
  target_compile_options(forensim_sanitizers INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                         -fno-sanitize-recover=undefined)
  target_link_options(forensim_sanitizers INTERFACE -fsanitize=address,undefined)
endif()
if(FORENSIM_WITH_FUZZERS)
  # libFuzzer's coverage instrumentation in forensim's own code; the fuzz targets link libFuzzer itself.
  target_compile_options(forensim_sanitizers INTERFACE -fsanitize=fuzzer-no-link)
endif()
