# The command-line flags the scripts read and the scripts under scripts/ that have a table or
# a summary to check (included by tests/CMakeLists.txt, after add_gpu_command_test).

# scripts/device-check (docs/device-check.md), the --quick way on this build: nothing built
# (--build-dir), no nested ctest on this build dir (CLOTHSIM_DEVICE_CHECK_NO_CTEST=1), validate
# and bench on whatever GL there is, then its summary.md checked (tests/tools/check_device_check.py).
add_gpu_command_test("scripts/device-check --quick runs on llvmpipe and writes its summary"
  COMMAND sh -c "out='${CMAKE_CURRENT_BINARY_DIR}/device_check_quick'; rm -rf \"$out\"; \
    CLOTHSIM_DEVICE_CHECK_NO_CTEST=1 OUT=\"$out\" '${PROJECT_SOURCE_DIR}/scripts/device-check' --quick --build-dir '${CMAKE_BINARY_DIR}'; code=$?; \
    /usr/bin/python3 '${CMAKE_CURRENT_SOURCE_DIR}/tools/check_device_check.py' \"$out\" --ctest-skipped || exit 1; \
    [ $code -eq 0 ] || { echo \"scripts/device-check exited $code\"; exit 1; }"
  PROPERTIES LABELS gpu-long TIMEOUT 900)
# simulate --intersections-every K: one flushed line per K-th frame (scripts/contact-check reads
# them); the selfCollision cloth of 4 frames has none.
add_test(NAME "cpu: simulate --intersections-every prints the count of every K-th frame"
  COMMAND sh -c "out=$('$<TARGET_FILE:clothsim-headless>' simulate '${PROJECT_SOURCE_DIR}/scenes/selfCollision.json' --backend cpu --frames 4 --intersections-every 2) || exit 1; \
    echo \"$out\"; [ \"$(echo \"$out\" | grep -c '^frame [24] self-intersections 0$')\" -eq 2 ]")
# simulate --stretch-every K: the largest and the 99th-percentile stretch of every K-th frame,
# both at least 1 on a hanging cloth (issue 22's 'at every frame' checks read them).
add_test(NAME "cpu: simulate --stretch-every prints the stretch of every K-th frame"
  COMMAND sh -c "out=$('$<TARGET_FILE:clothsim-headless>' simulate '${PROJECT_SOURCE_DIR}/scenes/hang_xpbd.json' --backend cpu --frames 4 --stretch-every 2) || exit 1; \
    echo \"$out\"; [ \"$(echo \"$out\" | grep -Ec '^frame [24] max stretch 1\\.[0-9]{4} p99 1\\.[0-9]{4}$')\" -eq 2 ]")
# scripts/hang-resolution (docs/solvers.md) prints its table: a 33² row on the CPU reference with
# a sag, its ratio 1.00 to itself and both stretch columns; a size it cannot use is exit 2.
add_test(NAME "cpu: scripts/hang-resolution prints the sag and stretch table; an even size is exit 2"
  COMMAND sh -c "out=$(CLOTHSIM='$<TARGET_FILE:clothsim-headless>' '${PROJECT_SOURCE_DIR}/scripts/hang-resolution' --sizes 33 --backends cpu) || exit 1; \
    echo \"$out\"; echo \"$out\" | grep -Eq '^ +cpu +33 +[0-9]+\\.[0-9]{3} +1\\.00 +1\\.[0-9]{4} +1\\.[0-9]{4} ' || exit 1; \
    CLOTHSIM='$<TARGET_FILE:clothsim-headless>' '${PROJECT_SOURCE_DIR}/scripts/hang-resolution' --sizes 64 --backends cpu; [ $? -eq 2 ]")

# scripts/drape-test (docs/materials.md): the Cusick tester on a coarse disc (2 cm edges) for a
# few frames on the CPU prints its row; an edge it cannot use and an unknown preset are exit 2.
add_test(NAME "cpu: scripts/drape-test prints a preset's drape coefficient and folds; bad input is exit 2"
  COMMAND sh -c "out=$(CLOTHSIM='$<TARGET_FILE:clothsim-headless>' /usr/bin/python3 '${PROJECT_SOURCE_DIR}/scripts/drape-test' --presets cotton --edge 0.02 --frames 20 --backend cpu) || exit 1; \
    echo \"$out\"; echo \"$out\" | grep -Eq '^cotton +[0-9]+\\.[0-9] +[0-9]+ +[0-9]+\\.[0-9] +0\\.0200$' || exit 1; \
    /usr/bin/python3 '${PROJECT_SOURCE_DIR}/scripts/drape-test' --edge 1; [ $? -eq 2 ] || exit 1; \
    /usr/bin/python3 '${PROJECT_SOURCE_DIR}/scripts/drape-test' --presets velvet; [ $? -eq 2 ]")

# scripts/fabric-check (docs/solvers.md, "The fabric solver"): for fabric its order check (a grid
# and the same grid as an OBJ of quads in grid, reversed and shuffled vertex order within 1 mm
# after 100 frames: 3 rows) and its slope check (Coulomb's closed form on a plane and on a tilted
# box mesh at 15, 30 and 60 substeps: 12 rows) pass; an unknown check is exit 2.
add_test(NAME "cpu: scripts/fabric-check order and slope pass for fabric; an unknown check is exit 2"
  COMMAND sh -c "out=$(CLOTHSIM='$<TARGET_FILE:clothsim-headless>' '${PROJECT_SOURCE_DIR}/scripts/fabric-check' --checks 'order slope') || exit 1; \
    echo \"$out\"; [ $(echo \"$out\" | grep -c ' PASS$') -eq 15 ] || exit 1; \
    CLOTHSIM='$<TARGET_FILE:clothsim-headless>' '${PROJECT_SOURCE_DIR}/scripts/fabric-check' --checks bogus; [ $? -eq 2 ]")
set_tests_properties("cpu: scripts/fabric-check order and slope pass for fabric; an unknown check is exit 2"
  PROPERTIES LABELS long)
