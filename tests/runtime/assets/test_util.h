#pragma once
// Small meshes and files for the asset tests; every file is generated into a per-process temp folder.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_meshes.h"
#include "welkin/assets/glb_writer.h"
#include "welkin/assets/gltf_loader.h"
#include "welkin/core/error.h"
#include "scratch_folder.h"

namespace welkin::assets::test {

namespace fs = std::filesystem;

inline fs::path temp_dir(const std::string& sub = "") {
  fs::path d = welkin::testing::scratch_folder("welkin-assets-test") / sub;
  fs::create_directories(d);
  return d;
}

inline void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Loads and returns the error; fails the test when loading succeeds.
template <typename F>
ErrorInfo error_of(F&& load) {
  try {
    load();
  } catch (const Error& e) {
    return e.info();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a welkin::Error: " << e.what();
    return {};
  }
  ADD_FAILURE() << "loading succeeded";
  return {};
}

}  // namespace welkin::assets::test
