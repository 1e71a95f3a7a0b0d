// The march after the geometry and its aerial perspective: at the quality's resolution, one pixel of
// each block per frame when upscaling temporally (the resolve fills the others, temporal_resolve.h),
// nothing at all while a still view keeps the clouds it has; then the composite over the frame.
#include "march.h"

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "density_field.h"
#include "first_hit_skip.h"
#include "frame_upload.h"
#include "placement.h"
#include "silhouette_march.h"
#include "temporal_resolve.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/screen_pass.h"

namespace welkin::clouds {

void bind_march_inputs(PassContext& pc, World& world, const CloudsGpu& gpu, const FrameTargets& t,
                       ResourceHandle front, GLuint front_unit) {  // (march.h)
  world.resource<LightEnvironment>().bind();
  bind_field(gpu);
  glBindTextureUnit(3, pc.texture(t.depth).id());
  glBindTextureUnit(4, gpu.blue_noise->id());
  if (front.valid()) glBindTextureUnit(front_unit, pc.texture(front).id());
}

namespace {

// What the march and the resolve read, the frame's index aside (it only turns the jitter) and the
// geometry's state aside: the block (the view) and layers, the field's noise and map, the shaders, the
// light environment's state.
uint64_t view_state(const CloudsGpu& gpu, uint64_t light, const ShaderDefines& defines, int n, int w, int h) {
  FrameBlock block = gpu.block;
  block.frame_index = 0.0f;
  uint64_t state = fnv1a_64_of(block, fnv1a_64_of(light));
  state = fnv1a_64(std::string_view(reinterpret_cast<const char*>(gpu.layers.data()),
                                    gpu.layers.size() * sizeof(LayerBlock)),
                   state);
  const int field[6] = {gpu.noise_seed, gpu.noise_builds, gpu.noise_cache_reads, n, w, h};
  state = fnv1a_64_of(gpu.coverage_map_revision, fnv1a_64_of(field, state));
  state = fnv1a_64(gpu.coverage_map_file, state);
  for (const auto& [k, v] : defines) state = fnv1a_64(k + "=" + v + ";", state);
  return state;
}

// The pixel of each n x n block this frame marches: in the order of a Bayer matrix (each next pixel
// as far as it can be from those marched just before); (0, 0) of 1 x 1 blocks when not `partial`.
glm::ivec2 block_offset(CloudsGpu& gpu, bool partial, int n) {
  static constexpr glm::ivec2 kOffsets2[4] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  static constexpr glm::ivec2 kOffsets4[16] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3},
                                               {3, 1}, {1, 3}, {1, 0}, {3, 2}, {3, 0}, {1, 2},
                                               {0, 1}, {2, 3}, {2, 1}, {0, 3}};
  return !partial ? glm::ivec2(0)
         : n == 4 ? kOffsets4[gpu.temporal_frame++ % 16]
                  : kOffsets2[gpu.temporal_frame++ % 4];
}

// A march's fragment form over the whole of `fb`.
void draw_march(RenderContext& rc, const Program& p, const Framebuffer& fb) {
  fb.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  // GL forbids several draw buffers while the blend function names a second source colour (the
  // atmosphere's aerial perspective leaves one), even with blending off.
  glBlendFunc(GL_ONE, GL_ZERO);
  p.use();
  rc.draw_fullscreen_triangle();
}

