// Entry points, the GLB container, JSON parsing and the external-file policy.
#include "welkin/assets/gltf_loader.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "internal.h"
#include "welkin/scene/json_fields.h"
#include "tiny_gltf.h"
#include "welkin/assets/glb_writer.h"
#include "welkin/core/files.h"

namespace welkin::assets {

namespace fs = std::filesystem;

glm::mat3 TextureTransform::matrix() const {
  const float c = std::cos(rotation), s = std::sin(rotation);
  // Columns of T * R * S as KHR_texture_transform writes them (rotation is clockwise in matrix form).
  glm::mat3 t(1.0f), r(1.0f), sc(1.0f);
  t[2] = glm::vec3(offset, 1.0f);
  r[0] = glm::vec3(c, -s, 0.0f);
  r[1] = glm::vec3(s, c, 0.0f);
  sc[0][0] = scale.x;
  sc[1][1] = scale.y;
  return t * r * sc;
}

size_t Model::vertex_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes)
    for (const Primitive& p : m.primitives) n += p.positions.size();
  return n;
}

size_t Model::triangle_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes)
    for (const Primitive& p : m.primitives) n += p.triangle_count();
  return n;
}

namespace detail {

void fail(const Source& src, const std::string& path, const std::string& expected, const std::string& found) {
  throw Error(ErrorInfo{.file = src.name, .path = path, .expected = expected, .found = found});
}

std::string pointer_key(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::string show(const nlohmann::json& value) {
  std::string s = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > 80) s = s.substr(0, 77) + "...";
  return s;
}

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

uint32_t read_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

std::string hex_bytes(std::span<const uint8_t> b) {
  std::string s;
  char buf[8];
  for (size_t i = 0; i < b.size() && i < 4; ++i) {
    std::snprintf(buf, sizeof buf, "%s%02x", i ? " " : "", b[i]);
    s += buf;
  }
  return s;
}

}  // namespace

Container split_container(std::span<const uint8_t> bytes, const Source& src) {
  Container c;
  const bool magic = bytes.size() >= 4 && read_u32(bytes.data()) == kGlbMagic;
  if (!magic) {
    if (ends_with(src.name, ".glb"))
      fail(src, "<glb header>", "magic \"glTF\" (67 6c 54 46)",
           bytes.empty() ? "an empty file" : hex_bytes(bytes.first(std::min<size_t>(4, bytes.size()))));
    if (bytes.size() > src.options.limits.max_json_bytes)
      fail(src, "", "JSON of at most " + std::to_string(src.options.limits.max_json_bytes) + " bytes",
           std::to_string(bytes.size()) + " bytes");
    c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return c;
  }
  c.is_glb = true;
  if (bytes.size() < 20)
    fail(src, "<glb header>", "a 12-byte header and a JSON chunk header",
         "a file truncated to " + std::to_string(bytes.size()) + " bytes");
  const uint32_t version = read_u32(bytes.data() + 4);
  const uint32_t length = read_u32(bytes.data() + 8);
  if (version != 2) fail(src, "<glb header>/version", "2", std::to_string(version));
  if (length != bytes.size())
    fail(src, "<glb header>/length", "the file size " + std::to_string(bytes.size()),
         std::to_string(length) + (length > bytes.size() ? " (file truncated)" : " (trailing bytes)"));
  const uint64_t json_len = read_u32(bytes.data() + 12);
  const uint32_t json_type = read_u32(bytes.data() + 16);
  if (json_type != kChunkJson)
    fail(src, "<glb chunk 0>/type", "JSON (0x4E4F534A)", std::to_string(json_type));
  if (json_len == 0 || 20 + json_len > length)
    fail(src, "<glb chunk 0>/length",
         "1 to " + std::to_string(length - 20) + " bytes (what follows the header)",
         std::to_string(json_len));
  if (json_len > src.options.limits.max_json_bytes)
    fail(src, "<glb chunk 0>/length",
         "JSON of at most " + std::to_string(src.options.limits.max_json_bytes) + " bytes",
         std::to_string(json_len));
  c.json = std::string_view(reinterpret_cast<const char*>(bytes.data() + 20), json_len);
  uint64_t pos = 20 + json_len;
  if (pos == length) return c;
  if (pos % 4 != 0)
    fail(src, "<glb chunk 0>/length", "a multiple of 4 (chunks are 4-byte aligned)",
         std::to_string(json_len));
  if (pos + 8 > length)
    fail(src, "<glb chunk 1>", "an 8-byte chunk header", std::to_string(length - pos) + " bytes left");
  const uint64_t bin_len = read_u32(bytes.data() + pos);
  const uint32_t bin_type = read_u32(bytes.data() + pos + 4);
  if (bin_type != kChunkBin) fail(src, "<glb chunk 1>/type", "BIN (0x004E4942)", std::to_string(bin_type));
  if (pos + 8 + bin_len > length)
    fail(src, "<glb chunk 1>/length", "at most " + std::to_string(length - pos - 8) + " bytes (what is left)",
         std::to_string(bin_len));
  if (bin_len < 4 || bin_len % 4 != 0)
    fail(src, "<glb chunk 1>/length", "a non-zero multiple of 4", std::to_string(bin_len));
  c.has_bin = true;
  c.bin = bytes.subspan(pos + 8, bin_len);
  return c;  // later chunks are ignored, as the specification asks
}

