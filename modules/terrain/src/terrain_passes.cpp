// The GL work of the terrain's passes (terrain_system.cpp declares them each frame).
#include "terrain_passes.h"

#include <algorithm>

#include "welkin/core/world.h"
#include "welkin/gfx/light_environment.h"

namespace welkin::terrain {

namespace {

// One chunk's level: 16-bit indices counted from the chunk's first vertex, and the range of vertices
// they use (a rasteriser that shades a draw's whole range then shades only the level's).
void draw_elements(const Draw& d) {
  glDrawRangeElementsBaseVertex(
      GL_TRIANGLES, 0, std::max(d.vertex_count, 1u) - 1, GLsizei(d.count), GL_UNSIGNED_SHORT,
      reinterpret_cast<const void*>(uintptr_t(d.first) * sizeof(uint16_t)), GLint(d.base_vertex));
}

// Where a terrain sits relative to the camera, for terrain.vert (view and shadow passes alike).
void bind_placement(const Program& prog, const Placed& p, const FrameView& view) {
  prog.set("u_anchor_relative", glm::vec3(p.anchor_m - view.camera_position_m));
  prog.set("u_anchor_xy", glm::vec2(p.anchor_m));
  prog.set("u_rotation", p.rotation);
  prog.set("u_inverse_two_radius", p.inverse_two_radius);
  glBindVertexArray(p.gpu->vao.id());
}

void set_material(const Program& prog, const GpuMaterial& m) {
  prog.set("u_base_color_factor", m.base_color_factor);
  prog.set("u_metallic", m.metallic);
  prog.set("u_roughness", m.roughness);
  prog.set("u_emissive", m.emissive);
  prog.set("u_occlusion_strength", m.occlusion_strength);
  prog.set("u_uv_transform", m.uv_transforms[0]);
  prog.set("u_metallic_roughness_transform", m.uv_transforms[1]);
  prog.set("u_occlusion_transform", m.uv_transforms[2]);
  prog.set("u_emissive_transform", m.uv_transforms[3]);
  prog.set("u_has_base_color", m.base_color ? 1 : 0);
  prog.set("u_has_metallic_roughness", m.metallic_roughness ? 1 : 0);
  prog.set("u_has_occlusion", m.occlusion ? 1 : 0);
  prog.set("u_has_emissive", m.emissive_map ? 1 : 0);
  glBindTextureUnit(0, m.base_color.id());
  glBindTextureUnit(1, m.metallic_roughness.id());
  glBindTextureUnit(2, m.occlusion.id());
  glBindTextureUnit(3, m.emissive_map.id());
}

}  // namespace

void draw_shadow_cascades(const Texture& atlas, const std::vector<Placed>& placed,
                          const std::array<glm::mat4, kShadowCascades>& light_view_projection, int size,
                          const std::vector<int>& stale,
                          const std::array<std::string, kShadowCascades>& inputs, RenderContext& rc,
                          TerrainCache& cache) {
  Framebuffer fb(nullptr, &atlas);
  fb.bind();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);  // slope-scaled bias against self-shadowing acne
  const Program& prog = rc.shaders.graphics("terrain/terrain.vert", "terrain/depth.frag");
  prog.use();
  for (int i : stale) {
    glViewport(i * size, 0, size, size);
    glScissor(i * size, 0, size, size);
    glClear(GL_DEPTH_BUFFER_BIT);
    prog.set("u_view_projection", light_view_projection[size_t(i)]);
    for (const Placed& p : placed) {
      bind_placement(prog, p, rc.view);
      for (const Draw& d : p.shadow_draws[size_t(i)]) draw_elements(d);
    }
    // Once drawn: a frame that failed before this draws it again.
    cache.cascade_inputs[size_t(i)] = inputs[size_t(i)];
    ++cache.cascade_draws;
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDepthFunc(GL_GREATER);  // back to the frame's reversed-Z convention
  glClearDepth(0.0);
}

void draw_kept_terrain(const Texture& color, const Texture& depth, RenderContext& rc,
                       const TerrainCache& cache) {
  // The kept depth replaces the frame's; the kept colour goes where it holds terrain (the depth
  // test against a triangle at infinity passes exactly there); the sky stays elsewhere.
  copy_texture(*cache.kept_depth, depth);
  Framebuffer fb(&color, &depth);
  fb.bind();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  rc.shaders.graphics("fullscreen.vert", "copy.frag").use();
  glBindTextureUnit(0, cache.kept_color->id());
  rc.draw_fullscreen_triangle();
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
}

void draw_surface(const Texture& color, const Texture& surface, const Texture& depth,
                  const std::vector<Placed>& placed, const SurfaceDraw& s, RenderContext& rc) {
  Framebuffer fb({&color, &surface}, &depth);
  fb.bind();
  // No terrain yet: the light pass skips what other geometry drew before (roughness 0).
  const GLuint none[4] = {0, 0, 0, 0};
  const PixelRect& covered = s.covered;
  glEnable(GL_SCISSOR_TEST);
  glScissor(covered.x0, covered.y0, covered.x1 - covered.x0, covered.y1 - covered.y0);
  glClearBufferuiv(GL_COLOR, 1, none);
  glColorMaski(0, s.emissive, s.emissive, s.emissive, s.emissive);
  glDisable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ZERO);  // several draw buffers: no second source colour may be named
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  const Program& prog = rc.shaders.graphics("terrain/terrain.vert", "terrain/terrain.frag",
                                            {{"TERRAIN_TEXTURE_TRANSFORMS", s.own_transforms ? "1" : "0"}});
  prog.use();
  prog.set("u_view_projection", rc.view.view_projection);
  for (const Placed& p : placed) {
    bind_placement(prog, p, rc.view);
    int bound = -2;
    for (const Draw& d : p.draws) {
      if (d.material != bound) {
        set_material(prog, p.gpu->materials[size_t(d.material)]);
        bound = d.material;
      }
      draw_elements(d);
    }
  }
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
}

