#pragma once
// The atmosphere's GPU blocks, declared once for GLSL (common.glsl includes this file) and C++
// (include/welkin/atmosphere/gpu_blocks.h includes it inside a namespace; welkin/gfx/gpu_block.h
// says how).
// Fields come in rows of 16 bytes (a vec4, four scalars, a vec3 and one scalar, or a mat4; a struct
// is a whole number of rows), so that std140 and std430 lay them out as C++ does;
// tests/modules/atmosphere/gpu/gpu_blocks_test.cpp reads every field back in a shader. No #include
// and no initialisers here. Lengths are km in a planet-centred frame whose axes are the scene's
// (x east, y north, z up); coefficients are per km.

// One layer of a density profile (Bruneton's): below width_km (the upper layer: everywhere above the
// lower one's width), the density at altitude h is
// clamp(exp_term exp(exp_scale_per_km h) + linear_term_per_km h + constant_term, 0, 1).
struct AtmosphereDensityLayerGpu {
  float width_km;
  float exp_term;
  float exp_scale_per_km;
  float linear_term_per_km;
  float constant_term;
  float unused_0;  // (padding)
  float unused_1;
  float unused_2;
};

// The planet and its air: with the persistent LUTs' sizes, all the transmittance and
// multi-scattering LUTs depend on (luts_differ).
struct AtmosphereMediumGpu {
  vec3 rayleigh_scattering;
  float unused_0;  // (padding)
  vec3 mie_scattering;
  float mie_g;  // the Mie phase's asymmetry
  vec3 mie_extinction;
  float mie_phase;  // 0 Cornette-Shanks, 1 Henyey-Greenstein
  vec3 absorption_extinction;
  float multiple_scattering_factor;
  vec3 ground_albedo;
  float lift_km;  // samples and the camera stay this far above the ground
  float bottom_radius_km;
  float top_radius_km;
  float horizon_distance_km;  // sqrt(top^2 - bottom^2): the top's distance at the ground's horizon
  float thickness_km;         // top - bottom
  // Bruneton's two-layer profiles: [0] below its width, [1] above (a one-layer profile has a lower
  // layer of width 0; an absent one has density 0 in both).
  AtmosphereDensityLayerGpu rayleigh_density[2];
  AtmosphereDensityLayerGpu mie_density[2];
  AtmosphereDensityLayerGpu absorption_density[2];
  float mie_moment_1;  // Legendre moments of the Mie phase, l = 1 and 2 (Funk-Hecke)
  float mie_moment_2;
  float unused_1;  // (padding)
  float unused_2;
};

// Per frame: the uniform block WelkinAtmosphere (src/uniforms.cpp fills it), read by every
// atmosphere shader and, through the light environment, by every material.
struct AtmosphereFrameGpu {
  AtmosphereMediumGpu medium;
  vec3 camera_km;  // planet-centred, never below the ground's lift
  float camera_radius_km;
  vec3 sun_direction;  // towards the sun
  float sun_cos_angular_radius;
  vec3 sun_illuminance;  // lux outside the atmosphere (colour, visible fraction applied)
  float sun_angular_radius_rad;
  vec3 moon_direction;
  float moon_cos_angular_radius;
  vec3 moon_illuminance;
  float moon_angular_radius_rad;
  vec3 moon_sunlit_direction;  // where sunlight comes from on the moon's visible face (its phase)
  float moon_illuminated_fraction;
  float sun_disc;                // 1: drawn
  float sun_limb_darkening;      // 1: applied
  float moon_disc;               // 1: drawn
  float moon_lights_sky;         // 1: the moon's light scatters in the air (ATM_MOON_LIGHT)
  mat4 inverse_view_projection;  // camera-relative
  mat4 view_projection;
  // The aerial-perspective volume's own frustum: the view's, or a wider one kept while the view turns
  // inside it (choose_aerial_frustum in gpu.h).
  mat4 aerial_inverse_view_projection;
  mat4 aerial_view_projection;
  mat4 sky_frame;  // the sky-view LUT's frame: x towards the sun's azimuth, z up at the camera
  int transmittance_width;
  int transmittance_height;
  int transmittance_steps;
  int unused_0;  // (padding)
  int multiscattering_size;
  int multiscattering_steps;
  int multiscattering_iterations;
  int unused_1;
  int sky_view_width;
  int sky_view_height;
  int sky_view_steps;
  int unused_2;
  int aerial_width;
  int aerial_height;
  int aerial_slices;
  int aerial_steps_per_slice;
  float aerial_distance_km;  // the aerial-perspective volume's depth
  float raymarch_steps;      // the sky's per-pixel march (when it does not read the sky-view LUT)
  float camera_in_space;     // 1: above the top of the atmosphere
  float raymarch_light_steps;
  // The sky-view LUT's mapping for this camera (atm_sky_view_uv_local, lut_mapping.h): beta is the
  // horizon's angle from the nadir.
  float sky_view_sin_beta;
  float sky_view_cos_beta;
  float sky_view_inv_tan_half_zenith_horizon;  // 1 / tan of half the horizon-to-zenith angle
  float sky_view_inv_tan_half_beta;
  float sky_view_v_scale;  // unit v to texel-centred v: v scale + offset
  float sky_view_v_offset;
  float sky_view_zenith_horizon;  // the horizon's zenith angle (rad)
  float sky_view_beta;
};

// One star of the star catalogue: the storage buffer AtmStars (src/stars.cpp makes them), read by
// stars.vert.
struct AtmosphereStarGpu {
  vec3 direction;         // on the celestial sphere: x towards the vernal equinox, z the celestial north pole
  float illuminance_lux;  // outside the atmosphere, on a surface facing the star
  vec3 color;             // linear Rec.709, luminance 1
  float unused_0;         // (padding)
};
