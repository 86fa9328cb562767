# Command-line contract: exit codes and the messages users see (label: input).
set(cli_dir ${CMAKE_CURRENT_LIST_DIR})
set(cli_out ${CMAKE_CURRENT_BINARY_DIR}/cli_out)

# simulation failure -> exit 1, message names step, time, element and a remedy; failure.vtu written
add_test(NAME cli.inverted_element_exits_1
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DOUT=${cli_out}/crush
                 -DSCENARIO=${cli_dir}/crush.toml -P ${cli_dir}/expect_failure.cmake)
# --version and --help exit 0
add_test(NAME cli.version COMMAND fdem_cli --version)
set_tests_properties(cli.version PROPERTIES PASS_REGULAR_EXPRESSION "^fdem [0-9]+\\.[0-9]+\\.[0-9]+")
add_test(NAME cli.help COMMAND fdem_cli run --help)
set_tests_properties(cli.help PROPERTIES PASS_REGULAR_EXPRESSION "--end-time.*--threads")
# usage errors -> exit 2
add_test(NAME cli.no_subcommand_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2 -DARGS=
                 "-DREGEX=A subcommand is required" -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.unknown_option_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${cli_dir}/crush.toml;--bogus" "-DREGEX=--bogus"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.missing_scenario_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${cli_dir}/no_such_file.toml" "-DREGEX=no_such_file.toml"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.check_prints_summary COMMAND fdem_cli check ${cli_dir}/crush.toml)
set_tests_properties(cli.check_prints_summary PROPERTIES
  PASS_REGULAR_EXPRESSION "stable dt +[0-9.e+-]+ s \\(limited by triangle [0-9]+, material \"soft\"\\)")
set_tests_properties(cli.inverted_element_exits_1 cli.version cli.help cli.no_subcommand_exits_2
  cli.unknown_option_exits_2 cli.missing_scenario_exits_2 cli.check_prints_summary PROPERTIES LABELS input)
