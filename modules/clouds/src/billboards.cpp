// The billboard clouds (clouds.CloudBillboards): one layer of the volumetric description drawn far
// away as impostors. When the layer's description or the atlas settings change, compute passes
// bake a few archetype clouds from the layer's own field into extinction volumes and from those an
// atlas of views that holds what relighting needs (shaders/clouds/billboards.glsl). Each frame the
// clusters' placement chooses the nearest cells whose weather holds cloud, a pass gives each its
// archetype, light and air, the instances are sorted far to near, and one instanced draw lays them
// into the mid- and far-range clouds' targets before the mesh clusters draw over them.
#include <algorithm>
#include <cmath>
#include <memory>

#include "billboards.h"
#include "clouds_gpu.h"
#include "density_field.h"
#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/gfx/light_environment.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

BillboardsGpu::~BillboardsGpu() {
  if (vao) glDeleteVertexArrays(1, &vao);
}

namespace {

// The archetypes' box: as wide as a cell, as high as the layer with its base's variation.
struct ArchetypeBox {
  float half_width_m, half_height_m, radius_m;
  int resolution, slices;     // voxels across and up
  float centre_above_base_m;  // the box's centre above the layer's base
};
ArchetypeBox archetype_box(const CloudBillboards& b, const CloudLayer& layer) {
  ArchetypeBox box;
  box.half_width_m = 0.5f * b.cell_m;
  box.half_height_m = 0.5f * layer.thickness_m + layer.base_variation_m;
  // The bake's window leaves nothing beyond 0.95 of the half width from the axis: the quads and
  // the views cover the cylinder that holds the cloud, not the box's corners.
  box.radius_m =
      std::sqrt(0.9025f * box.half_width_m * box.half_width_m + box.half_height_m * box.half_height_m);
  box.resolution = b.atlas_resolution;
  // Twice as fine upward as across (a layer is thin), at least 8 and at most as many as across.
  box.slices = std::clamp(2 * int(std::ceil(b.atlas_resolution * box.half_height_m / box.half_width_m)), 8,
                          std::max(8, b.atlas_resolution));
  box.centre_above_base_m = 0.5f * layer.thickness_m;
  return box;
}

// Everything the bake reads: the layer's description, the medium, the noise, the atlas settings
// and the coverage to 0.05 (so a keyed coverage re-bakes a few times, not every frame).
float bake_coverage(float coverage) { return std::round(coverage * 20.0f) / 20.0f; }
BillboardBakeKey bake_key(const CloudBillboards& b, const VolumetricClouds& clouds, const CloudLayer& L,
                          float coverage) {
  return {{float(b.archetypes),
           float(b.atlas_resolution),
           float(b.view_azimuths),
           float(b.view_elevations),
           b.cell_m,
           float(b.seed),
           float(L.genus),
           L.base_altitude_m,
           L.thickness_m,
           L.density_per_m,
           L.shape_amount,
           L.detail_amount,
           L.coverage_filter_width,
           L.base_variation_m,
           L.profile_exp_term,
           L.profile_exponent,
           L.profile_linear_term,
           L.profile_constant_term,
           bake_coverage(coverage),
           clouds.scattering_coefficient,
           clouds.absorption_coefficient,
           float(clouds.seed),
           clouds.shape_period_m,
           clouds.detail_period_m,
           clouds.weather_period_m,
           clouds.turbulence_displacement_m}};
}

void set_atlas_uniforms(const Program& p, const CloudBillboards& b, const ArchetypeBox& box) {
  glProgramUniform4i(p.id(), p.location("u_atlas"), b.view_azimuths, b.view_elevations, b.archetypes,
                     b.atlas_resolution);
  p.set("u_box", glm::vec4(box.half_width_m, box.half_height_m, box.radius_m, float(box.slices)));
  p.set("u_volume", glm::vec4(float(box.resolution), box.centre_above_base_m, 0.0f, 0.0f));
}

// The archetypes' volumes and the atlas of their views made anew (the bake) for `key`.
void add_bake_pass(RenderGraph& g, CloudsGpu& gpu, RenderContext& rc, const ShaderDefines& field, int packed,
                   const CloudBillboards& billboards, const ArchetypeBox& box, const BillboardBakeKey& key,
                   float coverage) {
  BillboardsGpu& bg = gpu.billboards;
  CloudsGpu* gp = &gpu;
  const int views = billboards.view_azimuths * billboards.view_elevations;
  auto volume = [&](TextureFormat format) {
    return std::make_unique<Texture>(TextureDesc{.width = box.resolution,
                                                 .height = box.resolution,
                                                 .depth = box.slices * billboards.archetypes,
                                                 .format = format});
  };
  bg.volume = volume(TextureFormat::r32f);
  bg.atlas = std::make_unique<Texture>(TextureDesc{.width = billboards.atlas_resolution,
                                                   .height = billboards.atlas_resolution,
                                                   .depth = 2 * views * billboards.archetypes,
                                                   .array = true,
                                                   .format = TextureFormat::rgba16f});
  // The fill beside them, a byte a voxel and a texel (a quarter of the volumes', a sixteenth of the
  // atlas's memory, bounded with them: validate()).
  bg.fill_volume = volume(TextureFormat::r8);
  bg.fill_atlas = std::make_unique<Texture>(TextureDesc{.width = billboards.atlas_resolution,
                                                        .height = billboards.atlas_resolution,
                                                        // an array even of one view and archetype
                                                        .depth = std::max(2, views * billboards.archetypes),
                                                        .array = true,
                                                        .format = TextureFormat::r8});
  bg.archetypes = std::make_unique<Buffer>(size_t(billboards.archetypes) * sizeof(glm::vec4));
  bg.baked = key;
  ++bg.bakes;
  const float rounded_coverage = bake_coverage(coverage);
  g.add_pass("clouds.billboards_bake", [](PassBuilder& b) { b.side_effect(); },
             [gp, &rc, field, packed, billboards, box, views, rounded_coverage](PassContext&) {
               BillboardsGpu& bb = gp->billboards;
               bind_field(*gp);
               glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, bb.archetypes->id());
               bind_image_for_write(0, *bb.volume);
               bind_image_for_write(1, *bb.atlas);
               bind_image_for_write(2, *bb.fill_volume);
               bind_image_for_write(3, *bb.fill_atlas);
               glBindTextureUnit(8, bb.volume->id());
               glBindTextureUnit(9, bb.fill_volume->id());
               const int r = billboards.atlas_resolution;
               const int64_t invocations[3] = {
                   billboards.archetypes,
                   int64_t(box.resolution) * box.resolution * box.slices * billboards.archetypes,
                   int64_t(r) * r * views * billboards.archetypes};
               for (int stage = 0; stage < 3; ++stage) {
                 ShaderDefines d = field;
                 d["BILLBOARDS_BAKE_STAGE"] = std::to_string(stage);
                 if (stage == 2) d["BILLBOARDS_VOLUME"] = "8", d["BILLBOARDS_FILL_VOLUME"] = "9";
                 const Program& p = rc.shaders.compute("clouds/billboards_bake.comp", d);
                 set_atlas_uniforms(p, billboards, box);
                 glProgramUniform1ui(p.id(), p.location("u_seed"), GLuint(billboards.seed));
                 p.set("u_layer", packed);
                 p.set("u_coverage", rounded_coverage);
                 dispatch_compute(p, group_count(int(invocations[stage]), 64), 1);
                 glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                                 GL_TEXTURE_FETCH_BARRIER_BIT);
               }
             });
}

}  // namespace

