// One coarse vertex's step of each pass of the V-cycle: restrict_vertex (restrict_residuals),
// smooth_vertex (smooth_corrections) and prolong_vertex (prolong_corrections), shared by those
// passes (one dispatch per level or colour) and by cycle_small_levels (every small level in one
// workgroup). The includer declares the storage buffers residual[], rhs[] and corr[] that these
// write, and includes collide_objects.glsl and multigrid.glsl first (with MG_*_OF defined to
// read in place where it reads what it wrote). The CPU twins are the passes of the same names in
// host/core/reference/reference_multigrid.cpp, per vertex in the same arithmetic.
#ifndef CLOTHSIM_COARSE_LEVELS_GLSL
#define CLOTHSIM_COARSE_LEVELS_GLSL

// Coarse vertex g (its row v) in a fold: a coarse spring shorter than params.folded_chord of its rest
// length (folded in host/core/reference/reference_multigrid.cpp).
bool folded(uint g, uvec4 v) {
  vec4 q = position_of(int(v.x));
  vec3 p = q.xyz;
  float chord = folded_chord_at(material_of(int(v.x)).stiffness.z * q.w, params);
  uint last = mg_vertex(g + 1u).w;
  for (uint k = v.w; k < last; ++k) {
    uvec4 s = mg_entry(k);  // y rest bits, w the other end's particle
    precise float shortest = chord * uintBitsToFloat(s.y);
    if (length3(position_of(int(s.w)).xyz - p) < shortest) return true;
  }
  return false;
}

// The weighted sum of coarse vertex g's children's residual forces and masses: its right-hand
// side and, with its correction zeroed, its residual (the next level restricts that).
void restrict_vertex(uint g) {
  uvec4 v = mg_vertex(g);
  corr[g] = vec4(0.0);
  // Pinned, held, held by a collider, or in a fold: fixed in the coarse problem (w -1 says so).
  vec4 p = position_of(int(v.x));
  precise vec3 start = p.xyz + offset_of(int(v.x));
  g_self = int(v.x);
  if (p.w == 0.0 ||
      (has_colliders() && touches_colliders(start)) ||
      folded(g, v)) {
    rhs[g] = vec4(0.0, 0.0, 0.0, -1.0);
    residual[particle_count() + g] = vec4(0.0);
    return;
  }
  uint first = v.y, last = mg_vertex(g + 1u).y;
  precise vec4 b = vec4(0.0);
  for (uint k = first; k < last; ++k) {
    uvec4 c = mg_entry(k);  // x the child's residual, y its weight's bits
    b = b + MG_RESIDUAL_OF(c.x) * uintBitsToFloat(c.y);
  }
  rhs[g] = b;  // xyz the force, w the mass the vertex stands for
  // (A child is on the finer level, so no vertex of this level reads what another writes.)
  residual[particle_count() + g] = b;
}

// A Gauss-Seidel step of the linear coarse problem on coarse vertex g's 3x3 block. No two
// vertices of a colour share a coarse spring, so a colour's writes never race with its reads.
void smooth_vertex(uint g) {
  uvec4 v = mg_vertex(g);
  vec4 b = MG_RHS_OF(g);
  if (b.w < 0.0) return;  // a fixed vertex does not move (restrict_vertex)
  Sym3 diag;
  vec3 r = coarse_residual(g, v, b, diag);
  vec3 step;
  if (solve3(diag, r, step)) {
    precise vec3 e = MG_CORR_OF(g).xyz + step;
    corr[g] = vec4(e, 0.0);
  }
}

// Coarse vertex g's parents' corrections (the coarser level's), weighted, added to its own.
void prolong_vertex(uint g) {
  uvec4 v = mg_vertex(g);
  if (MG_RHS_OF(g).w < 0.0) return;  // a fixed vertex does not move (restrict_vertex)
  uint last = mg_vertex(g + 1u).z;
  precise vec3 e = vec3(0.0);
  for (uint k = v.z; k < last; ++k) {
    uvec4 p = mg_entry(k);  // x the parent, y its weight's bits
    e = e + MG_CORR_OF(p.x).xyz * uintBitsToFloat(p.y);
  }
  precise vec3 sum = MG_CORR_OF(g).xyz + e;
  corr[g] = vec4(sum, 0.0);
}

#endif