nlohmann::json parse_json(std::string_view text, const Source& src) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (ch == '\\')
        escaped = true;
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > src.options.limits.max_json_depth)
        fail(src, "",
             "JSON nested at most " + std::to_string(src.options.limits.max_json_depth) + " levels deep",
             "deeper nesting at byte " + std::to_string(i));
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
  try {
    return parse_json_unique_keys(text);
  } catch (const DuplicateJsonKey& d) {
    fail(src, d.path, "each key once per object", "a duplicate key");
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    if (auto p = what.find("parse error"); p != std::string::npos) what = what.substr(p);
    fail(src, "", "valid JSON", "syntax error at byte " + std::to_string(e.byte) + " (" + what + ")");
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    fail(src, "", "valid JSON", what);
  }
}

std::string percent_decode(std::string_view str) {
  auto from_hex = [](unsigned char ch) -> unsigned char {
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < str.size(); ++i) {
    if (str[i] == '+') {
      out += ' ';
    } else if (str[i] == '%' && str.size() > i + 2) {
      out += static_cast<char>((from_hex(str[i + 1]) << 4) | from_hex(str[i + 2]));
      i += 2;
    } else {
      out += str[i];
    }
  }
  return out;
}

namespace {
constexpr const char* kBufferHeaders[] = {"data:application/octet-stream;base64,",
                                          "data:application/gltf-buffer;base64,", "data:text/plain;base64,"};
constexpr const char* kImageHeaders[] = {"data:image/png;base64,", "data:image/jpeg;base64,"};
}  // namespace

DataUriKind data_uri_kind(std::string_view uri) {
  if (uri.substr(0, 5) != "data:") return DataUriKind::none;
  for (const char* h : kBufferHeaders)
    if (uri.starts_with(h)) return DataUriKind::buffer;
  for (const char* h : kImageHeaders)
    if (uri.starts_with(h)) return DataUriKind::image;
  return DataUriKind::unsupported;
}

uint64_t data_uri_decoded_size(std::string_view uri) {
  const size_t comma = uri.find(',');
  if (comma == std::string_view::npos) return 0;
  uint64_t chars = 0;
  for (size_t i = comma + 1; i < uri.size(); ++i) {
    const unsigned char c = uri[i];
    if (!(std::isalnum(c) || c == '+' || c == '/')) break;  // '=' padding or junk ends the payload
    ++chars;
  }
  return chars / 4 * 3 + (chars % 4 >= 2 ? chars % 4 - 1 : 0);
}

bool inside_base(const Source& src, const fs::path& candidate) {
  if (src.base_dir.empty()) return false;
  std::error_code ec;
  const fs::path base = fs::canonical(src.base_dir, ec);
  if (ec) return false;
  const fs::path full =
      fs::weakly_canonical(candidate, ec);  // relative: to the working directory, as open() does
  if (ec) return false;
  auto b = base.begin();
  auto f = full.begin();
  for (; b != base.end(); ++b, ++f)
    if (f == full.end() || *b != *f) return false;
  return f != full.end();
}

fs::path resolve_external(const Source& src, const std::string& uri, const std::string& path) {
  const std::string decoded = percent_decode(uri);
  const std::string expected = "a relative path to a file beside the glTF (or a data: URI)";
  if (decoded.empty()) fail(src, path, expected, "an empty URI");
  if (decoded.find('\0') != std::string::npos) fail(src, path, expected, "a NUL character in " + uri);
  if (decoded.front() == '/' || decoded.front() == '\\')
    fail(src, path, expected, "absolute path \"" + uri + "\"");
  const size_t colon = decoded.find(':'), slash = decoded.find_first_of("/\\");
  if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
    fail(src, path, expected,
         "URI scheme or drive \"" + decoded.substr(0, colon + 1) + "\" in \"" + uri + "\"");
  size_t start = 0;
  while (start <= decoded.size()) {
    size_t end = decoded.find_first_of("/\\", start);
    if (end == std::string::npos) end = decoded.size();
    if (decoded.compare(start, end - start, "..") == 0)
      fail(src, path, expected, "\"..\" escaping the folder in \"" + uri + "\"");
    start = end + 1;
  }
  if (src.base_dir.empty())
    fail(src, path, "no external files (this glTF was loaded from memory)", "external URI \"" + uri + "\"");
  const fs::path full = fs::path(src.base_dir) / decoded;
  std::error_code ec;
  if (!fs::is_regular_file(full, ec))
    fail(src, path, "an existing file beside the glTF", "missing file \"" + uri + "\"");
  if (!inside_base(src, full))
    fail(src, path, expected, "\"" + uri + "\" resolving outside the folder (through a symbolic link)");
  return full;
}