// The march at qw x qh (the frame's size over the block's), stopping where the mesh clusters turn
// opaque (`front`, when valid, bound at `front_unit`), starting where `skip` allows; a fragment or a
// compute pass (welkin/gfx/screen_pass.h), one body (clouds/march_pixel.glsl).
MarchOutput add_march_pass(SystemContext& sc, CloudsGpu& gpu, const ShaderDefines& defines,
                           glm::ivec3 stride_offset, int qw, int qh, ResourceHandle front, GLuint front_unit,
                           const FirstHitSkip& skip) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  const FrameTargets t = *sc.targets;
  const bool cluster_front = front.valid();
  const MarchOutput current{
      .color = sc.graph->create("clouds.march",
                                TextureDesc{.width = qw, .height = qh, .format = TextureFormat::rgba16f}),
      .distance = sc.graph->create("clouds.march_distance", TextureDesc{.width = qw,
                                                                         .height = qh,
                                                                         .format = TextureFormat::rgba32f,
                                                                         .linear_filter = false})};
  CloudsGpu* gp = &gpu;
  const bool compute = rc.forms.compute("clouds.march");
  const ResourceHandle clear =
      skip.read ? sc.graph->import("clouds.first_hit_previous", *gpu.first_hit.clear[1 - gpu.history_index])
                : ResourceHandle{};
  sc.graph->add_pass(
      "clouds.march",
      [&](PassBuilder& b) {
        b.read(t.depth);
        if (cluster_front) b.read(front);
        if (skip.read) b.read(clear);
        b.write(current.color);
        b.write(current.distance);
      },
      [gp, &rc, &world, t, current, defines, stride_offset, cluster_front, front, front_unit, compute, qw, qh,
       skip, clear](PassContext& pc) {
        bind_march_inputs(pc, world, *gp, t, front, front_unit);
        if (skip.read) glBindTextureUnit(skip.unit, pc.texture(clear).id());
        const Program& p = compute ? rc.shaders.compute("clouds/march.comp", defines)
                                   : rc.shaders.graphics("fullscreen.vert", "clouds/march.frag", defines);
        glProgramUniform3i(p.id(), p.location("u_stride_offset"), stride_offset.x, stride_offset.y,
                           stride_offset.z);
        set_first_hit_uniforms(p, skip);
        if (compute) {
          bind_image_for_write(0, pc.texture(current.color));
          bind_image_for_write(1, pc.texture(current.distance));
          dispatch_screen(p, PixelRect{0, 0, qw, qh});
          return;
        }
        draw_march(rc, p, Framebuffer({&pc.texture(current.color), &pc.texture(current.distance)}, nullptr));
      });
  return current;
}

}  // namespace

