#include "welkin/core/error.h"

namespace welkin {

std::string format_error(const ErrorInfo& e) {
  std::string s;
  if (!e.file.empty()) s += e.file;
  if (!e.path.empty()) s += (s.empty() ? "" : ": ") + std::string("at ") + e.path;
  if (!s.empty()) s += ": ";
  if (!e.message.empty()) s += e.message;
  if (!e.expected.empty() || !e.found.empty()) {
    if (!e.message.empty()) s += " (";
    s += "expected " + e.expected + ", found " + e.found;
    if (!e.message.empty()) s += ")";
  }
  return s;
}

Error::Error(ErrorInfo info) : std::runtime_error(format_error(info)), info_(std::move(info)) {}

Error Error::with_file(const std::string& file) const {
  ErrorInfo i = info_;
  if (i.file.empty()) i.file = file;
  return Error(i);
}

Error Error::with_path_prefix(const std::string& prefix) const {
  ErrorInfo i = info_;
  i.path = prefix + i.path;
  return Error(i);
}

}  // namespace welkin
