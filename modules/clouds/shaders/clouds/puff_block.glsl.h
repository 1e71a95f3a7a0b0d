#pragma once
// One puff of the mesh clusters (a box: a column of its cell through the layer), declared once for
// GLSL (clouds/clusters.glsl includes this file) and C++ (src/clusters.h includes it inside a
// namespace; welkin/gfx/gpu_block.h says how). The placement compute (clusters_place.comp) writes it
// each frame, the puffs' draw reads it (std430). Fields come in rows of 16 bytes;
// tests/modules/clouds/gpu/gpu_blocks_test.cpp reads every field back in a shader.
// No #include and no initialisers here.
struct ClusterPuff {
  vec3 centre;                   // camera-relative m
  float extinction_per_density;  // the extinction per unit of the field's density (0: no puff)
  vec3 radii;                    // half the box along the cells' axes (east, north, up) m
  float light_depth;  // optical depth toward the light at the centre (the march's light steps)
  vec3 light;              // irradiance of the marched light at the centre
  float distance_m;        // of the centre from the camera
  vec3 sky;                // sky irradiance on a horizontal plane at the centre
  float system_signal;     // the weather systems' signal at the centre
  vec3 ap_inscattering;    // the air between the camera and the centre
  float inscattering_unused;  // (padding)
  vec3 ap_transmittance;
  float transmittance_unused;  // (padding)
  vec3 light_depth_gradient;   // how light_depth changes across the box: per unit of its normalised axes
  float gradient_unused;       // (padding)
};
