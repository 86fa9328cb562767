# Distributed runs (issue #15): label mpi, built with -DFDEM_MPI=ON only (scripts/test does).
# Each test runs under mpirun with 1-4 processes, oversubscribed on a 2-core machine, over shared
# memory only (spec parallel-and-python.md §3); as root (CI) Open MPI needs the two
# OMPI_ALLOW_RUN_AS_ROOT variables.
set(mpi_dir ${CMAKE_CURRENT_LIST_DIR})

# Without MPI: a serial fdem started by an MPI launcher refuses (exit 2) instead of running the
# whole scenario once per process (the launcher's variable, no mpirun needed; label input). An
# MPI build runs it distributed instead (the tests below).
if(NOT FDEM_MPI)
  add_test(NAME cli.refuses_mpi_launch_exits_2
           COMMAND ${CMAKE_COMMAND} -E env OMPI_COMM_WORLD_SIZE=3
                   ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                   "-DARGS=run;${PROJECT_SOURCE_DIR}/examples/03_contact_slide/scenario.toml;--quiet"
                   "-DREGEX=error: this fdem was started as one of 3 MPI processes, but it was built without MPI"
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_exit.cmake)
  set_tests_properties(cli.refuses_mpi_launch_exits_2 PROPERTIES LABELS input)
  # fdem decompose's default partition is Zoltan's RCB, which this build does not have
  add_test(NAME cli.decompose_rcb_without_mpi_exits_2
           COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                   "-DARGS=decompose;${PROJECT_SOURCE_DIR}/examples/03_contact_slide/scenario.toml;--parts;2"
                   "-DREGEX=--partition rcb needs Zoltan, which this fdem was built without"
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_exit.cmake)
  set_tests_properties(cli.decompose_rcb_without_mpi_exits_2 PROPERTIES LABELS input)
  return()
endif()

