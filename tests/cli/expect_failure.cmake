# Runs fdem on a scenario that must fail during the simulation and checks the contract.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${FDEM} run ${SCENARIO} --out ${OUT} --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "expected exit code 1, got ${rc}\n${out}\n${err}")
endif()
if(NOT err MATCHES "step [0-9]+ \\(t = [0-9.e+-]+ s\\): triangle [0-9]+ \\(body 0\\): element inverted \\(det F = [-0-9.e+]+\\); reduce dt")
  message(FATAL_ERROR "message does not name step, time, element and remedy:\n${err}")
endif()
if(NOT EXISTS ${OUT}/failure.vtu)
  message(FATAL_ERROR "failure.vtu was not written")
endif()
