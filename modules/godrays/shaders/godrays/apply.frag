// Subtracts the shafts from the frame (reverse-subtract blending: frame - loss), upsampled bilinearly:
// the shafts vary slowly across the screen, and at silhouettes the blend spreads over a few pixels
// (a depth-aware upsampling of four taps cost 4.9 copies of the frame against this one's 1.1).
in vec2 v_ndc;
layout(location = 0, index = 0) out vec4 o_loss;
layout(binding = 0) uniform sampler2D u_loss;
void main() { o_loss = vec4(textureLod(u_loss, v_ndc * 0.5 + 0.5, 0.0).rgb, 0.0); }
