// Parsers of option values several subcommands share.
#include <regex>

#include "commands.h"
#include "welkin/core/error.h"
#include "welkin/gfx/image.h"

namespace welkin::cli {

void parse_size(const std::string& s, int& w, int& h) {
  static const std::regex re(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw Error(ErrorInfo{.path = "--size", .expected = "WIDTHxHEIGHT, e.g. 640x360", .found = "'" + s + "'"});
  w = std::stoi(m[1]);
  h = std::stoi(m[2]);
  // The pixel bound keeps one frame's float readback (16 bytes a pixel) to 1 GiB.
  if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide || uint64_t(w) * uint64_t(h) > kMaxImagePixels)
    throw Error(ErrorInfo{.path = "--size",
                          .expected = "1.." + std::to_string(kMaxImageSide) + " per side and at most " +
                                      std::to_string(kMaxImagePixels) + " pixels",
                          .found = "'" + s + "'"});
}

}  // namespace welkin::cli
