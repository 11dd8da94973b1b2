#version 330 core
in vec3 v_colour;
out vec4 frag_colour;
void main() { frag_colour = vec4(pow(v_colour, vec3(1.0 / 2.2)), 1.0); }
