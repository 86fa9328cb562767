# The installed package (label: package): `cmake --install` of this build tree into a temporary
# prefix, then examples/api built against it by a fresh CMake with find_package(fdem CONFIG), run,
# and its state hash compared with the installed `fdem` CLI's for the same scenario and end time.
add_test(NAME package.install_and_build_consumer
         COMMAND ${CMAKE_COMMAND}
           -DBUILD_DIR=${PROJECT_BINARY_DIR}
           -DWORK=${CMAKE_CURRENT_BINARY_DIR}/package_consumer
           -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
           -DGENERATOR=${CMAKE_GENERATOR}
           -DMAKE_PROGRAM=${CMAKE_MAKE_PROGRAM}
           -DCXX=${CMAKE_CXX_COMPILER}
           -DVERSION=${PROJECT_VERSION}
           -DSANITIZE=${FDEM_SANITIZE}
           -P ${CMAKE_CURRENT_LIST_DIR}/consumer.cmake)
# installs the build tree: run it after everything is built (ctest runs after the build)
set_tests_properties(package.install_and_build_consumer PROPERTIES LABELS package TIMEOUT 300
                     PASS_REGULAR_EXPRESSION "OK: consumer hash [0-9a-f]+ = CLI hash")
