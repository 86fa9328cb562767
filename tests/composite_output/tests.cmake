# Composite element output (issue #7) checked with the real VTK reader (python3-vtk9):
# fdem_write_composite_state writes one frame of a composite and a CST body under a homogeneous
# F; check_composite_vtu.py recomputes the expected values from the same F.
set(FDEM_COMPOSITE_F "1.02,0.01,-0.005,0.97")
set(FDEM_COMPOSITE_VTU ${CMAKE_CURRENT_BINARY_DIR}/composite_output/frame.vtu)
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/composite_output)

add_executable(fdem_write_composite_state ${CMAKE_CURRENT_LIST_DIR}/write_composite_state.cpp)
target_link_libraries(fdem_write_composite_state PRIVATE fdem::fdem)

add_test(NAME composite_output.write
         COMMAND fdem_write_composite_state ${FDEM_COMPOSITE_VTU} ${FDEM_COMPOSITE_F})
set_tests_properties(composite_output.write PROPERTIES
    LABELS "unit;output" FIXTURES_SETUP fdem_composite_output)

add_test(NAME composite_output.vtk_reader_check
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_composite_vtu.py
                 ${FDEM_COMPOSITE_VTU} ${FDEM_COMPOSITE_F})
set_tests_properties(composite_output.vtk_reader_check PROPERTIES
    LABELS "unit;output" FIXTURES_REQUIRED fdem_composite_output)

# the checker must reject a wrong expectation: a different F
add_test(NAME composite_output.vtk_reader_check_detects_mismatch
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_composite_vtu.py
                 ${FDEM_COMPOSITE_VTU} "1.02,0.01,-0.005,0.9701")
set_tests_properties(composite_output.vtk_reader_check_detects_mismatch PROPERTIES
    LABELS "unit;output" FIXTURES_REQUIRED fdem_composite_output
    PASS_REGULAR_EXPRESSION "FAILED: cell 0: stress")
