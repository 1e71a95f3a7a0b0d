#include "ui/message_log.h"

#include "welkin/core/log.h"

namespace welkin::editor {

void MessageLog::info(std::string text) {
  log::info(text);
  add(Message{Message::Level::info, std::move(text)});
}

void MessageLog::error(std::string text) {
  log::write(log::Level::error, text);
  add(Message{Message::Level::error, std::move(text)});
}

void MessageLog::add(Message m) {
  messages_.push_back(std::move(m));
  while (messages_.size() > kKept) messages_.pop_front();
}

}  // namespace welkin::editor
