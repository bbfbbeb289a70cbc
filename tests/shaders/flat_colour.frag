// Test fixture: one colour, set as a uniform.
uniform vec4 colour;
out vec4 fragment;
void main() { fragment = colour; }
