# `validate` on shipped scenes and variants of them, each solver and feature at least once:
# every pass of the GPU simulator against its CPU twin, then frames in lock step, bit for bit on
# llvmpipe (docs/precision.md). Included by tests/CMakeLists.txt after add_gpu_command_test.
add_gpu_command_test("validate passes on pinned2 for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/pinned2.json --frames 10
  PROPERTIES LABELS gpu-long)
add_gpu_command_test("validate passes on cape (a cloth attached to a moving sphere, fabric) for 20 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/cape.json --frames 20)
add_gpu_command_test("validate passes on selfCollision for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/selfCollision.json --frames 10)
# The fabric solver (predict, the multigrid solve), alone and with self-collision and a collider.
add_gpu_command_test("validate passes on hang_xpbd (fabric) for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/hang_xpbd.json --frames 10)
add_gpu_command_test("validate passes on sphere with the fabric solver, fabric density and self-collision for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/sphere.json --frames 10
          --set simulation.solver="fabric" --set cloth.density=0.15
  PROPERTIES LABELS gpu-long)
# fabric's passes of the limit after the sweep (simulation.stretch_passes), with a limit tight
# enough (2 %) that they move springs once the cloth meets the floor.
add_gpu_command_test("validate passes on heap256 at 65² with stretch_passes 2 and max_stretch 0.02 for 20 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/heap256.json --frames 20
          --set cloth.num_width_points=65 --set cloth.num_height_points=65 --set simulation.max_stretch=0.02
          --set simulation.stretch_passes=2 --set simulation.stretch_passes_max=-1
  PROPERTIES LABELS gpu-long)
# Settling passes (simulation.stretch_passes_max) after the fixed ones, armed on the GPU (the
# pass check compares their count with the CPU's, and from a stretched state, which takes all 10).
add_gpu_command_test("validate passes on heap256 at 65² with settling passes up to 12 and max_stretch 0.02 for 30 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/heap256.json --frames 30
          --set cloth.num_width_points=65 --set cloth.num_height_points=65 --set simulation.max_stretch=0.02
          --set simulation.stretch_passes=2 --set simulation.stretch_passes_max=12
  PROPERTIES LABELS gpu-long)
# The same passes on the classic app's cloth under fabric, which leans on its limit from the
# tenth frame on.
add_gpu_command_test("validate passes on pinned2 under fabric with stretch_passes 2 for 20 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/pinned2.json --frames 20
          --set simulation.solver="fabric" --set simulation.stretch_passes=2
  PROPERTIES LABELS gpu-long)
# The fabric solver with self-collision, the CS184 cloth landed in folds on its floor by frame 20:
# the pass checks and the lock-step run, bitwise. Its thickness raised so that the contact
# distance (24 mm) exceeds the spacing (20.4 mm): the sweep's contacts then leave the cloth's
# own neighbours out (apart_at_rest) and take the others.
add_gpu_command_test("validate passes on selfCollision under the fabric solver for 21 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/selfCollision.json --frames 21
          --set simulation.solver="fabric" --set cloth.thickness=0.012
  PROPERTIES LABELS gpu-long)
add_gpu_command_test("validate passes on living (wind, gusts, a moving sphere, moving pins) for 20 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/living.json --frames 20
  PROPERTIES LABELS gpu-long)
# A mesh collider (docs/model.md, "Mesh colliders"): the drape over assimp-testmodels' open Wuson
# (its shell), at 33² so that the cloth lands on it within the 30 frames.
add_gpu_command_test("validate passes on drape_wuson (a mesh collider) at 33² for 30 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/drape_wuson.json --frames 30
          --set cloth.num_width_points=33 --set cloth.num_height_points=33
  PROPERTIES LABELS gpu-long)
# Mesh cloths (docs/model.md, "Mesh cloth"): a triangulated disc with a hole pinned by a box, and
# two cloths of different materials (a grid and a mesh) falling onto each other and a sphere.
add_gpu_command_test("validate passes on disc_hole (a mesh cloth) for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/disc_hole.json --frames 10)
add_gpu_command_test("validate passes on two_cloths (a grid and a mesh, two materials) for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/two_cloths.json --frames 10)
add_gpu_command_test("validate passes on disc_hole with the classic solver and wind for 10 frames"
  COMMAND $<TARGET_FILE:clothsim> validate ${PROJECT_SOURCE_DIR}/scenes/disc_hole.json --frames 10
          --set simulation.solver="classic" --set cloth.density=150 --set wind.velocity=[2,0,1])
