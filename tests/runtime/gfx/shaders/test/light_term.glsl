#pragma once
// A light term for the light-environment tests: scales the sun by a texel of its own texture and
// the sky by a value of its own uniform block, both at the units the environment assigned.
layout(binding = WELKIN_UNIT_TEST_SHADE) uniform sampler2D test_shade;
layout(std140, binding = WELKIN_BLOCK_TEST_SKY) uniform TestSky { vec4 test_sky; };
float test_light_visibility(vec3 p, vec3 n, int light) { return texelFetch(test_shade, ivec2(0), 0).r; }
float test_sky_visibility(vec3 p, vec3 n) { return test_sky.x; }
