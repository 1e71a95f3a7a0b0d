#pragma once
// One puff of the mesh clusters, declared once for GLSL (clouds/clusters.glsl includes this file) and
// C++ (src/clusters.h includes it inside a namespace; welkin/gfx/gpu_block.h says how). The placement
// compute (clusters_place.comp) writes it each frame, the puffs' draw reads it (std430). Fields come in
// rows of 16 bytes; tests/modules/clouds/gpu/gpu_blocks_test.cpp reads every field back in a shader.
// No #include and no initialisers here.
struct ClusterPuff {
  vec3 centre;             // camera-relative m
  float extinction_per_m;  // the peak extinction, at the centre (0: no puff)
  vec3 radii;              // along the clusters' axes (wind, across, up) m
  float light_depth;       // optical depth toward the light through the cluster's other puffs
  vec3 light;              // irradiance of the marched light at the centre
  float distance_m;        // of the centre from the camera
  vec3 sky;                // sky irradiance on a horizontal plane at the centre
  float height_m;          // of the centre above the cluster's base
  vec3 ap_inscattering;    // the air between the camera and the centre
  float inscattering_unused;  // (padding)
  vec3 ap_transmittance;
  float transmittance_unused;  // (padding)
  vec3 light_depth_gradient;   // how light_depth changes across the puff: per unit of its normalised axes
  float gradient_unused;       // (padding)
};
