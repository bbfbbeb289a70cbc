// What renderer.cpp and renderer_frame.cpp share beyond renderer.hpp.
#pragma once

#include "renderer.hpp"

namespace clothsim {

// A lit shader: one that takes the key light, its shadows and the ambient occlusion.
inline bool is_lit(ShaderKind k) {
  return k == ShaderKind::Diffuse || k == ShaderKind::Phong || k == ShaderKind::Texture || k == ShaderKind::Bump ||
         k == ShaderKind::Displacement;
}

}  // namespace clothsim
