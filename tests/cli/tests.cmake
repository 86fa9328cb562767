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

# ---- checkpoint / restart (two bodies in frictional contact, restart.toml) ------------------
# interrupted by SIGKILL / SIGTERM / SIGINT, restarted from the last checkpoint: the final state
# hash, history.csv and series.pvd are identical to an uninterrupted run
foreach(sig KILL TERM INT)
  add_test(NAME cli.restart_after_sig${sig}_is_bitwise
           COMMAND ${cli_dir}/kill_restart.sh $<TARGET_FILE:fdem_cli> ${cli_dir}/restart.toml
                   ${cli_out}/restart_${sig} ${sig})
  set_tests_properties(cli.restart_after_sig${sig}_is_bitwise PROPERTIES LABELS input
                       PASS_REGULAR_EXPRESSION "OK: bitwise identical")
endforeach()
# a checkpoint of another model, truncated, corrupt, foreign or missing -> exit 2 with a message
add_test(NAME cli.restart_refused_exits_2
         COMMAND ${cli_dir}/restart_refused.sh $<TARGET_FILE:fdem_cli> ${cli_dir}
                 ${cli_out}/restart_refused)
set_tests_properties(cli.restart_refused_exits_2 PROPERTIES LABELS input)

# ---- failure diagnosis: exit 1, message names step, time, quantity and a remedy -------------
add_test(NAME cli.energy_drift_exits_1
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=1
                 "-DARGS=run;${cli_dir}/energy.toml;--out;${cli_out}/energy;--quiet"
                 "-DREGEX=step [0-9]+ \\(t = [0-9.e+-]+ s\\): energy: total energy drifted by [0-9.e+-]+ J/m = [0-9.]+ % of the energy scale [0-9.e+-]+ J/m \\(limit 0.5 %, \\[checks\\] energy_tolerance = 0.005\\); the run is unstable or too coarse: reduce dt \\(now [0-9.e+-]+ s, stable limit [0-9.e+-]+ s\\).*the state at failure is in .*failure.vtu.*last good output frame: .*frame_[0-9]+.vtu"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.penetration_exits_1
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=1
                 "-DARGS=run;${cli_dir}/penetration.toml;--out;${cli_out}/penetration;--quiet"
                 "-DREGEX=step [0-9]+ \\(t = [0-9.e+-]+ s\\): contact: [0-9]+ target node\\(s\\) passed through the contact layer into the body they touched \\(deepest d / layer = [0-9.e+-]+\\); (node [0-9]+|the midpoint of boundary edge [0-9]+-[0-9]+) \\(body 0 .base., at \\([0-9.e+-]+, [0-9.e+-]+\\) m, d / layer = [0-9.e+-]+ when last in contact\\) is inside body 1 .block.; the contact force is lost there; reduce dt \\(now [0-9.e+-]+ s, stable limit [0-9.e+-]+ s\\) or increase the contact penalty"
                 -P ${cli_dir}/expect_exit.cmake)
set_tests_properties(cli.energy_drift_exits_1 cli.penetration_exits_1 PROPERTIES LABELS input)

# ---- determinism: the same input gives the same bits, run to run and for 1 or 2 threads -----
add_test(NAME cli.determinism_threads
         COMMAND ${cli_dir}/determinism.sh $<TARGET_FILE:fdem_cli> ${cli_dir}/determinism.toml
                 ${cli_out}/determinism)
# GOMP_SPINCOUNT: libgomp's default busy-wait (300000 spins per barrier) makes a 2-thread run
# ~50x slower when the 2 cores are shared with other jobs (measured 62 s vs 1.1 s); the spin
# count changes the waiting only, never the results.
set_tests_properties(cli.determinism_threads PROPERTIES LABELS input ENVIRONMENT GOMP_SPINCOUNT=1000
                     PASS_REGULAR_EXPRESSION "OK: 3 runs bitwise identical")

# ---- loads: a pressure on a curve inside the body is refused at load (docs/scenario.md) -------
add_test(NAME cli.load_inside_body_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${cli_dir}/bad_load.toml;--out;${cli_out}/bad_load"
                 "-DREGEX=bad_load.toml:20:9: error: load on \"middle\" of body \"bar\": the edge from \\(0.5, 0[.0-9]*\\) to \\(0.5, [0-9.]+\\) m of physical group \"middle\" is inside \\(shared by two triangles\\) of body \"bar\", not on its boundary"
                 -P ${cli_dir}/expect_exit.cmake)