void clouds_system(SystemContext& sc) {
  World& world = sc.world;
  const VolumetricClouds* clouds = first_clouds(world);
  if (!clouds) return;
  auto& gpu = world.resource<CloudsGpu>();
  auto& rc = world.resource<RenderContext>();
  // No layer holds cloud (coverage 0, no thickness or density): nothing is marched.
  if (!gpu.has_layers) return;
  const int w = int(gpu.block.march_width), h = int(gpu.block.march_height);
  const FrameView& view = rc.view;
  const char* ap_mode = camera_in_space(world, gpu.block)                                  ? "2"
                        : clouds->aerial_perspective == CloudAerialPerspective::mean_depth ? "1"
                                                                                           : "0";
  // The field's layers and what each uses are compiled in, turbulence only where it displaces anything.
  ShaderDefines defines = field_defines(gpu);
  defines.merge(light_model_defines(gpu));
  defines.merge(band_defines(gpu));
  defines["CLOUDS_AP_MODE"] = ap_mode;
  // The mesh clusters drawn just before: the march ends where they turn opaque.
  // (published on the graph by the billboards or the clusters when they drew this frame).
  const ResourceHandle front = sc.graph->published(kFarCloudsFront);
  const bool cluster_front = front.valid();
  const GLuint front_unit = world.resource<LightEnvironment>().free_unit();
  if (cluster_front) {
    defines["CLOUDS_CLUSTER_FRONT"] = "1";
    defines["CLOUDS_UNIT_CLUSTER_FRONT"] = std::to_string(front_unit);
  }
  // A frame rendered alone marches every pixel (the history is another moment's).
  const bool temporal = clouds->temporal_upscaling && !sc.frame.alone && w >= 2 && h >= 2;
  if (temporal) {
    ensure_texture(gpu.history_color[gpu.history_index],
                   {.width = w, .height = h, .format = TextureFormat::rgba16f});
    if (!gpu.history_color[1 - gpu.history_index]) {
      ensure_texture(gpu.history_color[1 - gpu.history_index],
                     {.width = w, .height = h, .format = TextureFormat::rgba16f});
      gpu.history_valid = false;
    }
  }
  // Without a history (the first frame, a new size, after a frame without upscaling) every pixel is
  // marched once and becomes the history; then one pixel of each block per frame, in the order of a
  // Bayer matrix (each next pixel as far as it can be from those marched just before).
  const bool partial = temporal && gpu.history_valid;
  const int n = partial ? resolve_quality(*clouds).temporal_block : 1;
  const FrameTargets t = *sc.targets;
  RenderGraph& g = *sc.graph;
  ResourceHandle clusters = g.published(kFarCloudsColor);

  // A still view keeps its clouds (march_state). Clusters and billboards drawn before the march are
  // not followed: with them it marches.
  const std::optional<uint64_t> light = world.resource<LightEnvironment>().state();
  if (partial && light && !clusters.valid()) {
    const uint64_t view = view_state(gpu, *light, defines, n, w, h);
    if (view != gpu.view_state) gpu.view_state = view, gpu.view_state_frames = 0;
    const uint64_t state = fnv1a_64_of(t.geometry_state, view);
    if (state != gpu.march_state) gpu.march_state = state, gpu.march_state_frames = 0;
  } else {
    gpu.march_state_frames = 0, gpu.march_state = 0;
    gpu.view_state_frames = 0, gpu.view_state = 0;
  }
  if (partial && gpu.march_state != 0 && gpu.march_state_frames >= n * n) {
    // Kept: the history as the last frame's resolve left it.
    const ResourceHandle kept = g.import("clouds.history_color", *gpu.history_color[1 - gpu.history_index]);
    composite_clouds(g, rc, t, kept, {});
    gpu.previous_view_projection = view.view_projection;
    gpu.previous_camera_m = view.camera_position_m;
    return;
  }
  if (gpu.march_state != 0) ++gpu.march_state_frames;
  if (gpu.view_state != 0) ++gpu.view_state_frames;
  // Each ray starts where the last frame's rays around it met no cloud (first_hit_skip.h).
  ShaderDefines march_defines = defines;
  const glm::vec3 moved = glm::vec3(view.camera_position_m - gpu.previous_camera_m);
  // A still view marches whole (its march_state holds): what it keeps is then exactly its own march.
  const bool view_changed = gpu.march_state_frames <= 1;
  const FirstHitSkip skip =
      plan_first_hit_skip(gpu, temporal && clouds->skip_empty_front, partial && view_changed, w, h, moved,
                          front_unit + 1, march_defines);
  ++gpu.marches;
  if (!partial) ++gpu.full_marches;

  const int qw = (w + n - 1) / n, qh = (h + n - 1) / n;
  const glm::ivec2 offset = block_offset(gpu, partial, n);
  const glm::ivec3 stride_offset(n, offset.x, offset.y);
  MarchOutput current =
      add_march_pass(sc, gpu, march_defines, stride_offset, qw, qh, front, front_unit, skip);
  // With 2 x 2 blocks only: at 4 x 4 (`low`, `medium`) the march takes a sixteenth of the pixels and the
  // pass over the whole frame cost 3.5 times as much as it (llvmpipe, the peer scene at `low`; the list
  // of silhouette_march.h was not measured there).
  if (partial && clouds->march_silhouettes && n == 2)
    current.silhouettes =
        add_silhouette_march(sc, gpu, defines, stride_offset, current, w, h, front, front_unit);
  ResourceHandle result = current.color;
  if (temporal) {
    result = add_resolve_pass(g, rc, gpu, *clouds, current, t.depth, offset, partial, n, w, h, clusters,
                              skip.write);
  } else {
    gpu.history_valid = false;
  }
  finish_first_hit(gpu, skip);
  gpu.previous_view_projection = view.view_projection;
  gpu.previous_camera_m = view.camera_position_m;
  composite_clouds(g, rc, t, result, clusters);
}

}  // namespace welkin::clouds