void billboards_system(SystemContext& sc) {
  World& world = sc.world;
  auto& gpu = world.resource<CloudsGpu>();
  BillboardsGpu& bg = gpu.billboards;
  Registry& reg = world.registry();
  const Entity be = reg.first<CloudBillboards>();
  if (be.is_null()) return;
  const CloudBillboards billboards = *reg.get<CloudBillboards>(be);
  check_component(billboards);
  const VolumetricClouds& clouds =
      drawn_clouds(reg, CloudBillboards::kTypeName, billboards.layer, "billboards");
  const int packed = gpu.billboards_layer;
  const int count = billboards.billboards;
  bg.drawn = 0;
  if (!gpu.has_layers || packed < 0 || count == 0) return;
  auto& rc = world.resource<RenderContext>();
  const FrameView& view = rc.view;
  const CloudLayer& layer = clouds.layers[size_t(billboards.layer)];
  const ArchetypeBox box = archetype_box(billboards, layer);
  const ShaderDefines field = field_defines(gpu);
  CloudsGpu* gp = &gpu;
  RenderGraph& g = *sc.graph;

  // The bake, when what it reads has changed.
  const float coverage = gpu.layers[size_t(packed)].coverage;
  const BillboardBakeKey key = bake_key(billboards, clouds, layer, coverage);
  if (!(key == bg.baked)) add_bake_pass(g, gpu, rc, field, packed, billboards, box, key, coverage);

  // Placement: the clusters' grid and choice over the billboards' ring, then the instances.
  const PlacementGrid grid = placement_grid(gpu, view, layer, billboards.cell_m, billboards.far_m);
  const int order_size = next_power_of_two(count);
  bg.placement.ensure(grid.grid, count);
  ensure_buffer(bg.billboards, bg.billboard_capacity, size_t(count) * sizeof(BillboardGpu));
  ensure_buffer(bg.order, bg.order_capacity, size_t(order_size) * 2 * sizeof(uint32_t));
  const glm::vec4 fade = gpu.billboards_fade;
  // The choice's ring: cells whose centres lie from the fade-in's middle (a billboard nearer is
  // moved out to it, so that every slot chosen draws) to far.
  const glm::vec2 ring{0.5f * (fade.x + fade.y), fade.w};
  const bool moon = gpu.block.moon_marched > 0.5f;
  const glm::vec3 light_dir = moon ? glm::vec3(0, 0, 1) : gpu.context.sun_direction;
  bg.drawn = count;
  g.add_pass(
      "clouds.billboards_place", [](PassBuilder& b) { b.side_effect(); },
      [gp, &rc, &world, field, grid, packed, count, order_size, ring, fade, billboards, box,
       moon](PassContext&) {
        BillboardsGpu& bb = gp->billboards;
        bind_field(*gp);
        world.resource<LightEnvironment>().bind();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bb.billboards->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, bb.order->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, bb.archetypes->id());
        bb.placement.choose(rc.shaders, field, grid, packed, count, ring, uint32_t(billboards.seed));
        const Program& p = rc.shaders.compute("clouds/billboards_place.comp", field);
        set_placement_uniforms(p, grid, uint32_t(billboards.seed));
        set_atlas_uniforms(p, billboards, box);
        p.set("u_layer", packed);
        p.set("u_count", count);
        p.set("u_order_size", order_size);
        p.set("u_fade", fade);
        p.set("u_density_scale", billboards.density_scale);
        p.set("u_light", moon ? 1 : 0);
        dispatch_compute(p, group_count(order_size, 64), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        sort_far_to_near(rc.shaders, order_size);
      });

  const FrameTargets t = *sc.targets;
  const int width = std::max(1, int(std::ceil(view.width * billboards.resolution_scale)));
  const int height = std::max(1, int(std::ceil(view.height * billboards.resolution_scale)));
  const bool volume = billboards.render == BillboardRender::volume;
  const FarCloudTargets targets = far_cloud_targets(g, width, height);
  // The sun's light through the clouds' shadow map where the layer casts shadows into it.
  const bool shadow_map = !moon && layer.casts_shadow && gpu.shadow.cascade_count > 0;
  g.add_pass(
      "clouds.billboards_draw",
      [&](PassBuilder& b) {
        b.read(t.depth);
        write_far_cloud_targets(b, targets);
      },
      [gp, &rc, &world, t, targets, count, grid, light_dir, billboards, box, volume,
       shadow_map](PassContext& pc) {
        BillboardsGpu& bb = gp->billboards;
        const Framebuffer fb = begin_far_cloud_draw(pc, targets);
        if (!bb.vao) glCreateVertexArrays(1, &bb.vao);
        glBindVertexArray(bb.vao);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, gp->frame_buffer->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bb.billboards->id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, bb.order->id());
        glBindTextureUnit(3, pc.texture(t.depth).id());
        glBindTextureUnit(4, volume ? bb.volume->id() : bb.atlas->id());
        glBindTextureUnit(volume ? 9 : 8, volume ? bb.fill_volume->id() : bb.fill_atlas->id());
        ShaderDefines d = light_model_defines(*gp);
        d["BILLBOARDS_RENDER_VOLUME"] = volume ? "1" : "0";
        if (volume) d["BILLBOARDS_VOLUME"] = "4", d["BILLBOARDS_FILL_VOLUME"] = "9";
        d["BILLBOARDS_SHADOW_MAP"] = shadow_map ? "1" : "0";
        if (shadow_map) world.resource<LightEnvironment>().bind();
        const Program& p = rc.shaders.graphics("clouds/billboard.vert", "clouds/billboard.frag", d);
        p.use();
        set_atlas_uniforms(p, billboards, box);
        p.set("u_view_projection", rc.view.view_projection);
        p.set("u_inverse_view_projection", rc.view.inverse_view_projection);
        p.set("u_viewport", glm::vec2(targets.width, targets.height));
        p.set("u_light_dir", light_dir);
        p.set("u_up_radius", glm::vec4(glm::vec3(gp->block.up), gp->block.camera_radius_m));
        p.set("u_axis_wind", grid.axis_wind);
        glDrawArraysInstanced(GL_TRIANGLES, 0, 6, count);
        end_far_cloud_draw(rc.view.width, rc.view.height);
      });
}

}  // namespace welkin::clouds