set_tests_properties(cli.load_inside_body_exits_2 PROPERTIES LABELS input)
add_test(NAME cli.check_lists_loads
         COMMAND fdem_cli check ${PROJECT_SOURCE_DIR}/examples/06_pressurised_ring/scenario.toml)
set_tests_properties(cli.check_lists_loads PROPERTIES LABELS input
  PASS_REGULAR_EXPRESSION "load       ring/outer: pressure 1e\\+07 Pa on 64 edge\\(s\\), 6.28[0-9] m, ramp over 0.005 s")

# ---- fracture: fdem check prints the joint numbers (docs/scenario.md; values by hand for example
# 07: h = 0.02 m / 5, p = 10 E = 5e11 Pa: o_p = 2 h f_t/p = 1.6e-7 m, s_p = 2 h c/p_s = 4.8e-7 m,
# o_r - o_p = G_I/(I_z f_t) = 50/(0.38631 x 1e7) = 1.2943e-5 m, h_max = p G_I/(4 I_z f_t^2) =
# 0.1618 m, l_ch = E G_I/f_t^2 = 0.025 m, E_eff/E = 1/(1 + 2/10) = 0.833)
add_test(NAME cli.check_prints_fracture
         COMMAND fdem_cli check ${PROJECT_SOURCE_DIR}/examples/07_pull_apart/scenario.toml)
set_tests_properties(cli.check_prints_fracture PROPERTIES LABELS input
  PASS_REGULAR_EXPRESSION "fracture   material \"rock\": 5 joints, h 0.004 \\.\\. 0.004 m \\(mean 0.004 m\\), h_max 0.1618 m \\(eq. 9.14\\)\n +at the mean h: o_p 1.6e-07 m, s_p 4.8e-07 m \\(eq. 9.4\\), o_r - o_p 1.294e-05 m \\(\"exact\", eq. 9.12\\)[^\n]*\n +mixed mode \"proportional\" \\(eq. 9.30: each softened traction scaled by its mode's share of the damage, blended in over K_w = 0.2\\)\n +l_ch = E G_I/f_t\\^2 = 0.025 m. E_eff = E/\\(1 \\+ c_m E/p\\) = 4.167e\\+10 Pa = 0.833 E, c_m = 3/2 \\+ p/\\(2 p_s\\) = 2 \\(eq. 9.6[^\n]*\ndt limits  elements [0-9.e+-]+ s, joints [0-9.e+-]+ s \\(eq. 9.16\\), contact none")

# the vector kernels and the thread count (docs/output.md "Console output"); the "." stands for
# the ";" of the line, which would split a CMake regex list
add_test(NAME cli.check_prints_kernels
         COMMAND fdem_cli check ${PROJECT_SOURCE_DIR}/examples/07_pull_apart/scenario.toml)
set_tests_properties(cli.check_prints_kernels PROPERTIES LABELS input ENVIRONMENT OMP_NUM_THREADS=1
  PASS_REGULAR_EXPRESSION "\nkernels    CST (avx512|avx2|portable), node update (avx512|avx2|portable), joints (avx512|avx2|portable|scalar), broad-phase scan (avx512|portable). 1 OpenMP thread\\(s\\)\n")

# the same with p_s = p/2 = 2.5e11 Pa (tests/data/pull_apart_soft_shear.toml): s_p = 2 h c/p_s =
# 9.6e-7 m, c_m = 3/2 + p/(2 p_s) = 2.5, E_eff/E = 1/(1 + 2.5/10) = 0.8 = 4e10 Pa
add_test(NAME cli.check_prints_fracture_soft_shear
         COMMAND fdem_cli check ${PROJECT_SOURCE_DIR}/tests/data/pull_apart_soft_shear.toml)
set_tests_properties(cli.check_prints_fracture_soft_shear PROPERTIES LABELS input
  PASS_REGULAR_EXPRESSION "s_p 9.6e-07 m \\(eq. 9.4\\)[^\n]*shear 2.5e\\+11 Pa\n +mixed mode \"proportional\"[^\n]*\n +l_ch = E G_I/f_t\\^2 = 0.025 m. E_eff = E/\\(1 \\+ c_m E/p\\) = 4e\\+10 Pa = 0.800 E, c_m = 3/2 \\+ p/\\(2 p_s\\) = 2.5 \\(eq. 9.6")

