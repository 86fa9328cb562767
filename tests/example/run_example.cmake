# Run one example: fdem run must exit 0 and leave series.pvd, history.csv and a frame behind.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${FDEM} run ${SCENARIO} --end-time ${END_TIME} --out ${OUT} --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fdem run exited with ${rc}\n${out}\n${err}")
endif()
foreach(f series.pvd history.csv frame_000000.vtu)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "missing output ${OUT}/${f}")
  endif()
endforeach()
message(STATUS "ok: ${SCENARIO}")