void draw_surface_light(const Texture& color, const Texture& depth, const Texture& surface,
                        const SurfaceDraw& s, const std::optional<uint64_t>& inputs, RenderContext& rc,
                        World& world, TerrainCache& cache) {
  {
    // Depth attached read-only and read at the fragment's own texel (GL 4.5, 9.3.1); the triangle
    // at infinity passes GL_LESS only where something was drawn.
    Framebuffer fb(&color, &depth);
    fb.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_SCISSOR_TEST);
    const PixelRect& covered = s.covered;
    glScissor(covered.x0, covered.y0, covered.x1 - covered.x0, covered.y1 - covered.y0);
    if (s.emissive) {
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // onto the materials' own light
    }
    world.resource<LightEnvironment>().bind();
    const Program& prog = rc.shaders.graphics("fullscreen.vert", "terrain/light.frag");
    prog.use();
    prog.set("u_inverse_view_projection", rc.view.inverse_view_projection);
    glBindTextureUnit(0, depth.id());
    glBindTextureUnit(1, surface.id());
    rc.draw_fullscreen_triangle();
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_GREATER);
  }
  // Recorded once drawn (a failed frame draws again); kept when drawn twice alike.
  if (inputs && *inputs == cache.drawn_inputs) {
    const TextureDesc color_desc = color.desc(), depth_desc = depth.desc();
    if (!cache.kept_color || !(cache.kept_color->desc() == color_desc))
      cache.kept_color = std::make_unique<Texture>(color_desc);
    if (!cache.kept_depth || !(cache.kept_depth->desc() == depth_desc))
      cache.kept_depth = std::make_unique<Texture>(depth_desc);
    copy_texture(color, *cache.kept_color);
    copy_texture(depth, *cache.kept_depth);
    cache.kept_inputs = *inputs;
  }
  cache.drawn_inputs = inputs.value_or(0);
}

}  // namespace welkin::terrain
