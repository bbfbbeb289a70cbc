// Reads and writes values; one invocation per value. Test fixture: doubles the first `count`.
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Values { float values[]; };
uniform uint count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < count) values[i] *= 2.0;
}
