#version 330 core
// Blinn-Phong with a hemisphere ambient term, one directional light with a filtered shadow
// map, and three materials: plain, checkerboard ground (box-filtered with fwidth so it does
// not alias in the distance) and the sphere's octant pattern (shows rotation).
// The material is a compile-time constant, MATERIAL (0 plain, 1 checker ground, 2 sphere
// pattern; the renderer builds one program per material): llvmpipe runs both sides of a
// branch on every fragment, so a uniform switch made every ground pixel pay for the sphere's
// pattern and every sphere pixel for the checkerboard.
#ifndef MATERIAL
#define MATERIAL 0
#endif
in vec3 v_world;
in vec3 v_normal;
in vec3 v_local;
in vec4 v_light;

uniform vec3 u_colour;         // linear RGB
uniform vec3 u_colour2;        // second colour of the pattern
uniform float u_checker_size;  // metres per square (ground)
uniform float u_grid_spacing;  // metres between grid lines
uniform float u_local_scale;   // object coordinates to metres
uniform vec2 u_local_offset;
uniform vec3 u_spin_axis;      // sphere pattern: spin axis (object coordinates)
uniform float u_spin_blur;     // radians turned during the frame's exposure
uniform float u_shininess;
uniform float u_specular;
uniform vec3 u_light_dir;      // unit vector towards the light
uniform vec3 u_eye;
uniform vec3 u_background;
uniform float u_fog_start;
uniform float u_fog_end;
uniform sampler2DShadow u_shadow_map;
uniform vec2 u_shadow_kernel;    // tap offset (the soft edge), map coordinates
uniform float u_shadow_bias;     // depth bias, map depth units
uniform float u_shadow_slope_bias;

out vec4 frag_colour;

// Integral of a square wave of period 2: box-filtered checker (Inigo Quilez).
float filtered_checker(vec2 p) {
  vec2 w = max(fwidth(p), vec2(1e-4));
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) - abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}

// Anti-aliased thin lines on integer values of p.
float grid_lines(vec2 p, float width) {
  vec2 w = max(fwidth(p), vec2(1e-4));
  vec2 d = abs(fract(p - 0.5) - 0.5) / w;
  float line = 1.0 - min(min(d.x, d.y) / width, 1.0);
  return line * clamp(1.0 - 4.0 * max(w.x, w.y), 0.0, 1.0);
}

// SHADOWS (0 or 1) and SHADOW_TAPS (1 or 4) are compile-time constants too: the renderer
// draws with SHADOWS 1 only inside the screen rectangle where a shadow can fall
// (render/shadow_region.hpp) and with SHADOWS 0, which samples nothing, everywhere else.
#ifndef SHADOWS
#define SHADOWS 1
#endif
#ifndef SHADOW_TAPS
#define SHADOW_TAPS 4
#endif

// The map covers only where a visible shadow can fall (fitted each frame): outside it, lit.
// Receivers beyond the map's far depth are behind every caster: their depth is clamped.
float shadow_factor(vec3 n) {
#if SHADOWS == 0
  return 1.0;
#else
  vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0) return 1.0;
  float slope = 1.0 - max(dot(n, u_light_dir), 0.0);
  float ref = min(p.z, 1.0) - u_shadow_bias - u_shadow_slope_bias * slope;
#if SHADOW_TAPS == 1
  return texture(u_shadow_map, vec3(p.xy, ref));
#else
  float s = 0.0;
  s += texture(u_shadow_map, vec3(p.xy + vec2(-0.75, -0.25) * u_shadow_kernel, ref));
  s += texture(u_shadow_map, vec3(p.xy + vec2(0.25, -0.75) * u_shadow_kernel, ref));
  s += texture(u_shadow_map, vec3(p.xy + vec2(0.75, 0.25) * u_shadow_kernel, ref));
  s += texture(u_shadow_map, vec3(p.xy + vec2(-0.25, 0.75) * u_shadow_kernel, ref));
  return 0.25 * s;
#endif
#endif
}

float smooth_sign(float x) {
  float w = max(fwidth(x), 1e-5);
  return clamp(x / w, -1.0, 1.0);
}

// +1 / -1 on alternating octants, smoothed over `w` (about a pixel).
float octants(vec3 q, float w) {
  vec3 s = clamp(q / w, -1.0, 1.0);
  return s.x * s.y * s.z;
}

vec3 rotate(vec3 v, vec3 k, float a) {
  return v * cos(a) + cross(k, v) * sin(a) + k * dot(k, v) * (1.0 - cos(a));
}

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = u_colour;
#if MATERIAL == 1
  {
    vec2 g = v_local.xy * u_local_scale + u_local_offset;
    float c = filtered_checker(g / u_checker_size);
    albedo = mix(u_colour, u_colour2, c);
    float line = grid_lines(g / u_grid_spacing, 1.2);
    albedo = mix(albedo, albedo * 0.55, line);
  }
#elif MATERIAL == 2
  {
    // Octants alternate between the two colours; a dark band on the equator of the body's
    // x-z plane and one on a meridian make the spin axis and the rotation angle readable.
    vec3 q = normalize(v_local);
    float s = smooth_sign(q.x) * smooth_sign(q.y) * smooth_sign(q.z);
    if (u_spin_blur > 0.02) {
      // Motion blur: the pattern averaged over the frame's rotation (spin cue, no aliasing).
      float w = max(max(fwidth(q.x), fwidth(q.y)), max(fwidth(q.z), 1e-5));
      int n = int(clamp(ceil(u_spin_blur / 0.05), 2.0, 48.0));
      float sum = 0.0;
      for (int i = 0; i < n; ++i) {
        float a = u_spin_blur * ((float(i) + 0.5) / float(n) - 0.5);
        sum += octants(rotate(q, u_spin_axis, a), w);
      }
      s = sum / float(n);
    }
    albedo = mix(u_colour2, u_colour, 0.5 + 0.5 * s);
    float band_w = 0.06;
    float eq = abs(q.y);
    float band = 1.0 - smoothstep(band_w - fwidth(eq), band_w + fwidth(eq), eq);
    albedo = mix(albedo, vec3(0.04), band);
  }
#endif

  vec3 l = u_light_dir;
  vec3 v = normalize(u_eye - v_world);
  vec3 h = normalize(l + v);
  float diffuse = max(dot(n, l), 0.0);
  float spec = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), u_shininess) * u_specular : 0.0;
  float shadow = diffuse > 0.0 ? shadow_factor(n) : 0.0;
  vec3 sky = vec3(0.62, 0.66, 0.72);
  vec3 ground_bounce = vec3(0.30, 0.29, 0.27);
  vec3 ambient = mix(ground_bounce, sky, 0.5 + 0.5 * n.z) * 0.55;
  vec3 colour = albedo * (ambient + vec3(1.0, 0.98, 0.94) * diffuse * mix(0.18, 1.0, shadow)) +
                vec3(spec * shadow);
  float dist = length(u_eye - v_world);
  float fog = clamp((dist - u_fog_start) / max(u_fog_end - u_fog_start, 1e-3), 0.0, 1.0);
  colour = mix(colour, u_background, fog * fog);
  frag_colour = vec4(pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
