# Warnings shared by every Welkin target.
add_library(welkin_warnings INTERFACE)
target_compile_options(welkin_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>)
