# Runs ${FDEM} with ${ARGS} (a ;-list) and checks the exit code is exactly ${RC}
# and that stderr matches ${REGEX} when given.
execute_process(COMMAND ${FDEM} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL RC)
  message(FATAL_ERROR "expected exit code ${RC}, got ${rc}\n${out}\n${err}")
endif()
if(DEFINED REGEX AND NOT err MATCHES "${REGEX}")
  message(FATAL_ERROR "stderr does not match '${REGEX}':\n${err}")
endif()
# Optional: ${COUNT_REGEX} must occur exactly ${COUNT} times in stderr.
if(DEFINED COUNT_REGEX)
  string(REGEX MATCHALL "${COUNT_REGEX}" hits "${err}")
  list(LENGTH hits n)
  if(NOT n EQUAL COUNT)
    message(FATAL_ERROR "expected ${COUNT} matches of '${COUNT_REGEX}' in stderr, got ${n}:\n${err}")
  endif()
endif()