void hash_content(const Source& src, std::span<const uint8_t> bytes) {
  // The size first: bytes moved from one file to the next change the hash.
  const uint64_t size = bytes.size();
  src.content_hash = DiskCache::hash({reinterpret_cast<const char*>(&size), sizeof size}, src.content_hash);
  src.content_hash =
      DiskCache::hash({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, src.content_hash);
}

std::vector<uint8_t> read_file_limited(const Source& src, const fs::path& file, uint64_t max_bytes,
                                       const std::string& path) {
  try {
    // regular files only, never past max_bytes
    std::vector<uint8_t> bytes = read_file_bytes(file.string(), max_bytes);
    hash_content(src, bytes);
    return bytes;
  } catch (const Error& e) {
    fail(src, path, "a readable regular file of at most " + std::to_string(max_bytes) + " bytes",
         file.string() + ": " + e.info().message);
  }
}

Model load_checked(std::span<const uint8_t> bytes, const Source& src);

// Validation should leave nothing else to throw; should a library still throw (a failed allocation, a
// range check in tinygltf or Draco), the caller gets the same one kind of error.
Model load(std::span<const uint8_t> bytes, const Source& src) {
  try {
    return load_checked(bytes, src);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorInfo{.file = src.name, .message = "not enough memory to load this file"});
  } catch (const std::exception& e) {
    throw Error(ErrorInfo{.file = src.name,
                          .message = std::string("could not load (internal error: ") + e.what() + ")"});
  }
}

Model load_checked(std::span<const uint8_t> bytes, const Source& src) {
  const Container container = split_container(bytes, src);
  const nlohmann::json doc = parse_json(container.json, src);
  validate_document(doc, container, src);
  tinygltf::Model gm;
  // tinygltf 2.7 (without its unsafe Draco path) insists that index accessors have a bufferView, which
  // Draco-compressed primitives lack: it gets a copy without those "indices"; convert_model takes
  // them from `doc`.
  nlohmann::json stripped;
  for (size_t i = 0; doc.contains("meshes") && i < doc["meshes"].size(); ++i)
    for (size_t j = 0; j < doc["meshes"][i]["primitives"].size(); ++j) {
      const nlohmann::json& p = doc["meshes"][i]["primitives"][j];
      if (p.contains("indices") && p.contains("extensions") &&
          p["extensions"].contains("KHR_draco_mesh_compression")) {
        if (stripped.is_null()) stripped = doc;
        stripped["meshes"][i]["primitives"][j].erase("indices");
      }
    }
  if (stripped.is_null()) {
    parse_with_tinygltf(gm, bytes, container, src);
  } else {
    const std::string text = stripped.dump();
    Container copy = container;
    if (container.is_glb) {
      const std::string glb =
          GlbWriter::assemble(stripped, std::vector<uint8_t>(container.bin.begin(), container.bin.end()));
      const auto* b = reinterpret_cast<const uint8_t*>(glb.data());
      parse_with_tinygltf(gm, std::span(b, glb.size()), split_container(std::span(b, glb.size()), src), src);
    } else {
      copy.json = text;
      parse_with_tinygltf(gm, {}, copy, src);
    }
  }
  Model m = convert_model(gm, doc, src);
  m.file = src.name;
  m.content_hash = src.content_hash;
  return m;
}

}  // namespace detail

Model load_gltf(const std::string& path, const LoadOptions& options) {
  detail::Source src{.name = path, .base_dir = "", .options = options};
  std::error_code ec;
  fs::path dir = fs::path(path).parent_path();
  src.base_dir = dir.empty() ? std::string(".") : dir.string();
  if (!fs::exists(path, ec)) detail::fail(src, "", "an existing glTF file", "no such file");
  const std::vector<uint8_t> bytes = detail::read_file_limited(src, path, options.limits.max_file_bytes, "");
  return detail::load(bytes, src);
}

Model load_gltf_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& base_dir,
                       const LoadOptions& options) {
  detail::Source src{.name = name, .base_dir = base_dir, .options = options};
  if (bytes.size() > options.limits.max_file_bytes)
    detail::fail(src, "", "at most " + std::to_string(options.limits.max_file_bytes) + " bytes",
                 std::to_string(bytes.size()) + " bytes");
  detail::hash_content(src, bytes);
  return detail::load(bytes, src);
}

}  // namespace welkin::assets
