// Dear ImGui's GLFW platform backend, compiled from the sources libimgui-dev ships.
#include "imgui_impl_glfw.cpp"
