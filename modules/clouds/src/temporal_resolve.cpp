// The temporal resolve and the composite (temporal_resolve.h).
#include "temporal_resolve.h"

#include <memory>

#include "welkin/gfx/compute.h"
#include "welkin/gfx/screen_pass.h"

namespace welkin::clouds {

ResourceHandle add_resolve_pass(RenderGraph& g, RenderContext& rc, CloudsGpu& gpu,
                                const VolumetricClouds& clouds, const MarchOutput& current,
                                ResourceHandle scene_depth, glm::ivec2 offset, bool partial, int n, int w,
                                int h, ResourceHandle& clusters, bool clear) {
  const FrameView& view = rc.view;
  // The mesh clusters (and billboards) drawn before the march lie behind it. At the march's resolution
  // or below, the resolve lays them in as it writes (magnified at the march's pixels, a quarter of the
  // frame's); otherwise the composite reads them at the frame's resolution.
  const bool merge_clusters =
      clusters.valid() && g.resource_desc(clusters).width <= w && g.resource_desc(clusters).height <= h;
  const int write = gpu.history_index, read = 1 - write;
  const ResourceHandle out_color = g.import("clouds.history_color", *gpu.history_color[write]);
  const ResourceHandle history = g.import("clouds.history_previous", *gpu.history_color[read]);
  const TextureDesc depth_desc{
      .width = w, .height = h, .format = TextureFormat::r32f, .linear_filter = false};
  ensure_texture(gpu.history_depth[write], depth_desc);
  if (!gpu.history_depth[read]) ensure_texture(gpu.history_depth[read], depth_desc);  // read when held only
  const ResourceHandle out_depth = g.import("clouds.history_depth", *gpu.history_depth[write]);
  const ResourceHandle history_depth = g.import("clouds.history_depth_previous", *gpu.history_depth[read]);
  const glm::vec3 moved = glm::vec3(view.camera_position_m - gpu.previous_camera_m);
  const glm::mat4 previous_vp = gpu.previous_view_projection, inverse_vp = view.inverse_view_projection;
  const bool valid = gpu.history_valid;
  // What the march reads held since the last frame, the geometry aside (view_state): only the jitter
  // turned, so the history is this view's own march and is not clipped where the scene's depth is the
  // one it was marched against (resolve_pixel.glsl). The geometry is judged by its depth and not by its
  // digest, which a host's geometry changes every frame: the same camera and geometry resolve alike
  // whoever draws them (the package test compares a host's frame with `welkin render`'s).
  const bool held = gpu.view_state != 0 && gpu.view_state_frames >= 2;
  const float inside_cloud_m = 2.0f * gpu.block.min_step_m;  // two of the shortest march steps
  const ShaderDefines resolve_defines = {{"CLOUDS_CLIP", clouds.temporal_clipping ? "1" : "0"},
                                         {"CLOUDS_WITH_CLUSTERS", merge_clusters ? "1" : "0"},
                                         {"CLOUDS_CLEAR", clear ? "1" : "0"},
                                         {"CLOUDS_SILHOUETTES", current.silhouettes.valid() ? "1" : "0"}};
  const ResourceHandle merged =
      merge_clusters ? g.create("clouds.with_clusters",
                                TextureDesc{.width = w, .height = h, .format = TextureFormat::rgba16f})
                     : ResourceHandle{};
  const ResourceHandle out_clear =
      clear ? g.import("clouds.first_hit_clear", *gpu.first_hit.clear[write]) : ResourceHandle{};
  const bool compute = rc.forms.compute("clouds.resolve");
  g.add_pass(
      "clouds.resolve",
      [&](PassBuilder& b) {
        b.read(current.color);
        b.read(current.distance);
        if (current.silhouettes.valid()) b.read(current.silhouettes);
        b.read(history);
        b.read(scene_depth);
        b.read(history_depth);
        b.write(out_color);
        b.write(out_depth);
        if (clear) b.write(out_clear);
        if (merge_clusters) {
          b.read(clusters);
          b.write(merged);
        }
      },
      [&rc, current, out_color, history, offset, moved, previous_vp, inverse_vp, valid, resolve_defines,
       inside_cloud_m, partial, n, merge_clusters, clusters, merged, compute, w, h, clear, out_clear, held,
       scene_depth, history_depth, out_depth](PassContext& pc) {
        glBindTextureUnit(0, pc.texture(current.color).id());
        glBindTextureUnit(1, pc.texture(current.distance).id());
        glBindTextureUnit(2, pc.texture(history).id());
        if (merge_clusters) glBindTextureUnit(3, pc.texture(clusters).id());
        if (current.silhouettes.valid()) glBindTextureUnit(4, pc.texture(current.silhouettes).id());
        glBindTextureUnit(5, pc.texture(scene_depth).id());
        glBindTextureUnit(6, pc.texture(history_depth).id());
        const Program& p =
            compute ? rc.shaders.compute("clouds/resolve.comp", resolve_defines)
                    : rc.shaders.graphics("fullscreen.vert", "clouds/resolve.frag", resolve_defines);
        glProgramUniform2i(p.id(), p.location("u_offset"), offset.x, offset.y);
        glProgramUniform1i(p.id(), p.location("u_block"), n);
        p.set("u_inverse_view_projection", inverse_vp);
        p.set("u_previous_view_projection", previous_vp);
        p.set("u_camera_moved_m", moved);
        p.set("u_history_valid", valid ? 1 : 0);
        p.set("u_full_frame", partial ? 0 : 1);
        p.set("u_inside_cloud_m", inside_cloud_m);
        p.set("u_view_held", held ? 1 : 0);
        if (compute) {
          bind_image_for_write(0, pc.texture(out_color));
          if (merge_clusters) bind_image_for_write(1, pc.texture(merged));
          if (clear) bind_image_for_write(2, pc.texture(out_clear));
          bind_image_for_write(3, pc.texture(out_depth));
          dispatch_screen(p, PixelRect{0, 0, w, h});
          return;
        }
        // Drawn in this order: colour, depth, the clusters laid in, the clear distances (resolve.frag).
        const Texture* color = &pc.texture(out_color);
        const Texture* depth = &pc.texture(out_depth);
        const Texture* laid_in = merge_clusters ? &pc.texture(merged) : nullptr;
        const Texture* clear_distances = clear ? &pc.texture(out_clear) : nullptr;
        Framebuffer fb = laid_in && clear_distances
                             ? Framebuffer({color, depth, laid_in, clear_distances}, nullptr)
                         : laid_in         ? Framebuffer({color, depth, laid_in}, nullptr)
                         : clear_distances ? Framebuffer({color, depth, clear_distances}, nullptr)
                                           : Framebuffer({color, depth}, nullptr);
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ZERO);  // no second source colour while several buffers are drawn
        p.use();
        rc.draw_fullscreen_triangle();
      });
  const ResourceHandle result = merge_clusters ? merged : out_color;
  if (merge_clusters) clusters = {};
  gpu.history_index = read;
  gpu.history_valid = true;
  return result;
}

