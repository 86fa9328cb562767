# Output checks with the real VTK reader (python3-vtk9) and the history plot (docs/output.md).
# Included from tests/CMakeLists.txt, so CMAKE_CURRENT_LIST_DIR is tests/output.
#
# The same --body/--frame lists go to the writer (C++, fdem::write_vtu) and to the checker
# (python, analytic values from those lists); one source of truth, two independent computations.

set(FDEM_PYTHON /usr/bin/python3)  # the python3 on PATH may lack vtk/matplotlib (project rules)
set(FDEM_OUTPUT_TEST_DIR ${CMAKE_CURRENT_BINARY_DIR}/output_known)
set(FDEM_OUTPUT_TEST_ARGS
    # body: x0,y0,w,h [m], nx,ny, E [Pa], nu, plane mode
    --body 0,0,2,1,4,2,1e9,0.25,strain
    --body 3,0.5,1,1,2,3,5e8,0.3,stress
    # frame: t [s], F (row-major), translation c [m]
    --frame 0,1,0,0,1,0,0                          # reference: zero displacement, zero stress
    --frame 0.5,1.01,0,0,0.997,0.1,-0.2            # biaxial stretch + translation
    --frame 1.25,0.87,-0.49,0.51,0.86,-1,2         # rotation ~30 deg with stretch and shear
    --frame 2.0000000000000004,1,0.02,0,1,0,0      # simple shear; time needs all 17 digits
)

add_executable(fdem_write_known_state ${CMAKE_CURRENT_LIST_DIR}/write_known_state.cpp)
target_link_libraries(fdem_write_known_state PRIVATE fdem::fdem)

add_test(NAME output.write_known_state
         COMMAND fdem_write_known_state ${FDEM_OUTPUT_TEST_DIR} ${FDEM_OUTPUT_TEST_ARGS})
set_tests_properties(output.write_known_state PROPERTIES
    LABELS "unit;output" FIXTURES_SETUP fdem_output_known)

# fails with "cannot import VTK/numpy ... install python3-vtk9" (exit 2) when the reader is missing
add_test(NAME output.vtk_reader_check
         COMMAND ${FDEM_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_vtu.py
                 ${FDEM_OUTPUT_TEST_DIR}/series.pvd ${FDEM_OUTPUT_TEST_ARGS})
set_tests_properties(output.vtk_reader_check PROPERTIES
    LABELS "unit;output" FIXTURES_REQUIRED fdem_output_known)

# the checker must reject a wrong expectation (guards against a check that cannot fail):
# the same series checked against a different stretch in frame 1
add_test(NAME output.vtk_reader_check_detects_mismatch
         COMMAND ${FDEM_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_vtu.py
                 ${FDEM_OUTPUT_TEST_DIR}/series.pvd
                 --body 0,0,2,1,4,2,1e9,0.25,strain --body 3,0.5,1,1,2,3,5e8,0.3,stress
                 --frame 0,1,0,0,1,0,0 --frame 0.5,1.0100001,0,0,0.997,0.1,-0.2
                 --frame 1.25,0.87,-0.49,0.51,0.86,-1,2 --frame 2.0000000000000004,1,0.02,0,1,0,0)
set_tests_properties(output.vtk_reader_check_detects_mismatch PROPERTIES
    LABELS "unit;output" FIXTURES_REQUIRED fdem_output_known
    PASS_REGULAR_EXPRESSION "FAILED: frame_000001.vtu: points")

# history plot: energies.png must be written and be a PNG (--check), and the reported balance
# error must be the one write_known_state put in: total = 10 + 0.001 k^2 J/m, k = 0..3 -> 9e-3
add_test(NAME output.plot_history
         COMMAND ${FDEM_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot_history.py
                 ${FDEM_OUTPUT_TEST_DIR}/history.csv --check)
set_tests_properties(output.plot_history PROPERTIES
    LABELS "unit;output" FIXTURES_REQUIRED fdem_output_known
    PASS_REGULAR_EXPRESSION "4 rows, max [|]energy_error[|] 9[.]000e-03 J/m")
