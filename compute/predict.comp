// Reads positions and displacements (through the views) and the colliders; writes positions
// and displacements in place. One invocation per particle: the xpbd solver's first pass
// (docs/model.md), damped Verlet under gravity alone, the springs being constraints solved
// after it, then the particle's tether to its nearest pin; with u_collide_objects the collision objects follow in the same invocation. The
// CPU twin is predict() in host/core/reference.cpp. Pinned particles (w = 0) stay.
#include "layout.glsl"
#include "common.glsl"
#include "collide_objects.glsl"

layout(local_size_x = WORKGROUP_SIZE) in;
layout(std430, binding = BINDING_POSITIONS) writeonly buffer Positions { vec4 pos[]; };
layout(std430, binding = BINDING_DISPLACEMENT) writeonly buffer Displacements { vec4 disp[]; };

uniform bool u_collide_objects;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(particle_count())) return;
  vec4 p = position_of(i);
  if (p.w == 0.0) return;
  precise vec3 d = displacement_of(i).xyz * params.keep_velocity + params.gravity * params.dt2;
  precise vec3 next = p.xyz + d;
  // The tether to the nearest pin (long-range attachments, host/core/tethers.cpp). Pins are
  // never written by this pass, so reading one races with nothing.
  vec4 tether = texelFetch(tethers_view, i);
  if (tether.x >= 0.0) {
    precise vec3 e = next - position_of(int(tether.x)).xyz;
    float len = length3(e);
    precise float limit = params.tether_limit * tether.y;
    if (len > limit) {
      precise float scale = (limit - len) * (1.0 / len);
      precise vec3 corr = e * scale;
      next = next + corr;
      d = d + corr;
    }
  }
  if (u_collide_objects) collide_with_objects(next, d);
  pos[i] = vec4(next, p.w);
  disp[i] = vec4(d, 0.0);
}
