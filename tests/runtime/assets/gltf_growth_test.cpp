// The glTF reader does work linear in its JSON: fed 1x, 10x and 100x a pathological document (many
// nodes in many scenes, a long chain of children, many unknown keys, long strings), its time may grow
// by about 10x per step, not 100x (tests/support/growth.h).
#include <gtest/gtest.h>

#include <string>

#include "growth.h"
#include "test_util.h"

namespace {

using namespace welkin::assets;
using welkin::testing::measure_growth;

Model load_text(const std::string& text) {
  return load_gltf_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()),
                          "growth.gltf", "");
}

welkin::ErrorInfo error_of_text(const std::string& text) {
  try {
    load_text(text);
  } catch (const welkin::Error& e) {
    return e.info();
  }
  return {};
}

TEST(GltfGrowth, ManyScenesOverManyNodes) {
  // n nodes and n scenes, each scene listing one root: the roots' "listed once" marks are per scene.
  auto make = [](size_t n) {
    std::string s = R"({"asset": {"version": "2.0"}, "nodes": [)";
    for (size_t i = 0; i < n; ++i) s += i ? ", {}" : "{}";
    s += R"(], "scenes": [)";
    for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + ("{\"nodes\": [" + std::to_string(i) + "]}");
    return s + "]}";
  };
  auto g = measure_growth(200, make, load_text);
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(load_text(make(5)).nodes.size(), 5u);
}

TEST(GltfGrowth, ALongChainOfChildren) {
  // Node i is the child of node i + 1: the cycle check walks each node up once, not once per node.
  auto make = [](size_t n) {
    std::string s = R"({"asset": {"version": "2.0"}, "nodes": [{})";
    for (size_t i = 1; i < n; ++i) s += ", {\"children\": [" + std::to_string(i - 1) + "]}";
    return s + "], \"scenes\": [{\"nodes\": [" + std::to_string(n - 1) + "]}]}";
  };
  auto g = measure_growth(200, make, load_text);
  EXPECT_TRUE(g.linear()) << g.describe();
  EXPECT_EQ(load_text(make(6)).nodes.size(), 6u);
}

TEST(GltfGrowth, ManyExtrasKeysAndLongNames) {
  auto make = [](size_t n) {
    std::string s = R"({"asset": {"version": "2.0", "extras": {)";
    for (size_t i = 0; i < n; ++i)
      s += (i ? ", " : "") + ("\"k" + std::to_string(i) + "\": " + std::to_string(i));
    s += R"(}}, "nodes": [{"name": ")" + std::string(n * 20, 'n') + R"("}], "scenes": [{"nodes": [0, 0]}]})";
    return s;
  };
  auto g = measure_growth(300, make, error_of_text);
  EXPECT_TRUE(g.linear()) << g.describe();
  welkin::ErrorInfo e = error_of_text(make(3));
  EXPECT_EQ(e.file, "growth.gltf");
  EXPECT_EQ(e.path, "/scenes/0/nodes/1");
  EXPECT_EQ(e.expected, "each root node once");
}

}  // namespace