void composite_clouds(RenderGraph& g, RenderContext& rc, const FrameTargets& t, ResourceHandle result,
                      ResourceHandle clusters) {
  const bool compute = rc.forms.compute("clouds.composite");
  g.add_pass(
      "clouds.composite",
      [&](PassBuilder& b) {
        b.read(result);
        if (clusters.valid()) b.read(clusters);
        b.read(t.color);
        b.write(t.color);
      },
      [&rc, t, result, clusters, compute](PassContext& pc) {
        const Texture& color = pc.texture(t.color);
        glBindTextureUnit(0, pc.texture(result).id());
        if (clusters.valid()) glBindTextureUnit(1, pc.texture(clusters).id());
        ShaderDefines defines = {{"CLOUDS_WITH_CLUSTERS", clusters.valid() ? "1" : "0"}};
        if (compute) {
          defines["CLOUDS_RADIANCE_FORMAT"] = image_format_qualifier(color.desc().format);
          const Program& p = rc.shaders.compute("clouds/composite.comp", defines);
          bind_image_read_write(0, color);
          dispatch_screen(p, PixelRect{0, 0, color.desc().width, color.desc().height});
          return;
        }
        Framebuffer fb(&color, nullptr);
        fb.bind();
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_SRC_ALPHA);  // clouds + transmittance x what lies behind
        const Program& p = rc.shaders.graphics("fullscreen.vert", "clouds/composite.frag", defines);
        p.use();
        rc.draw_fullscreen_triangle();
        glDisable(GL_BLEND);
      });
}

}  // namespace welkin::clouds
