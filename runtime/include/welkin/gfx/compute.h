#pragma once
// Small helpers every module's compute work shares: persistent textures made on demand, dispatches
// followed by the barrier their readers need, and write-only image bindings.
#include <memory>

#include "welkin/gfx/gl_objects.h"
#include "welkin/gfx/shader.h"

namespace welkin {

// (Re)creates a persistent texture when its size or format changes, cleared to zero so that a pass
// that skips it still reads defined contents; returns true when it did.
bool ensure_texture(std::unique_ptr<Texture>& texture, const TextureDesc& desc);
// Uses the program and dispatches; later passes may sample or load what it stored.
void dispatch_compute(const Program& program, int groups_x, int groups_y, int groups_z = 1);
// Uses the program and dispatches the work groups that `commands` holds at `offset` (GL's indirect
// dispatch command: groups x, y, z, written by an earlier pass); later passes may read what it stored.
void dispatch_compute_indirect(const Program& program, const Buffer& commands, size_t offset = 0);
// Work groups of `size` covering n invocations.
inline int group_count(int n, int size) { return (n + size - 1) / size; }
// Binds every layer of a texture as a write-only image at `unit`.
void bind_image_for_write(GLuint unit, const Texture& texture);

}  // namespace welkin
