#pragma once
// One error type for everything a user can get wrong: it names the file, the path inside the file,
// what was expected and what was found, so every front end can print one clear line.
#include <stdexcept>
#include <string>

namespace welkin {

struct ErrorInfo {
  std::string file;      // file the bad input came from ("" for code or command line)
  std::string path;      // JSON-pointer-like path inside it, e.g. /entities/0/components/core.Camera
  std::string expected;  // what a valid value looks like
  std::string found;     // what was there
  std::string message;   // free text when expected/found do not fit
};

class Error : public std::runtime_error {
 public:
  explicit Error(ErrorInfo info);
  explicit Error(const std::string& message) : Error(ErrorInfo{.message = message}) {}
  const ErrorInfo& info() const { return info_; }
  // Returns a copy with the file set when the thrower did not know it.
  Error with_file(const std::string& file) const;
  // Returns a copy whose path is prefixed (errors are thrown deep and located on the way out).
  Error with_path_prefix(const std::string& prefix) const;

 private:
  ErrorInfo info_;
};

std::string format_error(const ErrorInfo& info);

}  // namespace welkin
