# Installs the build tree into a scratch prefix, builds the consumer project against it, runs it;
# then runs the installed programs from the prefix as a user would: they must find their own
# libraries (RPATH $ORIGIN/../lib), modules and shaders, and nothing in the build tree.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -G Ninja -DCMAKE_PREFIX_PATH=${WORK}/prefix
  RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed")
endif()
execute_process(COMMAND ${WORK}/build/consumer ${WORK}/consumer.png RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer run failed")
endif()

# examples/host-app, a program with its own window, camera, geometry and shaders and Welkin inside,
# built against the installed package and run headless with both depth conventions. Its frame must
# match `welkin render` of the same scene with the host's objects as debug shapes (host_objects.json).
# Tolerance, over the third frame (the reference is `welkin render --frames 3`'s; the host draws
# through render's draw_geometry, so its materials read the frame's own lights from the first): a mean
# colour difference of at most 0.25 steps of 255, and at most 0.2% of the pixels (28 of 160x90, one
# box's silhouette) with a channel more than 3 steps apart. Measured on llvmpipe: 0 and 0 (the frames
# are byte for byte the same, both depth conventions). The allowance is for what differs in kind: the
# host rasterises its boxes from its own vertex arithmetic (a silhouette pixel can flip on another
# driver), and forward depth comes back through float rounding (0.5 m at 3 km: below a step of haze).
# A depth read 10% off fails (0.6% of the pixels beyond 3 steps), as do unlit materials (39 steps).
set(HOST_MEAN_STEPS 0.25)
set(HOST_FAR_STEPS 3)
set(HOST_FAR_FRACTION 0.002)
set(host_size 160x90)
# The smallest complete host (host-minimal, built below) is the one docs/embedding.md shows, verbatim.
file(READ ${SOURCE_ROOT}/examples/host-app/minimal.cpp minimal)
file(READ ${SOURCE_ROOT}/docs/embedding.md embedding)
string(FIND "${embedding}" "${minimal}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "docs/embedding.md does not show examples/host-app/minimal.cpp as it is")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_ROOT}/examples/host-app -B ${WORK}/host-build -G Ninja
  -DCMAKE_PREFIX_PATH=${WORK}/prefix RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "host-app configure failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/host-build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "host-app build failed")
endif()
foreach(depth reversed forward)
  set(flag)
  if(depth STREQUAL "forward")
    set(flag --forward-depth)
  endif()
  execute_process(COMMAND ${WORK}/host-build/host-app examples/host-app/scene.json --size ${host_size} --frames 3
    --out ${WORK}/host-${depth} ${flag} WORKING_DIRECTORY ${SOURCE_ROOT} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(rc OR NOT EXISTS ${WORK}/host-${depth}/frame-0002.png)
    message(FATAL_ERROR "host-app --frames 3 (${depth} depth) failed (${rc}): ${err}")
  endif()
endforeach()
# The reference: the example's scene plus the host's objects, rendered by the installed `welkin`.
file(READ ${SOURCE_ROOT}/examples/host-app/scene.json scene)
file(READ ${CMAKE_CURRENT_LIST_DIR}/host_objects.json objects)
string(JSON count LENGTH "${scene}" entities)
string(JSON added LENGTH "${objects}" entities)
math(EXPR last "${added} - 1")
foreach(i RANGE ${last})
  string(JSON entity GET "${objects}" entities ${i})
  math(EXPR at "${count} + ${i}")
  string(JSON scene SET "${scene}" entities ${at} "${entity}")
endforeach()
file(WRITE ${WORK}/host-reference.json "${scene}")
# The first frame too, against `welkin render --frames 1`'s, with the same tolerance: the host's
# materials are lit from the first frame on (measured on llvmpipe: 0 and 0, as the third; before
# draw_geometry the first frame's materials were unlit, as the unlit materials above that fail).
foreach(frames 3 1)
  execute_process(COMMAND ${WORK}/prefix/bin/welkin render ${WORK}/host-reference.json --size ${host_size}
    --frames ${frames} --out ${WORK}/host-reference-${frames}.png WORKING_DIRECTORY ${SOURCE_ROOT}
    RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "welkin render of the host's scene failed (${rc}): ${err}")
  endif()
endforeach()
foreach(depth reversed forward)
  foreach(frame 0002 0000)
    set(frames 3)
    if(frame STREQUAL "0000")
      set(frames 1)
    endif()
    execute_process(COMMAND ${WORK}/build/compare_images ${WORK}/host-${depth}/frame-${frame}.png
      ${WORK}/host-reference-${frames}.png ${HOST_MEAN_STEPS} ${HOST_FAR_STEPS} ${HOST_FAR_FRACTION}
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    message(STATUS "host-app (${depth} depth, frame ${frame}) against welkin render: ${out}${err}")
    if(rc)
      message(FATAL_ERROR "host-app's frame ${frame} (${depth} depth) is not welkin render's: ${out}${err}")
    endif()
  endforeach()
endforeach()

set(prefix ${WORK}/prefix)
# No help from the environment: what runs is what was installed.
unset(ENV{LD_LIBRARY_PATH})
unset(ENV{WELKIN_MODULE_PATH})
execute_process(COMMAND ${prefix}/bin/welkin --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR NOT out MATCHES "render")
  message(FATAL_ERROR "installed welkin --help failed (${rc}): ${out}${err}")
endif()
if(EXISTS ${prefix}/bin/welkin-editor)
  execute_process(COMMAND ${prefix}/bin/welkin-editor --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc OR NOT out MATCHES "--script")
    message(FATAL_ERROR "installed welkin-editor --help failed (${rc}): ${out}${err}")
  endif()
  # A scripted session of the installed editor (an edit, a save, a quit) under Xvfb.
  execute_process(COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/installed_editor.sh ${prefix} ${SOURCE_ROOT} ${WORK}/editor
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 77)
    message(STATUS "installed welkin-editor --script skipped: ${out}")
  elseif(rc)
    message(FATAL_ERROR "installed welkin-editor --script failed (${rc}): ${out}${err}")
  endif()
endif()
execute_process(COMMAND ${prefix}/bin/welkin info --modules --json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc)
  message(FATAL_ERROR "installed welkin info failed (${rc}): ${err}")
endif()
# Module folders and data folders: the prefix's own, never the build tree's or the sources'.
foreach(foreign ${BUILD}/lib/ ${SOURCE_ROOT}/modules/)
  string(FIND "${out}" "${foreign}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "installed welkin looks into ${foreign}:\n${out}")
  endif()
endforeach()
string(JSON skipped LENGTH "${out}" skipped_manifests)
if(NOT skipped EQUAL 0)
  message(FATAL_ERROR "installed module manifests were skipped:\n${out}")
endif()
# The README's command, from the source root (the scene's terrain file is relative to it): a scene
# that loads plugins (terrain, clouds, time of day) and the linked-in atmosphere.
execute_process(COMMAND ${prefix}/bin/welkin render assets/scenes/default.json --size 32x18 --out ${WORK}/render.png
  WORKING_DIRECTORY ${SOURCE_ROOT} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR NOT EXISTS ${WORK}/render.png)
  message(FATAL_ERROR "installed welkin render failed (${rc}): ${out}${err}")
endif()
