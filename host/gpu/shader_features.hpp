// What the compute passes are compiled with (compute/features.glsl): which collider kinds the
// scene has, whether a collider or a pin moves, which contact response it takes (fabric's
// Coulomb friction or classic's CS184 blend), the wind, attachments and skinned colliders. llvmpipe executes every branch of a shader for every invocation whatever the data,
// so a zero-trip mesh loop or an untaken Coulomb branch costs its full time there (a third of
// the classic step at 256², docs/performance.md); compiling only what the scene can reach
// removes it, and on a GPU it saves registers. The results are the same bits either way: the
// code left out is code no mass could take.
#pragma once

#include <filesystem>
#include <string>

#include "program.hpp"
#include "reference/reference.hpp"
#include "../../compute/layout.glsl"

namespace clothsim {

struct ShaderFeatures {
  bool spheres = true, planes = true, meshes = true;
  bool moving = true;   // some collider has keyframed motion (else every collider's motion is 0)
  bool coulomb = true;  // fabric's Coulomb friction, else the CS184 blend
  bool pins_moving = true;  // cloth.pinned_motion
  bool wind = true;         // the wind (advance and predict read compute_wind_forces' output)
  bool attachments = true;  // cloth.attachments (the forces and the multigrid solve read them)
  bool skinned = true;      // a skinned mesh collider (mesh.animation)

  // What a run with these constants can reach.
  static ShaderFeatures of(const Constants<float>& c) {
    ShaderFeatures f;
    f.spheres = !c.control.spheres.empty();
    f.planes = !c.control.planes.empty();
    f.meshes = !c.control.meshes.empty();
    f.moving = false;
    for (const auto* keys : {&c.timeline.spheres, &c.timeline.planes, &c.timeline.meshes})
      for (const auto& k : *keys) f.moving = f.moving || k.has_value();
    f.coulomb = c.multigrid != 0u;
    f.pins_moving = c.moving_pins();
    f.wind = c.wind_enabled;
    f.attachments = c.has_attachments();
    f.skinned = c.skin_vertices > 0;
    f.moving = f.moving || f.skinned;
    return f;
  }

  // The #defines of compute/features.glsl.
  gl::Defines defines() const {
    auto b = [](bool v) { return std::string(v ? "true" : "false"); };
    return {{"COLLIDE_SPHERES", b(spheres)}, {"COLLIDE_PLANES", b(planes)}, {"COLLIDE_MESHES", b(meshes)},
            {"COLLIDERS_MOVE", b(moving)},   {"COULOMB_FRICTION", b(coulomb)},
            {"PINS_MOVE", b(pins_moving)},   {"WIND_ENABLED", b(wind)},
            {"ATTACHMENTS", b(attachments)}, {"SKINNED_MESHES", b(skinned)}};
  }

  bool operator==(const ShaderFeatures&) const = default;
};

// compute/NAME.comp compiled for `features`, with `extra` defines after them (the multigrid
// passes' constants).
inline gl::Program load_pass(const std::filesystem::path& dir, const std::string& name, const ShaderFeatures& features,
                             const gl::Defines& extra = {}) {
  gl::Defines defines{{"WORKGROUP_SIZE", std::to_string(WORKGROUP_SIZE)}};
  for (const auto& d : features.defines()) defines.push_back(d);
  for (const auto& d : extra) defines.push_back(d);
  return gl::Program::compute(dir / (name + ".comp"), defines);
}

}  // namespace clothsim