# ---- batch output: progress lines when stderr is no terminal, line-buffered stdout, bodies.csv
add_test(NAME cli.batch_progress_and_bodies_csv
         COMMAND ${cli_dir}/progress.sh $<TARGET_FILE:fdem_cli> ${cli_dir}/restart.toml
                 ${cli_out}/progress ${PROJECT_SOURCE_DIR}/docs/output.md)
set_tests_properties(cli.batch_progress_and_bodies_csv PROPERTIES LABELS input
                     PASS_REGULAR_EXPRESSION "OK: batch progress")

# ---- load-time contact geometry (issue #12 items 4 and 6, docs/theory.md §6.13-6.14) ----------
add_test(NAME cli.initial_overlap_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=check;${cli_dir}/initial_overlap.toml"
                 "-DREGEX=initial_overlap.toml:12:1: error: bodies 0 \"first\" and 1 \"second\" overlap at t = 0: the centroid of boundary element [0-9]+ \\(node [0-9]+\\) of body 0 at \\([0-9.e+-]+, [0-9.e+-]+\\) m lies [0-9.e+-]+ m inside body 1 \\(touching counts up to [0-9.e+-]+ m = 1e-6 x the smallest element altitude\\); the contact penalty would push them apart at once with energy that is not in the balance. Move the meshes apart, or set \\[contact\\] initial_overlap = \"allow\" if the prestress is intended"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.thin_contact_layer_warns
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=0
                 "-DARGS=check;${cli_dir}/thin_base.toml"
                 "-DREGEX=warning: body 0 \"base\" is too thin for its contact layer: in [0-9]+ boundary sub-triangle\\(s\\) an inner node takes its contact distance from the opposite face, e.g. node [0-9]+ of element [0-9]+: [0-9.e+-]+ m from boundary edge [0-9]+-[0-9]+ on the far side instead of [0-9.e+-]+ m from the face element [0-9]+ lies on; the contact normal there tilts towards the far face \\(docs/theory.md §6.13\\). Remedy: make the body thicker \\(at least three elements through its thickness\\) or refine the mesh there"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.thin_contact_layer_warns_at_run
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=0
                 "-DARGS=run;${cli_dir}/thin_base.toml;--out;${cli_out}/thin_base;--quiet"
                 "-DREGEX=warning: body 0 \"base\" is too thin for its contact layer"
                 -P ${cli_dir}/expect_exit.cmake)
# example 04: 2 500 grains from 8 [[body]] entries with pieces = "separate", hundreds of them thin:
# one warning per entry (its worst grain, the others counted), not one per grain
add_test(NAME cli.thin_contact_layer_one_warning_per_entry
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=0
                 "-DARGS=check;${PROJECT_SOURCE_DIR}/examples/04_particles/scenario.toml"
                 "-DREGEX=scenario.toml:31:1: warning: body [0-9]+ \"p0\" is too thin for its contact layer: .* \\([0-9]+ other bodies of this \\[\\[body\\]\\] entry are thin too\\)"
                 "-DCOUNT_REGEX=is too thin for its contact layer" -DCOUNT=8
                 -P ${cli_dir}/expect_exit.cmake)
set_tests_properties(cli.initial_overlap_exits_2 cli.thin_contact_layer_warns
  cli.thin_contact_layer_warns_at_run cli.thin_contact_layer_one_warning_per_entry
  PROPERTIES LABELS input)

# ---- the last step's contact pairs in the run summary (issue #16 item 1, docs/output.md) -----
add_test(NAME cli.run_prints_contact_pairs
         COMMAND ${cli_dir}/contact_pairs.sh $<TARGET_FILE:fdem_cli> ${cli_dir}/restart.toml
                 ${cli_out}/contact_pairs)
set_tests_properties(cli.run_prints_contact_pairs PROPERTIES LABELS input
                     PASS_REGULAR_EXPRESSION "OK: contact pairs line")
# the timing table of the run summary (State::timing): rows, sums, and no bit changed by it
add_test(NAME cli.run_prints_timing
         COMMAND ${cli_dir}/timing.sh $<TARGET_FILE:fdem_cli> ${cli_dir}/restart.toml
                 ${cli_out}/timing 0.025)
