// A plain texel copy: the cost floor any full-screen pass is measured against.
out vec4 o_color;
uniform sampler2D u_source;
void main() { o_color = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0); }
