// Dear ImGui's OpenGL 3 renderer backend, compiled from the sources libimgui-dev ships, with GL
// entry points from libepoxy (as the runtime uses) instead of the backend's own gl3w loader.
#include <epoxy/gl.h>
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#include "imgui_impl_opengl3.cpp"