set_tests_properties(cli.run_prints_timing PROPERTIES LABELS input
                     PASS_REGULAR_EXPRESSION "OK: timing table")
# the summary says which pages hold the arrays (core/huge_pages.hpp); --no-huge-pages leaves
# them on 4 KiB pages (the same bits: HugePages.SameStepBitsOnEitherPageSize)
add_test(NAME cli.run_prints_pages
         COMMAND $<TARGET_FILE:fdem_cli> run ${cli_dir}/restart.toml --out ${cli_out}/pages
                 --end-time 0.005)
set_tests_properties(cli.run_prints_pages PROPERTIES LABELS input PASS_REGULAR_EXPRESSION
    "\npages      ([0-9.]+ MB of this process on [0-9]+ [KM]iB transparent huge pages|4 KiB \\(this kernel has no transparent huge pages\\))\n")
add_test(NAME cli.run_no_huge_pages
         COMMAND $<TARGET_FILE:fdem_cli> run ${cli_dir}/restart.toml --out ${cli_out}/pages_off
                 --end-time 0.005 --no-huge-pages)
set_tests_properties(cli.run_no_huge_pages PROPERTIES LABELS input PASS_REGULAR_EXPRESSION
    "\npages      4 KiB \\(--no-huge-pages\\)\n")
# fdem decompose (issue #15, docs/parallel.md): bad arguments exit 2 naming the option and the
# value; a run prints one summary line per part count and writes the CSV
add_test(NAME cli.decompose_zero_parts_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=decompose;${cli_dir}/crush.toml;--parts;2,0"
                 "-DREGEX=--parts: Value 0 not in range 1 to 1048576"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.decompose_unknown_partition_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=decompose;${cli_dir}/crush.toml;--parts;2;--partition;metis"
                 "-DREGEX=--partition: metis not in \\{rcb,ids,random\\}"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.decompose_unwritable_csv_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=decompose;${cli_dir}/crush.toml;--parts;2;--partition;ids;--csv;/no_such_dir/x.csv"
                 "-DREGEX=--csv.*cannot write \"/no_such_dir/x.csv\": No such file or directory; expected a writable file path"
                 -P ${cli_dir}/expect_exit.cmake)
# load balancing of distributed runs (spec D10): bad values exit 2 naming the option and value
add_test(NAME cli.run_imbalance_below_one_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${cli_dir}/crush.toml;--imbalance;0.5"
                 "-DREGEX=--imbalance: expected a finite ratio >= 1, got '0.5'"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.run_negative_rebalance_every_exits_2
         COMMAND ${CMAKE_COMMAND} -DFDEM=$<TARGET_FILE:fdem_cli> -DRC=2
                 "-DARGS=run;${cli_dir}/crush.toml;--rebalance-every;-1"
                 "-DREGEX=--rebalance-every: Value -1 not in range 0 to 2147483647"
                 -P ${cli_dir}/expect_exit.cmake)
add_test(NAME cli.decompose_prints_parts
         COMMAND fdem_cli decompose ${cli_dir}/crush.toml --parts 1,3 --partition ids)
set_tests_properties(cli.decompose_prints_parts PROPERTIES PASS_REGULAR_EXPRESSION
  "parts     1 \\(ids.*\nparts     3 \\(ids, [0-9.]+ s\\): nodes per part [0-9]+ mean")
set_tests_properties(cli.decompose_zero_parts_exits_2 cli.decompose_unknown_partition_exits_2
  cli.decompose_unwritable_csv_exits_2 cli.decompose_prints_parts cli.run_imbalance_below_one_exits_2
  cli.run_negative_rebalance_every_exits_2 PROPERTIES LABELS input)

# the same with mixed_mode = "proportional" (tests/data/pull_apart_proportional.toml; theory §9.3b)
add_test(NAME cli.check_prints_mixed_mode
         COMMAND fdem_cli check ${PROJECT_SOURCE_DIR}/tests/data/pull_apart_proportional.toml)
set_tests_properties(cli.check_prints_mixed_mode PROPERTIES LABELS input
  PASS_REGULAR_EXPRESSION "shear 5e\\+11 Pa\n +mixed mode \"proportional\" \\(eq. 9.30: each softened traction scaled by its mode's share of the damage, blended in over K_w = 0.2\\)\n +l_ch")
