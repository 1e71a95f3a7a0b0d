#pragma once
// The mesh clusters: puffs placed from the field, lit, sorted and drawn (clusters.cpp).
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "placement.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// std430 mirror of ClusterPuff (shaders/clouds/clusters.glsl): one puff, written by the placement
// compute each frame, read by the puffs' draw.
struct ClusterPuffGpu {
  glm::vec4 centre;  // camera-relative m; w: peak extinction 1/m (0: no puff)
  glm::vec4 radii;   // along the clusters' axes (wind, across, up) m; w: optical depth toward the light
                     // through the cluster's other puffs
  glm::vec4 light;   // irradiance of the marched light at the centre; w: distance from the camera m
  glm::vec4 sky;     // sky irradiance on a horizontal plane at the centre; w: the centre's height above the
                     // cluster's base m
  glm::vec4 ap_inscattering;  // the air between the camera and the centre
  glm::vec4 ap_transmittance;
  glm::vec4
      light_gradient;  // how that optical depth changes across the puff: per unit of its normalised axes
};
static_assert(sizeof(ClusterPuffGpu) == 112, "ClusterPuffGpu must match the std430 ClusterPuff struct");

// The mesh clusters' GPU state (src/clusters.cpp).
struct ClustersGpu {
  std::unique_ptr<Buffer> proxy;  // the puff's proxy mesh as a triangle list of vec4 (pulled by gl_VertexID)
  int proxy_vertices = 0, proxy_level = -1;
  PlacementBuffers placement;
  std::unique_ptr<Buffer> puffs, order;
  size_t puff_capacity = 0, order_capacity = 0;
  GLuint vao = 0;
  int puff_count = 0;  // instances drawn last frame (clusters x puffs)
  ~ClustersGpu();
};

// Render phase, after the god rays and before the march (order 145): the mesh clusters, placed from
// the field, lit, sorted and drawn over the frame; the march then stops where they turn opaque.
void clusters_system(SystemContext& sc);
// The proxy mesh of one puff: a cube refined by Catmull-Clark (OpenSubdiv) onto the unit sphere and
// pushed out until it encloses it, as a triangle list (counter-clockwise from outside).
std::vector<glm::vec4> puff_proxy_mesh(int level);

}  // namespace welkin::clouds
