// Depth only: the shadow pass and the occlusion pre-pass write nothing but depth.
void main() {}
