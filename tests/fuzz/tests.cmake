# Fuzz targets (libFuzzer) and their corpus replay (label input).
#   Replay (any compiler): fdem_fuzz_replay_<target> runs every file of corpus/<target>/ through
#     the reader; a crash fails the test.
#   Fuzzing (clang only): configure with -DFDEM_FUZZ=ON (scripts/fuzz does it) to build
#     fdem_fuzz_<target> with -fsanitize=fuzzer,address,undefined.
set(fuzz_dir ${CMAKE_CURRENT_LIST_DIR})
option(FDEM_FUZZ "Build the libFuzzer targets (clang only)" OFF)
foreach(target scenario mesh)
  add_executable(fdem_fuzz_replay_${target} ${fuzz_dir}/${target}_fuzz.cpp ${fuzz_dir}/replay_main.cpp)
  target_link_libraries(fdem_fuzz_replay_${target} PRIVATE fdem::fdem)
  target_compile_definitions(fdem_fuzz_replay_${target} PRIVATE
    FDEM_TEST_DATA_DIR="${FDEM_TEST_DATA_DIR}")
  add_test(NAME fuzz.replay_${target}
           COMMAND fdem_fuzz_replay_${target} ${fuzz_dir}/corpus/${target} ${fuzz_dir}/crashes/${target})
  set_tests_properties(fuzz.replay_${target} PROPERTIES LABELS input
                       PASS_REGULAR_EXPRESSION "replayed [1-9][0-9]* inputs")
  if(FDEM_FUZZ)
    add_executable(fdem_fuzz_${target} ${fuzz_dir}/${target}_fuzz.cpp)
    target_link_libraries(fdem_fuzz_${target} PRIVATE fdem::fdem)
    target_compile_definitions(fdem_fuzz_${target} PRIVATE FDEM_TEST_DATA_DIR="${FDEM_TEST_DATA_DIR}")
    target_compile_options(fdem_fuzz_${target} PRIVATE -fsanitize=fuzzer)
    target_link_options(fdem_fuzz_${target} PRIVATE -fsanitize=fuzzer)
  endif()
endforeach()
if(FDEM_FUZZ)
  # coverage instrumentation of the library code under test
  target_compile_options(fdem PRIVATE -fsanitize=fuzzer-no-link)
endif()
