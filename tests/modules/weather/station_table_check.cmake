# Regenerates the station table from the installed weather-util-data and compares it byte for byte
# with the one the project ships.
execute_process(COMMAND ${GENERATOR} --out ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "welkin-station-table failed (${rc}); is weather-util-data installed (tools/setup)?")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${SHIPPED} RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "${SHIPPED} differs from what tools/station_table makes of weather-util-data now; regenerate it")
endif()
message(STATUS "the shipped station table is the generator's output")
