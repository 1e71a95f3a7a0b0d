# Warnings shared by every Welkin target. Exported (static module libraries name it in their link
# interface) but empty outside this build, so consumers' flags are their own.
add_library(welkin_warnings INTERFACE)
target_compile_options(welkin_warnings INTERFACE
  $<BUILD_INTERFACE:$<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>>)

# Coverage feedback and ASan inside a library the fuzz targets exercise (WELKIN_FUZZ builds only);
# the fuzz targets themselves link the fuzzer's main.
function(welkin_fuzz_instrument target)
  if(NOT WELKIN_FUZZ)
    return()
  endif()
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "WELKIN_FUZZ needs clang (libFuzzer); configure with CMAKE_CXX_COMPILER=clang++")
  endif()
  target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address -fno-omit-frame-pointer)
  target_link_options(${target} PRIVATE -fsanitize=address)
endfunction()
