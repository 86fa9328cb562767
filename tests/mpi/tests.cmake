# Distributed runs (issue #15): label mpi, built with -DFDEM_MPI=ON only (scripts/test does).
# Each test runs under mpirun with 1-4 processes, oversubscribed on a 2-core machine, over shared
# memory only (spec parallel-and-python.md §3); as root (CI) Open MPI needs the two
# OMPI_ALLOW_RUN_AS_ROOT variables.
set(mpi_dir ${CMAKE_CURRENT_LIST_DIR})

# Without MPI: a serial fdem started by an MPI launcher refuses (exit 2) instead of running the
# whole scenario once per process (the launcher's variable, no mpirun needed; label input)
add_test(NAME cli.refuses_mpi_launch_exits_2
         COMMAND ${CMAKE_COMMAND} -E env OMPI_COMM_WORLD_SIZE=3
                 ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${PROJECT_SOURCE_DIR}/examples/03_contact_slide/scenario.toml;--quiet"
                 "-DREGEX=error: this fdem was started as one of 3 MPI processes, but it runs a scenario in one process only"
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_exit.cmake)
set_tests_properties(cli.refuses_mpi_launch_exits_2 PROPERTIES LABELS input)

if(NOT FDEM_MPI)
  return()
endif()

file(GLOB mpi_test_srcs CONFIGURE_DEPENDS ${mpi_dir}/*_test.cpp)
add_executable(fdem_mpi_tests ${mpi_dir}/main.cpp ${mpi_test_srcs})
target_link_libraries(fdem_mpi_tests PRIVATE fdem_mpi GTest::gtest)
target_include_directories(fdem_mpi_tests PRIVATE ${PROJECT_SOURCE_DIR}/src/fdem)

set(FDEM_MPIRUN ${MPIEXEC_EXECUTABLE} --oversubscribe --bind-to none --mca btl self,vader)
set(FDEM_MPI_ENV OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
                 OMPI_MCA_rmaps_base_oversubscribe=1)
foreach(np 1 2 3 4)
  add_test(NAME mpi.unit_np${np}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${FDEM_MPIRUN} -np ${np} $<TARGET_FILE:fdem_mpi_tests>)
  set_tests_properties(mpi.unit_np${np} PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2)
endforeach()

# the same refusal under a real mpirun: every process exits 2 with the message
add_test(NAME mpi.cli_refuses_np2_exits_2
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${CMAKE_COMMAND} "-DFDEM=${MPIEXEC_EXECUTABLE}" -DRC=2
                 "-DARGS=--oversubscribe;--bind-to;none;--mca;btl;self,vader;-np;2;$<TARGET_FILE:fdem_cli>;run;${PROJECT_SOURCE_DIR}/examples/03_contact_slide/scenario.toml;--quiet"
                 "-DREGEX=started as one of 2 MPI processes"
                 "-DCOUNT_REGEX=started as one of 2 MPI" -DCOUNT=2
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_exit.cmake)
set_tests_properties(mpi.cli_refuses_np2_exits_2 PROPERTIES LABELS mpi TIMEOUT 120)
