#version 460
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) writeonly buffer Out { float values[]; };
void main() { values[gl_GlobalInvocationID.x] = float(gl_GlobalInvocationID.x); }
