# Every example runs as a CTest `example` smoke test at a reduced end time: it must load, run
# without a simulation failure and write its PVD series. Add a line per new example.
#   name                      end time [s] for the smoke test
set(FDEM_EXAMPLES
  "01_cantilever            0.05"
  "02_elastic_bar           2.0e-4"
  "03_contact_slide         0.05"
  "04_particles             2.0e-5"
  "05_composite             2.0e-3"
)
foreach(entry ${FDEM_EXAMPLES})
  string(REGEX REPLACE " +" ";" parts "${entry}")
  list(GET parts 0 name)
  list(GET parts 1 end_time)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/example_out/${name})
  add_test(NAME example.${name}
           COMMAND ${CMAKE_COMMAND}
             -DFDEM=$<TARGET_FILE:fdem_cli>
             -DSCENARIO=${PROJECT_SOURCE_DIR}/examples/${name}/scenario.toml
             -DEND_TIME=${end_time} -DOUT=${out}
             -P ${CMAKE_CURRENT_LIST_DIR}/run_example.cmake)
  set_tests_properties(example.${name} PROPERTIES LABELS example TIMEOUT 600)
endforeach()
