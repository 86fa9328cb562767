# Every example runs as a CTest `example` smoke test at a reduced end time: it must load, run
# without a simulation failure and write its PVD series. Add a line per new example.
#   name                      end time [s] for the smoke test
set(FDEM_EXAMPLES
  "01_cantilever            0.05"
  "02_elastic_bar           2.0e-4"
  "03_contact_slide         0.05"
  "04_particles             2.0e-5"
  "05_composite             2.0e-3"
  "06_pressurised_ring      0.03"
  "07_pull_apart            2.0e-4"
  "08_brazilian_disc        2.0e-4"
  "09_ucs                   2.0e-4"
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

# Example 04 at the paper's size (10^4 particles, scenario_10k.toml): Gmsh needs 1-2 min to mesh
# it, so it is not in the default suite; run it with `ctest --test-dir build/release -L full`.
add_test(NAME example.04_particles_10k
         COMMAND ${CMAKE_COMMAND}
           -DFDEM=$<TARGET_FILE:fdem_cli>
           -DSCENARIO=${PROJECT_SOURCE_DIR}/examples/04_particles/scenario_10k.toml
           -DEND_TIME=2.0e-6 -DOUT=${CMAKE_CURRENT_BINARY_DIR}/example_out/04_particles_10k
           -P ${CMAKE_CURRENT_LIST_DIR}/run_example.cmake)
set_tests_properties(example.04_particles_10k PROPERTIES LABELS full TIMEOUT 1200)
