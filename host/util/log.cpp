// log.cpp - the sink behind log_message(), stderr unless app/ sets another.
#include "util/log.hpp"

#include <iostream>
#include <mutex>
#include <utility>

namespace clrt {
namespace {

std::mutex& log_mutex() {
  static std::mutex m;
  return m;
}

LogSink& current_sink() {
  static LogSink sink = write_log_to_stderr;
  return sink;
}

}  // namespace

void write_log_to_stderr(LogLevel level, const std::string& message) {
  const char* prefix = level == LogLevel::Info ? "clrt: " : level == LogLevel::Warning ? "clrt: warning: " : "";
  std::cerr << prefix << message << "\n";
}

void log_message(LogLevel level, const std::string& message) {
  std::lock_guard<std::mutex> lock(log_mutex());
  current_sink()(level, message);
}

void set_log_sink(LogSink sink) {
  std::lock_guard<std::mutex> lock(log_mutex());
  current_sink() = sink ? std::move(sink) : LogSink(write_log_to_stderr);
}

}  // namespace clrt
