# Loading scales linearly in the [[body]] entries (issue #16 item 4): 10^3 against 10^4 entries,
# time ratio and peak-RSS growth of `fdem check` (no absolute wall-clock threshold). Label full:
# about 5 s of a shared machine.
add_test(NAME loading.linear_in_body_entries
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/check_load_scaling.py
                 $<TARGET_FILE:fdem_cli> ${CMAKE_CURRENT_LIST_DIR}/make_pack_scenario.py
                 ${CMAKE_CURRENT_BINARY_DIR}/loading_out)
set_tests_properties(loading.linear_in_body_entries PROPERTIES LABELS full TIMEOUT 600
                     PASS_REGULAR_EXPRESSION "OK: loading is linear")
