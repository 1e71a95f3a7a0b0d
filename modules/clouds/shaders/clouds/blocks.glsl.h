#pragma once
// The clouds' GPU blocks, declared once for GLSL (density.glsl includes this file) and C++
// (src/frame_block.h includes it inside a namespace; welkin/gfx/gpu_block.h says how). Fields come
// in rows of 16 bytes (a vec4, four scalars, a vec3 and one scalar, or a mat4), so that std140 and
// std430 lay them out as C++ does; tests/modules/clouds/gpu/gpu_blocks_test.cpp reads every field
// back in a shader. No #include and no initialisers here.

// Per frame: the uniform block CloudsFrame (src/frame_block.cpp fills it).
struct CloudsFrameGpu {
  float planet_radius_m;
  float camera_altitude_m;
  float camera_radius_m;  // from the planet's centre
  float layer_count;
  vec3 up;               // planet-centred up at the camera
  float max_distance_m;  // the march's
  float lowest_m;        // the layers' lowest base and highest top (altitudes)
  float highest_m;
  float empty_step_m;     // the empty-space step
  float largest_block_m;  // the largest occupancy block
  vec3 shape_origin;      // the camera in shape periods (fraction, drift applied)
  float shape_per_m;      // 1 / the shape noise's period
  vec3 detail_origin;     // the same for the detail noise
  float detail_per_m;
  float max_steps;
  float min_step_m;
  float max_step_m;
  float light_steps;
  float light_step_m;  // the first light step
  float octaves;       // multiple-scattering octaves
  float powder;
  float ground_albedo;
  float scattering;  // per unit density
  float absorption;
  float phase_model;  // CloudPhase
  float droplet_diameter_um;
  float g_forward;
  float g_backward;
  float forward_weight;
  float moon_marched;  // the light marched: 0 the sun, 1 the moon
  float frame_index;
  float shape_detail;  // 1: the detail noise erodes the layers
  float march_width;
  float march_height;
  float multiple_scattering;  // 0 octaves, 1 diffusion
  float pixel_angle_rad;      // a march pixel's angle
  float band_count;
  float step_growth;
  vec4 band_low;  // the altitude bands that hold layers (m, at most CLOUDS_MAX_BANDS): lower bounds
  vec4 band_high;  // and upper bounds
  // The painted coverage map's frame (welkin/scene/painted_map.h), relative to the planet's centre.
  vec3 map_east;    // east at the map's centre
  float map_scale;  // planet radius / map side
  vec3 map_north;
  float map_raise;  // the largest coverage the map adds
  vec3 map_up;
  float has_map;     // 1 when the scene has a map
  vec3 map_origin;   // the camera in (east, north, up) from the planet's centre, m
  float map_unused;  // (padding)
  float turbulence_m;        // largest displacement of the detail noise by the curl field (0: off)
  float system_amount;       // the weather systems' amount
  float system_slope_per_m;  // the largest change of the weather systems' signal per metre
  float noise_unused;        // (padding)
  vec3 system_origin;  // the camera in weather-system periods (fraction; the scene's origin at the anchor,
                       // drift applied)
  float system_per_m;  // 1 / the weather systems' period
  mat4 inverse_view_projection;  // camera-relative
};

// One layer: the storage buffer CloudLayers (src/frame_block.cpp packs them).
struct CloudLayerGpu {
  float base_m;
  float thickness_m;
  float base_variation_m;
  float density_per_m;
  float coverage;
  float shape_amount;
  float detail_amount;
  float filter_width;  // the coverage filter's width
  float profile_exp_term;
  float profile_exponent;
  float profile_linear_term;
  float profile_constant_term;
  vec3 weather_origin;  // the camera in weather periods (fraction, drift applied)
  float weather_per_m;  // 1 / the weather's period
  float dome;           // 0 sheet .. 1 dome
  float weather_channel;
  float casts_shadow;  // 1: it does
  float follows_map;   // 1: the painted coverage map adds to its coverage
  // The march hands the layer over to the mesh clusters or billboards from view distance
  // handover_near_m to handover_far_m (near 0: never), cross-fading over handover_crossfade_m.
  float handover_near_m;
  float handover_crossfade_m;
  float handover_far_m;
  float handover_unused;  // (padding)
  // The genus's erosion (welkin/clouds/genera.h): the detail noise's depth at the top (billows) and
  // at the base (wisps), and the density's rise inside the noise's edge.
  float billow;
  float wisp;
  float edge;
  float anvil_spread;  // the fraction of the clear sky around the towers the anvil covers (genera.h)
  // Streaks (welkin/clouds/genera.h): the shape and detail noise are read in a frame stretched by
  // `streak` along `streak_axis` (the layer's wind, unit, world axes; 0 without wind), the base trailing
  // the top downwind by hook_m; the noises' origins in that frame (fractions of their periods).
  vec3 streak_axis;
  float streak;
  vec3 streak_shape_origin;
  float hook_m;
  vec3 streak_detail_origin;
  float anvil_start;  // where the anvil starts (a fraction of the thickness; 0: no anvil)
};
