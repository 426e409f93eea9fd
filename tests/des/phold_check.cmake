# Runs the PHOLD benchmark at a short end time and checks that it commits
# exactly the events and per-LP checksum the peer programs commit (their
# published validation figures), i.e. that the kernel runs every event once.
# Arguments: -DPHOLD=<program> -DARGS=<;-list> -DEVENTS=<n> -DCHECK=<hex>
execute_process(COMMAND "${PHOLD}" ${ARGS} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "phold failed (${rc}): ${err}")
endif()
string(FIND "${out}" "events=${EVENTS} " at_events)
string(FIND "${err}" "check=${CHECK}" at_check)
if(at_events LESS 0 OR at_check LESS 0)
  message(FATAL_ERROR "phold ${ARGS}: expected events=${EVENTS} check=${CHECK}, got:\n${out}${err}")
endif()
