#version 330 core
// Lit pass: world position, normal, object-space position (patterns) and light-space
// position (shadow lookup).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_local;
out vec4 v_light;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_local = a_position;
  v_light = u_light_view_proj * world;
  gl_Position = u_view_proj * world;
}
