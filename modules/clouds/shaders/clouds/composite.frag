// Adds the clouds (marched at a fraction of the frame's resolution, upsampled bilinearly: colour
// is premultiplied, so filtering it is exact) over the frame: colour + transmittance x behind.
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_color;
layout(binding = 0) uniform sampler2D u_clouds;
void main() {
  o_color = texture(u_clouds, v_ndc * 0.5 + 0.5);
}
