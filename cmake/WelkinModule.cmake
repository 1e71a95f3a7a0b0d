# welkin_add_module(NAME name SOURCES ... [LIBS ...] [OUTPUT_DIR dir] [NO_INSTALL])
# Builds a module twice from the same sources and registration code:
#   welkin_<name>_static  a static library for all-in-one builds and tests (welkin::modules::<name>_module())
#   welkin_<name>         the plugin (MODULE library) with the exported entry point, plus
#                         <name>.module.json beside it: the manifest the runtime reads before loading.
# module.json in the module folder is the single source of the manifest.
function(welkin_add_module)
  cmake_parse_arguments(M "NO_INSTALL" "NAME;OUTPUT_DIR" "SOURCES;LIBS" ${ARGN})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  if(NOT M_OUTPUT_DIR)
    set(M_OUTPUT_DIR ${WELKIN_MODULE_OUTPUT_DIR})
  endif()
  file(READ ${dir}/module.json manifest)
  string(JSON manifest_name GET "${manifest}" name)
  if(NOT manifest_name STREQUAL M_NAME)
    message(FATAL_ERROR "${dir}/module.json names '${manifest_name}', CMake says '${M_NAME}'")
  endif()

  set(gen ${CMAKE_CURRENT_BINARY_DIR}/generated)
  file(MAKE_DIRECTORY ${gen})
  # The definition: embedded manifest + the module's register function (defined in src/register.cpp).
  file(CONFIGURE OUTPUT ${gen}/module_definition.cpp CONTENT [=[
#include "welkin/core/module.h"
namespace welkin::modules {
void register_@M_NAME@(ModuleContext& ctx);
const ModuleDefinition& @M_NAME@_module() {
  static const ModuleDefinition def{R"welkin(@manifest@)welkin", "@dir@", &register_@M_NAME@};
  return def;
}
}  // namespace welkin::modules
]=] @ONLY)
  file(CONFIGURE OUTPUT ${gen}/plugin_entry.cpp CONTENT [=[
#include "welkin/core/module.h"
namespace welkin::modules { const ModuleDefinition& @M_NAME@_module(); }
extern "C" __attribute__((visibility("default"))) const welkin::ModuleDefinition* welkin_module_entry(unsigned* abi) {
  *abi = welkin::kModuleAbiVersion;
  return &welkin::modules::@M_NAME@_module();
}
]=] @ONLY)

  add_library(welkin_${M_NAME}_static STATIC ${M_SOURCES} ${gen}/module_definition.cpp)
  target_include_directories(welkin_${M_NAME}_static PUBLIC
    $<BUILD_INTERFACE:${dir}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(welkin_${M_NAME}_static PUBLIC welkin_runtime ${M_LIBS} PRIVATE welkin_warnings)

  add_library(welkin_${M_NAME} MODULE ${gen}/plugin_entry.cpp)
  target_link_libraries(welkin_${M_NAME} PRIVATE welkin_${M_NAME}_static)
  file(RELATIVE_PATH module_to_lib /${WELKIN_INSTALL_MODULE_DIR} /${CMAKE_INSTALL_LIBDIR})
  set_target_properties(welkin_${M_NAME} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${M_OUTPUT_DIR}
    CXX_VISIBILITY_PRESET hidden INSTALL_RPATH "$ORIGIN/${module_to_lib}")
  add_library(Welkin::${M_NAME} ALIAS welkin_${M_NAME}_static)

  # Manifests: the build tree points at the source folder for shaders and presets; the installed
  # one at share/welkin/modules/<name>, relative to itself so the install tree can move.
  string(JSON build_manifest SET "${manifest}" library "\"libwelkin_${M_NAME}.so\"")
  string(JSON build_manifest SET "${build_manifest}" data_dir "\"${dir}\"")
  file(WRITE ${M_OUTPUT_DIR}/${M_NAME}.module.json "${build_manifest}\n")
  string(JSON install_manifest SET "${manifest}" library "\"libwelkin_${M_NAME}.so\"")
  string(JSON install_manifest SET "${install_manifest}" data_dir "\"../../../share/welkin/modules/${M_NAME}\"")
  file(WRITE ${gen}/${M_NAME}.module.json "${install_manifest}\n")
  if(M_NO_INSTALL)
    return()
  endif()

  install(TARGETS welkin_${M_NAME} LIBRARY DESTINATION ${WELKIN_INSTALL_MODULE_DIR})
  install(FILES ${gen}/${M_NAME}.module.json DESTINATION ${WELKIN_INSTALL_MODULE_DIR})
  install(TARGETS welkin_${M_NAME}_static EXPORT WelkinTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  set_target_properties(welkin_${M_NAME}_static PROPERTIES EXPORT_NAME ${M_NAME})
  if(EXISTS ${dir}/include)
    install(DIRECTORY ${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
  foreach(sub shaders presets editor data)
    if(EXISTS ${dir}/${sub})
      install(DIRECTORY ${dir}/${sub} DESTINATION ${CMAKE_INSTALL_DATADIR}/welkin/modules/${M_NAME})
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY WELKIN_MODULES ${M_NAME})
endfunction()
