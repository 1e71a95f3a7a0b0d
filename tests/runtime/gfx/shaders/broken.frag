out vec4 o_color;
#include "pattern_common.glsl"
void main() {
  o_color = vec4(1.0);
  undefined_function_here();
}
