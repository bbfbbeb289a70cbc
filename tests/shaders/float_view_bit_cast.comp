// For tests/tools/check_shader_bit_casts.py: the three ways an integer read through a float view
// can reach floatBitsToInt / floatBitsToUint (each must be found), and reads it must leave alone.
#version 430
layout(local_size_x = 1) in;
layout(binding = 0) uniform samplerBuffer floats_view;
layout(binding = 1) uniform isamplerBuffer ints_view;
layout(std430, binding = 0) buffer Out { ivec4 result[]; };

vec4 floats_of(int i) { return texelFetch(floats_view, i); }

void main() {
  result[0] = floatBitsToInt(texelFetch(floats_view, 0));  // found: directly
  result[1] = ivec4(floatBitsToUint(floats_of(1)));         // found: through an accessor
  vec4 fetched = texelFetch(floats_view, 2);
  result[2] = floatBitsToInt(fetched);                      // found: through a local
  // Left alone: integers through the integer view, and the bits of a computed float.
  result[3] = texelFetch(ints_view, 3) + floatBitsToInt(vec4(0.5) * 2.0);
}
