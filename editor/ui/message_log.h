#pragma once
// What the editor tells the user: errors from rejected edits, bad files, saves. Shown in the status
// bar and echoed to stderr, so scripted runs under Xvfb leave a readable trail.
#include <deque>
#include <string>

namespace welkin::editor {

struct Message {
  enum class Level { info, error } level = Level::info;
  std::string text;
};

class MessageLog {
 public:
  void info(std::string text);
  void error(std::string text);
  const std::deque<Message>& messages() const { return messages_; }
  static constexpr size_t kKept = 200;

 private:
  void add(Message m);
  std::deque<Message> messages_;
};

}  // namespace welkin::editor
