// The march at the last frame's silhouettes over a dense list of the marked pixels
// (silhouette_march.h). Marching them in a pass over the whole frame cost 1.8-2.2 times the frame at
// `high` on llvmpipe, and 4.6 ms on an H200 at 1080p: a group of pixels (llvmpipe's SIMD lanes, a GPU's
// warp) runs as long as its longest march, and a few marked pixels kept nearly every group busy.
#include "silhouette_march.h"

#include <string>

#include "march.h"
#include "placement.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/renderer.h"
#include "welkin/gfx/screen_pass.h"

namespace welkin::clouds {

namespace {

// The last frame's opacity range over the 3 x 3 pixels around that marks a pixel: 0.6, the strongest
// silhouettes; and how far the view must have moved the pixel (in the history's pixels) for it to be
// marked. On the peer scene at `high` before cd57934 (`welkin accuracy clouds --silhouettes --quick
// --size 640x360`, frames at 320 x 180: turning / flying at silhouettes, 10.12% / 19.27% without; the
// pixels listed turning 1 degree a frame, of 57600) 0.5 left 2.43% / 4.10% (3500 listed), 0.6 with
// the motion 3.35% / 5.77% (2620), 0.65 3.71% / 6.19% (2250), 0.75 4.73% / 7.48% (1630). Still, the
// motion lists none: 0.94% against 1.13% without the pass, 0.25% marching the still view's too.
// A silhouette pixel's march costs 2-3 times a pixel of the block march's (its ray meets thin cloud
// and goes on through the layer): docs/performance.md, "Silhouettes".
constexpr float kSilhouetteOpacity = 0.6f, kSilhouetteMotionPx = 0.25f;
// The list's storage buffer binding (clouds/silhouette_list.glsl); the march's layers hold 0.
constexpr GLuint kListBinding = 2;
// The list's head as each frame starts: no work group, no pixel (GL's DispatchIndirectCommand, then
// the count).
constexpr GLuint kEmptyHead[4] = {0, 1, 1, 0};

}  // namespace

ResourceHandle add_silhouette_march(SystemContext& sc, CloudsGpu& gpu, ShaderDefines defines,
                                    glm::ivec3 stride_offset, const MarchOutput& current, int w, int h,
                                    ResourceHandle front, GLuint front_unit) {
  World& world = sc.world;
  auto& rc = world.resource<RenderContext>();
  const FrameTargets t = *sc.targets;
  const FrameView& view = rc.view;
  const GLuint unit = front_unit + 1;
  defines["CLOUDS_UNIT_SILHOUETTE_HISTORY"] = std::to_string(unit);
  defines["CLOUDS_UNIT_SILHOUETTE_CURRENT"] = std::to_string(unit + 1);
  defines["CLOUDS_UNIT_SILHOUETTE_DISTANCE"] = std::to_string(unit + 2);
  defines["CLOUDS_SILHOUETTE_LIST_BINDING"] = std::to_string(kListBinding);
  // Every pixel listed at most once: the head and one word per pixel bound the list.
  ensure_buffer(gpu.silhouette_list, gpu.silhouette_list_capacity,
                sizeof(kEmptyHead) + size_t(w) * size_t(h) * sizeof(GLuint));
  const Buffer* list = gpu.silhouette_list.get();
  const ResourceHandle out = sc.graph->create(
      "clouds.march_silhouettes", TextureDesc{.width = w, .height = h, .format = TextureFormat::rgba16f});
  const ResourceHandle history =
      sc.graph->import("clouds.history_previous", *gpu.history_color[1 - gpu.history_index]);
  const glm::mat4 previous_vp = gpu.previous_view_projection, inverse_vp = view.inverse_view_projection;
  const glm::vec3 moved = glm::vec3(view.camera_position_m - gpu.previous_camera_m);
  sc.graph->add_pass(
      "clouds.silhouettes_mark",
      [&](PassBuilder& b) {
        b.read(history);
        b.read(current.color);
        b.read(current.distance);
        b.write(out);
      },
      [&rc, list, unit, defines, stride_offset, history, current, out, previous_vp, inverse_vp, moved, w,
       h](PassContext& pc) {
        const float unmarked[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
        glClearTexImage(pc.texture(out).id(), 0, GL_RGBA, GL_FLOAT, unmarked);
        glNamedBufferSubData(list->id(), 0, sizeof(kEmptyHead), kEmptyHead);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kListBinding, list->id());
        glBindTextureUnit(unit, pc.texture(history).id());
        glBindTextureUnit(unit + 1, pc.texture(current.color).id());
        glBindTextureUnit(unit + 2, pc.texture(current.distance).id());
        const Program& p = rc.shaders.compute("clouds/silhouettes_mark.comp", defines);
        glProgramUniform3i(p.id(), p.location("u_stride_offset"), stride_offset.x, stride_offset.y,
                           stride_offset.z);
        p.set("u_inverse_view_projection", inverse_vp);
        p.set("u_previous_view_projection", previous_vp);
        p.set("u_camera_moved_m", moved);
        p.set("u_silhouette_opacity", kSilhouetteOpacity);
        p.set("u_silhouette_motion_px", kSilhouetteMotionPx);
        glProgramUniform2i(p.id(), p.location("u_silhouette_size"), w, h);
        dispatch_screen(p, PixelRect{0, 0, w, h});  // its barrier covers the list's reads and the command
      });
  CloudsGpu* gp = &gpu;
  sc.graph->add_pass(
      "clouds.march_silhouettes",
      [&](PassBuilder& b) {
        b.read(t.depth);
        if (front.valid()) b.read(front);
        b.read(out);
        b.write(out);
      },
      [gp, &rc, &world, t, front, front_unit, list, defines, out](PassContext& pc) {
        bind_march_inputs(pc, world, *gp, t, front, front_unit);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kListBinding, list->id());
        const Program& p = rc.shaders.compute("clouds/march_silhouettes.comp", defines);
        bind_image_for_write(0, pc.texture(out));
        dispatch_compute_indirect(p, *list);
      });
  return out;
}

}  // namespace welkin::clouds
