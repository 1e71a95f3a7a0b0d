# welkin_add_test(NAME name SOURCES a.cpp ... LIBS lib ... [LABELS l ...])
# One GoogleTest executable per call, its tests discovered into ctest.
function(welkin_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main welkin_warnings)
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  # The checkout's absolute paths go only to the sources that name them: the others compile the
  # same in every checkout, so ccache (base_dir) shares them between worktrees.
  foreach(src IN LISTS T_SOURCES)
    get_filename_component(src_path "${src}" ABSOLUTE)
    if(EXISTS "${src_path}")
      file(STRINGS "${src_path}" uses_paths REGEX "WELKIN_(SOURCE|BINARY)_DIR" LIMIT_COUNT 1)
      if(uses_paths)
        set_property(SOURCE "${src}" APPEND PROPERTY COMPILE_DEFINITIONS
          "WELKIN_SOURCE_DIR=\"${PROJECT_SOURCE_DIR}\"" "WELKIN_BINARY_DIR=\"${PROJECT_BINARY_DIR}\"")
      endif()
    endif()
  endforeach()
  # In the fuzz build (clang, instrumented libraries) the tests run under ASan and UBSan too:
  # tests/runtime/assets/run_fuzz.sh builds and runs the runtime's and the assets' there.
  if(WELKIN_FUZZ)
    target_compile_options(${T_NAME} PRIVATE ${WELKIN_FUZZ_SANITIZERS} -fno-omit-frame-pointer)
    target_link_options(${T_NAME} PRIVATE ${WELKIN_FUZZ_SANITIZERS})
  endif()
  include(GoogleTest)
  # The disk cache (core/disk_cache.h) is the build tree's own, never the user's: a LUT that one test
  # builds, the next reads, bit for bit (AtmosphereLuts.ReadFromTheDiskCacheBitForBit), and the
  # tests of building them turn it off.
  gtest_discover_tests(${T_NAME} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "WELKIN_CACHE_DIR=${PROJECT_BINARY_DIR}/test-disk-cache")
  # Labels are set by a script ctest reads after the discovered tests, from the list of their names
  # discovery leaves in <name>_TESTS: gtest_discover_tests' PROPERTIES splits a list value, which
  # kept only the first label.
  if(T_LABELS)
    set(labels_file "${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_labels.cmake")
    file(WRITE "${labels_file}"
      "if(${T_NAME}_TESTS)\n"
      "  set_tests_properties(\${${T_NAME}_TESTS} PROPERTIES LABELS \"${T_LABELS}\")\n"
      "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${labels_file}")
  endif()
endfunction()
