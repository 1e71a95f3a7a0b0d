#pragma once
// The march pixels next to the last frame's silhouettes as one dense list (issue 35): the marking
// (silhouettes_mark.comp) appends them, the march over the list (march_silhouettes.comp) is dispatched
// indirectly from its head, one invocation per listed pixel. The head is GL's indirect dispatch command
// (work groups x, y, z) and the count; src/silhouette_march.cpp resets it to (0, 1, 1, 0) each frame.
// Each listed pixel packs x in its low 16 bits, y in its high 16 (a march is at most 16384 wide).
#define CLOUDS_SILHOUETTE_GROUP 64  // invocations of the march over the list per work group
layout(std430, binding = CLOUDS_SILHOUETTE_LIST_BINDING) buffer CloudsSilhouetteList {
  uint sl_groups_x, sl_groups_y, sl_groups_z;
  uint sl_count;
  uint sl_pixels[];
};
