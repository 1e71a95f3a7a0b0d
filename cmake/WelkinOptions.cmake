# Warnings shared by every Welkin target. Exported (static module libraries name it in their link
# interface) but empty outside this build, so consumers' flags are their own.
add_library(welkin_warnings INTERFACE)
target_compile_options(welkin_warnings INTERFACE
  $<BUILD_INTERFACE:$<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>>)

# Coverage feedback, ASan and UBSan inside a library the fuzz targets exercise (WELKIN_FUZZ builds
# only); the fuzz targets themselves link the fuzzer's main. Undefined behaviour stops the run
# (-fno-sanitize-recover) so libFuzzer records it as a finding instead of printing and going on.
set(WELKIN_FUZZ_SANITIZERS -fsanitize=address,undefined -fno-sanitize-recover=undefined)
function(welkin_fuzz_instrument target)
  if(NOT WELKIN_FUZZ)
    return()
  endif()
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "WELKIN_FUZZ needs clang (libFuzzer); configure with CMAKE_CXX_COMPILER=clang++")
  endif()
  target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link ${WELKIN_FUZZ_SANITIZERS} -fno-omit-frame-pointer)
  target_link_options(${target} PRIVATE ${WELKIN_FUZZ_SANITIZERS})
endfunction()

# A libFuzzer executable (WELKIN_FUZZ builds only): libFuzzer's main, ASan and UBSan.
function(welkin_fuzz_target target)
  target_compile_options(${target} PRIVATE -fsanitize=fuzzer ${WELKIN_FUZZ_SANITIZERS} -fno-omit-frame-pointer)
  target_link_options(${target} PRIVATE -fsanitize=fuzzer ${WELKIN_FUZZ_SANITIZERS})
endfunction()
