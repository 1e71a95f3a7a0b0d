# Warnings shared by every Welkin target. Exported (static module libraries name it in their link
# interface) but empty outside this build, so consumers' flags are their own.
add_library(welkin_warnings INTERFACE)
target_compile_options(welkin_warnings INTERFACE
  $<BUILD_INTERFACE:$<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>>)