file(GLOB mpi_test_srcs CONFIGURE_DEPENDS ${mpi_dir}/*_test.cpp)
add_executable(fdem_mpi_tests ${mpi_dir}/main.cpp ${mpi_test_srcs})
target_link_libraries(fdem_mpi_tests PRIVATE fdem_mpi GTest::gtest)
target_include_directories(fdem_mpi_tests PRIVATE ${PROJECT_SOURCE_DIR}/src/fdem ${PROJECT_SOURCE_DIR}/tests)

set(FDEM_MPIRUN ${MPIEXEC_EXECUTABLE} --oversubscribe --bind-to none --mca btl self,vader)
set(FDEM_MPI_ENV OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
                 OMPI_MCA_rmaps_base_oversubscribe=1)
foreach(np 1 2 3 4)
  add_test(NAME mpi.unit_np${np}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${FDEM_MPIRUN} -np ${np} $<TARGET_FILE:fdem_mpi_tests>)
  set_tests_properties(mpi.unit_np${np} PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2)
endforeach()

# T1: `mpirun -np P fdem run` is bitwise the one-process run (state hash, history.csv,
# bodies.csv, last frame) for P = 1..4, ~400 steps of: a cantilever under gravity (one body
# cut between processes), frictional contact (03), 2 500 particles (04 as the raster below:
# ~5 000 steps, so that contacts across the cuts occur; without the contactor ghosts its frames differ), composite
# elements (05),
# follower pressure with mass damping (06), jointed disc between platens (08), and a ring that
# fractures into 62 fragments (11: 170 joints broken by 1e-4 s)
set(mpi_out ${CMAKE_CURRENT_BINARY_DIR}/mpi_out)
set(ex ${PROJECT_SOURCE_DIR}/examples)
# Example 04's 2 500 particles as a .msh (raster_scenario.sh: example 12's make_raster.py at
# N = 50 in particles.geo's order, example 12's scenario template), written once for every
# particle test below (fixture mpi_raster50): Gmsh meshing particles.geo took ~4 s in each of
# the ~60 processes those tests start, two thirds of this label's time
set(raster50 ${mpi_out}/raster50)
add_test(NAME mpi.setup.raster50
         COMMAND ${mpi_dir}/raster_scenario.sh ${PROJECT_SOURCE_DIR} ${raster50} 50)
set_tests_properties(mpi.setup.raster50 PROPERTIES LABELS mpi FIXTURES_SETUP mpi_raster50
                     PASS_REGULAR_EXPRESSION "OK: ")
# mpi.same_as_serial.<name>: same_as_serial.sh runs SCENARIO with one process, then under
# mpirun with each of NPS (a list in one string), writing to ${mpi_out}/<out>; the arguments after
# NPS go to fdem run, those after ENV to the environment of the test
function(mpi_same_as_serial name scenario out nps)
  cmake_parse_arguments(PARSE_ARGV 4 arg "" "" "ENV")
  add_test(NAME mpi.same_as_serial.${name}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV} ${arg_ENV}
                   ${mpi_dir}/same_as_serial.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                   ${scenario} ${mpi_out}/${out} "${nps}" ${arg_UNPARSED_ARGUMENTS})
  set_tests_properties(mpi.same_as_serial.${name} PROPERTIES LABELS mpi TIMEOUT 300 PROCESSORS 2
                       PASS_REGULAR_EXPRESSION "OK: bitwise the serial run")
endfunction()
# the scenario each case below runs, by example folder: the raster for 04
foreach(name 01_cantilever 03_contact_slide 05_composite 06_pressurised_ring 08_brazilian_disc
        11_impact_fragmentation)
  set(scenario_${name} ${ex}/${name}/scenario.toml)
endforeach()
set(scenario_04_particles ${raster50}/scenario.toml)
foreach(case "01_cantilever:0.008" "03_contact_slide:0.002" "04_particles:2e-3"
        "05_composite:0.002" "06_pressurised_ring:0.03" "08_brazilian_disc:4e-6"
        "11_impact_fragmentation:1e-4")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 end)
  mpi_same_as_serial(${name} ${scenario_${name}} ${name} "1 2 3 4" --end-time ${end})
endforeach()
# the fracturing disc with the spec's joint law, mixed_mode = "independent" (theory §9.3a; the
# examples above run the default "proportional" rule and its per-mode history), to 5e-5 s
mpi_same_as_serial(impact_independent ${PROJECT_SOURCE_DIR}/tests/data/impact_independent.toml
                   impact_independent "2 3" --end-time 5e-5)
# the joints run by their owners (JointSubset, docs/parallel.md "Joints"): a ring of 5 joint
# chunks fracturing (20 joints broken by 3e-5 s), by RCB on 2 and 3 processes and by a random
# owner per node group on 4 (every chunk then shared: ranges of joints run by several processes)
foreach(part "rcb:2 3" "random:4")
  string(REPLACE ":" ";" part "${part}")
  list(GET part 0 rule)
  list(GET part 1 nps)
  mpi_same_as_serial(joint_chunks_${rule} ${mpi_dir}/impact_fine.toml joint_chunks_${rule}
                     "${nps}" --end-time 3e-5 --partition ${rule})
endforeach()
# Ghosts of a jointed model (docs/parallel.md "Joints"): process 0 holds only a far block and no
# current position of the fracturing disc; cracks.csv, which it writes, needs the all-gather of a
# step with breaks (without it this test fails); 12 joints broken by 1.4e-5 s
mpi_same_as_serial(ghosts_far_body ${mpi_dir}/ghosts_far_body.toml ghosts_far_body "2"
                   --end-time 1.4e-5 --partition ids)
# Ghosts (spec D6): a kick, a follower pressure and a support reaction, whose nodes each
# process reads beyond its own
mpi_same_as_serial(kick_load_support ${mpi_dir}/kick_load.toml kick_load "2 3 4")
# A model of ~165 000 triangles, whose element schedule has units of 2 chunks (docs/performance.md
# "Stop 50"): the processes' element subsets keep the units, the run stays the serial bits
mpi_same_as_serial(units_of_chunks ${mpi_dir}/units_block.toml units_of_chunks "2 3")
# T3: the result does not depend on the partition: a random owner per node group (4 processes)
# and contiguous node ids (3) instead of Zoltan's RCB
foreach(part "random:4" "ids:3")
  string(REPLACE ":" ";" part "${part}")
  list(GET part 0 how)
  list(GET part 1 np)
  mpi_same_as_serial(partition_${how} ${scenario_04_particles} partition_${how} "${np}"
                     --end-time 1e-3 --partition ${how})
endforeach()
# D10 / T3 with load balancing: a new partition at every broad-phase search (Zoltan RCB of the
# groups' current centres weighted by their estimated work, a new random draw, or weighted
# contiguous ids), so node groups, candidate pairs and the element halo change owners hundreds
# of times; and a ring fracturing into fragments (11) whose node groups move between processes
# as it breaks. Bitwise the serial run, and at least one new partition made.
foreach(case "04_rcb:04_particles:3:rcb:1e-3" "04_random:04_particles:4:random:1e-3"
        "04_ids:04_particles:2:ids:1e-3" "11_rcb:11_impact_fragmentation:3:rcb:1e-4")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 example)
  list(GET case 2 np)
  list(GET case 3 how)
  list(GET case 4 end)
  add_test(NAME mpi.same_as_serial.rebalance_${name}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${mpi_dir}/rebalance.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                   ${scenario_${example}} ${mpi_out}/rebalance_${name} "${np}" ${how}
                   --end-time ${end})
  set_tests_properties(mpi.same_as_serial.rebalance_${name} PROPERTIES LABELS mpi TIMEOUT 300
                       PROCESSORS 2 PASS_REGULAR_EXPRESSION
                       "OK: bitwise the serial run through every rebalance")
endforeach()
# D12 with the local broad phase: each process holds its own targets' candidate pairs, and the
# checkpoint of a distributed run is still byte for byte the serial one (the lists gathered)
foreach(case "04_particles:1e-3:4e-4:2 3 4" "08_brazilian_disc:4e-6:2e-6:3")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 end)
  list(GET case 2 every)
  list(GET case 3 nps)
  add_test(NAME mpi.same_checkpoint.${name}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${mpi_dir}/same_checkpoint.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                   ${scenario_${name}} ${mpi_out}/checkpoint_${name} "${nps}" ${end}
                   ${every})
  set_tests_properties(mpi.same_checkpoint.${name} PROPERTIES LABELS mpi TIMEOUT 300
                       PROCESSORS 2 PASS_REGULAR_EXPRESSION "OK: the serial checkpoint")
endforeach()
# The contact apply on several threads (contact.cpp step 3b, from kMinParallelApply pairs in
# contact): the saturated pack with 2 OpenMP threads per process, 1 and 2 processes, against one
# process with one thread
add_test(NAME mpi.same_as_serial.saturated_pack_threads
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/saturated_pack.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_out}/saturated_pack "2 3")
set_tests_properties(mpi.same_as_serial.saturated_pack_threads PROPERTIES LABELS mpi TIMEOUT 300
                     PROCESSORS 2 PASS_REGULAR_EXPRESSION "OK: bitwise the serial run")
# fewer node groups than processes (Zoltan RCB refuses a process without points): no hang, the
# serial bits (few_groups.sh)
add_test(NAME mpi.same_as_serial.few_node_groups
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/few_groups.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_out}/few_groups)
set_tests_properties(mpi.same_as_serial.few_node_groups PROPERTIES LABELS mpi TIMEOUT 120
                     PROCESSORS 2 PASS_REGULAR_EXPRESSION "OK: fewer node groups")
# a distributed run with history.csv as its only output gathers the joints' state alone at
# its output steps and the whole State at the last: the serial bits (history_only.sh)
add_test(NAME mpi.same_as_serial.history_only
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/history_only.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_out}/history_only)
set_tests_properties(mpi.same_as_serial.history_only PROPERTIES LABELS mpi TIMEOUT 120
                     PROCESSORS 2 PASS_REGULAR_EXPRESSION "OK: history-only output")
# scripts/scaling (docs/parallel.md "Measuring scaling"): the two scenes at toy sizes, one round;
# the summary lines and scaling.csv's rows (3 runs per scene and round)
add_test(NAME mpi.scaling_script
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${PROJECT_SOURCE_DIR}/scripts/scaling --block-mesh 0.05 --pack-blocks 16
                 --rounds 1 --steps 20 --out ${mpi_out}/scaling --fdem $<TARGET_FILE:fdem_cli>
                 --mpiexec ${MPIEXEC_EXECUTABLE})
set_tests_properties(mpi.scaling_script PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2
    PASS_REGULAR_EXPRESSION "block: 242 / 484 triangles, 20 steps at dt [^:]+: strong speed-up median [0-9.]+x \\([0-9.-]+\\), weak efficiency median [0-9.]+ \\([0-9.-]+\\) over 1 round\\(s\\)\npack: 32 / 64 triangles, 20 steps")
# --split: the P*N scene on 1 process too, and the weak efficiency as the product of the size
# factor and the parallel efficiency at P*N (check_scaling_split.py recomputes both from
# scaling.csv and checks the printed figures and the product)
add_test(NAME mpi.scaling_script.split
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/scaling_split.sh ${PROJECT_SOURCE_DIR}/scripts/scaling
                 $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE} ${mpi_out}/scaling_split)
set_tests_properties(mpi.scaling_script.split PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2
                     PASS_REGULAR_EXPRESSION "OK: scaling split")
# D13: [output] merge = true: process 0 writes the serial .vtu frames instead of .pvtu pieces
mpi_same_as_serial(merged_frames ${mpi_dir}/merged.toml merged "3")
# Example 12 (issue #15 "Done when"): the example's own run script (make_raster.py, the generated
# scenario, mpirun, the picture) at N = 20 (400 particles) on 4 processes to 4e-4 s (~880 steps;
# grains touch from ~2e-4 s on) is bitwise the serial run of the scenario it generated: state hash,
# history.csv, bodies.csv, the last .pvtu merged by check_pvtu.py (~5 s on an idle machine)
add_test(NAME mpi.example.12_particles_mpi
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/raster_example.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_out}/12_particles_mpi 20 4 4e-4)
set_tests_properties(mpi.example.12_particles_mpi PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2
                     PASS_REGULAR_EXPRESSION "OK: the example is bitwise the serial run")
# ... and at its default size, 316 x 316 = 99 856 particles on 4 processes, for 2e-6 s (6 steps,
# 3 frames of ~220 MB): each process loads the whole scenario (measured: 69 s for the test on an
# idle 2-core machine, 450 MB per process), so label full: `ctest --test-dir build/release -L full
# -R 12_`
add_test(NAME example.12_particles_mpi_full
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/raster_example.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_out}/12_particles_mpi_full 0 4 2e-6 1)
set_tests_properties(example.12_particles_mpi_full PROPERTIES LABELS full TIMEOUT 900
                     PROCESSORS 2 PASS_REGULAR_EXPRESSION
                     "OK: the example ran and wrote its .pvtu series")
# T2: two OpenMP threads inside each of two processes
mpi_same_as_serial(two_threads_per_process ${ex}/03_contact_slide/scenario.toml threads "2"
                   --end-time 0.002 ENV OMP_NUM_THREADS=2)
# T7 / D9: failures are the one-process run's: exit code, message (printed once) and
# failure.vtu; an input error exits 2 on every process
foreach(case "penetration:2:1" "crush:3:1" "bad_load:2:2")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 np)
  list(GET case 2 rc)
  add_test(NAME mpi.same_failure.${name}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${mpi_dir}/same_failure.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                   ${PROJECT_SOURCE_DIR}/tests/cli/${name}.toml ${mpi_out}/fail_${name} ${np} ${rc})
  set_tests_properties(mpi.same_failure.${name} PROPERTIES LABELS mpi TIMEOUT 120
                       PASS_REGULAR_EXPRESSION "OK: the same failure")
endforeach()
# ... and a mesh error, which only process 0 meets (it alone reads the meshes and broadcasts
# them, parallel/mesh_broadcast.hpp): exit 2 with the serial message on all three processes
add_test(NAME mpi.same_failure.bad_mesh
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/same_failure.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_dir}/bad_mesh.toml ${mpi_out}/fail_bad_mesh 3 2)
set_tests_properties(mpi.same_failure.bad_mesh PROPERTIES LABELS mpi TIMEOUT 120
                     PASS_REGULAR_EXPRESSION "OK: the same failure")
# T4: a checkpoint written by 2 processes restarts on 3 and on 1 with the uninterrupted hash
add_test(NAME mpi.restart_on_another_process_count
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/restart_other_count.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${ex}/03_contact_slide/scenario.toml ${mpi_out}/restart 0.002 0.004)
set_tests_properties(mpi.restart_on_another_process_count PROPERTIES LABELS mpi TIMEOUT 300
                     PASS_REGULAR_EXPRESSION "OK: restart on another process count is bitwise")
# a fracturing model (joints run by their owners, ghosts): 6 joints broken before the
# checkpoint at 2.7e-5 s, 14 more after it; the restarts on 3 and 1 processes end bitwise the
# uninterrupted run
add_test(NAME mpi.restart_on_another_process_count_joints
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/restart_other_count.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${mpi_dir}/impact_fine.toml ${mpi_out}/restart_joints 2.7e-5 3e-5)
set_tests_properties(mpi.restart_on_another_process_count_joints PROPERTIES LABELS mpi
                     TIMEOUT 300 PROCESSORS 2 PASS_REGULAR_EXPRESSION
                     "OK: restart on another process count is bitwise")
# the same with a new partition at every broad-phase search before and after the restart (D10:
# the restarted run starts from the reference partition and rebalances at its first search)
add_test(NAME mpi.restart_on_another_process_count_rebalancing
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/restart_other_count.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${scenario_04_particles} ${mpi_out}/restart_rebalancing 5e-4 1e-3
                 --rebalance-every 1 --imbalance 1)
set_tests_properties(mpi.restart_on_another_process_count_rebalancing PROPERTIES LABELS mpi
                     TIMEOUT 300 PASS_REGULAR_EXPRESSION
                     "OK: restart on another process count is bitwise")
# D9 for signals: SIGTERM to one process of two stops both after the same step with one
# checkpoint; its restart is bitwise the uninterrupted run
add_test(NAME mpi.signal_to_one_process_stops_all
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${mpi_dir}/signal_one_process.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                 ${ex}/03_contact_slide/scenario.toml ${mpi_out}/signal 0.4)
set_tests_properties(mpi.signal_to_one_process_stops_all PROPERTIES LABELS mpi TIMEOUT 120
                     PASS_REGULAR_EXPRESSION "OK: a signal to one process stops all")
# T8: `fdem decompose --parts P` (one process) counts what P processes own, run and exchange per
# step: its rows equal the partition.csv of the run, for Zoltan's RCB (numbered alike on one and
# on P processes), contiguous ids and random owners, with contact records (04 to 0.3 ms), support
# slots (kick_load) and without ghost lists (08: joints, x and v all-gathered)
foreach(case "04_rcb:${scenario_04_particles}:2 3 4:rcb:3e-4"
        "04_random:${scenario_04_particles}:4:random:3e-4"
        "04_ids:${scenario_04_particles}:3:ids:3e-4"
        "kick_load:${mpi_dir}/kick_load.toml:3:rcb:2e-4"
        "08_joints:${ex}/08_brazilian_disc/scenario.toml:2:rcb:2e-6")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 scenario)
  list(GET case 2 nps)
  list(GET case 3 how)
  list(GET case 4 end)
  add_test(NAME mpi.decompose_matches_run.${name}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${mpi_dir}/decompose_matches_run.sh $<TARGET_FILE:fdem_cli>
                   ${MPIEXEC_EXECUTABLE} ${scenario} ${mpi_out}/decompose_${name} "${nps}" ${how}
                   ${end})
  set_tests_properties(mpi.decompose_matches_run.${name} PROPERTIES LABELS mpi TIMEOUT 300
                       PROCESSORS 2 PASS_REGULAR_EXPRESSION
                       "OK: fdem decompose counts what the processes exchanged")
endforeach()
# D9 for output: an error only process 0 meets (history.csv on a full device at the start, a
# folder in the place of the checkpoint mid-run) stops every process with the serial exit code
# and message instead of a hang
foreach(case "history:2" "checkpoint:3")
  string(REPLACE ":" ";" case "${case}")
  list(GET case 0 kind)
  list(GET case 1 np)
  add_test(NAME mpi.same_failure.output_${kind}
           COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                   ${mpi_dir}/output_failure.sh $<TARGET_FILE:fdem_cli> ${MPIEXEC_EXECUTABLE}
                   ${ex}/03_contact_slide/scenario.toml ${mpi_out}/output_${kind} ${np} ${kind}
                   0.002)
  set_tests_properties(mpi.same_failure.output_${kind} PROPERTIES LABELS mpi TIMEOUT 200
                       PASS_REGULAR_EXPRESSION "OK: an output error of process 0 stops every")
endforeach()

# the timing table of a distributed run: min / mean / max over the processes, with the
# communication row (tests/cli/timing.sh)
add_test(NAME mpi.run_prints_timing
         COMMAND ${CMAKE_COMMAND} -E env ${FDEM_MPI_ENV}
                 ${PROJECT_SOURCE_DIR}/tests/cli/timing.sh $<TARGET_FILE:fdem_cli>
                 ${PROJECT_SOURCE_DIR}/tests/cli/restart.toml ${mpi_out}/timing 0.025
                 ${MPIEXEC_EXECUTABLE} 2)
set_tests_properties(mpi.run_prints_timing PROPERTIES LABELS mpi TIMEOUT 120 PROCESSORS 2
                     PASS_REGULAR_EXPRESSION "OK: timing table")

# every particle test reads the raster written by mpi.setup.raster50
set_tests_properties(mpi.same_as_serial.04_particles mpi.same_as_serial.partition_random
                     mpi.same_as_serial.partition_ids mpi.same_as_serial.rebalance_04_rcb
                     mpi.same_as_serial.rebalance_04_random mpi.same_as_serial.rebalance_04_ids
                     mpi.same_checkpoint.04_particles
                     mpi.restart_on_another_process_count_rebalancing
                     mpi.decompose_matches_run.04_rcb mpi.decompose_matches_run.04_random
                     mpi.decompose_matches_run.04_ids
                     PROPERTIES FIXTURES_REQUIRED mpi_raster50)
