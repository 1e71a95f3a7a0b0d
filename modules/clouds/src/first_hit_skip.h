#pragma once
// The march's empty-space skipping from the last frame: each ray starts where the last frame's rays
// around it (reprojected) still saw no cloud, less how far the camera and the field moved since
// (march_pixel.glsl, clouds_skip_start). The resolve keeps, per pixel at the march's resolution, the
// distance up to which the ray held no cloud (resolve_pixel.glsl, resolved_clear); one block in eight
// of each march is marched whole in turn (the refresh that finds clouds appearing in front of that
// distance, whatever moved them there), and a change of the field other than its drift (coverage,
// layers, noise, shaders) marches every pixel whole, as does a still view.
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "frame_block.h"
#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/shader.h"

namespace welkin::clouds {

struct CloudsGpu;

// What the resolve keeps between frames for the skipping (CloudsGpu::first_hit).
struct FirstHitHistory {
  std::unique_ptr<Texture> clear[2];  // r32f at the march's size, indexed as CloudsGpu::history_color
  bool valid = false;                 // clear[1 - history_index] holds the last frame's
  uint64_t field = 0;                 // the field's digest when it was written (drift left out)
  FrameBlock block;                   // the last frame's block and layers (how far the noise drifted)
  std::vector<LayerBlock> layers;
};

// This frame's skipping: whether the march reads the last frame's clear distances and whether the
// resolve writes this frame's.
struct FirstHitSkip {
  bool read = false, write = false;
  float margin_m = 0.0f;  // the camera's move plus the field's largest drift since the last frame
  int round = 0;          // the blocks marched whole this frame: those with (x + 3 y + round) % 8 == 0
  GLuint unit = 0;        // where the march reads the clear distances
  glm::mat4 previous_view_projection{1.0f};
  glm::vec3 camera_moved_m{0.0f};
};

// Plans the skipping of a march at w x h and makes its textures; `enabled`:
// VolumetricClouds::skip_empty_front and the frame temporally upscaled; `partial`: one pixel of each
// block marched this frame, the view not still. `defines` gain what the march compiles in.
FirstHitSkip plan_first_hit_skip(CloudsGpu& gpu, bool enabled, bool partial, int w, int h,
                                 const glm::vec3& camera_moved_m, GLuint unit, ShaderDefines& defines);
// The march's uniforms for `skip` (program `p`).
void set_first_hit_uniforms(const Program& p, const FirstHitSkip& skip);
// After the march: the history's state for the next frame.
void finish_first_hit(CloudsGpu& gpu, const FirstHitSkip& skip);

}  // namespace welkin::clouds
