# The Python face (python/, docs/python.md, docs/sweeps.md) under pytest: the module's API
# against the command line on a 7 x 5 cloth, and sweeps on a 2-worker Dask LocalCluster (8 runs,
# bad values and divergences recorded, a worker and then the sweep killed and the sweep resumed).
# GPU-tier: both backends run. No cache or bytecode is written into the source tree.
if(TARGET _clothsim)
  set(pytest_env env "PYTHONPATH=${CMAKE_BINARY_DIR}/python" PYTHONDONTWRITEBYTECODE=1
      "CLOTHSIM_SOURCE=${PROJECT_SOURCE_DIR}" "CLOTHSIM_BINARY=$<TARGET_FILE:clothsim-headless>")
  add_gpu_command_test("python: clothsim.Simulation steps, reads, sets, exports and renders as the command line does"
    COMMAND ${pytest_env} /usr/bin/python3 -m pytest -p no:cacheprovider -q
            "${CMAKE_CURRENT_LIST_DIR}/test_module.py")
  add_gpu_command_test("python: sweeps on Dask are bitwise deterministic and resume after a killed worker"
    COMMAND ${pytest_env} /usr/bin/python3 -m pytest -p no:cacheprovider -q
            "${CMAKE_CURRENT_LIST_DIR}/test_sweeps.py")
endif()
