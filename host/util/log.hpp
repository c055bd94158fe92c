// log.hpp - the one way code below app/ says something to the user outside
// its results (warnings, --verbose detail, a failed build's log). By default
// every message goes to stderr; app/ may route them elsewhere with a sink,
// so the layers that measure never write to a stream themselves.
#pragma once
#include <functional>
#include <string>

namespace clrt {

enum class LogLevel {
  Info,     // asked-for detail (--verbose): "clrt: <message>"
  Warning,  // something degraded but the command goes on: "clrt: warning: <message>"
  Error,    // the detail of an error about to be thrown (a kernel build log),
            // shown as it is: the error's own one line is main()'s
};

// `message`: one or more lines without the final newline.
using LogSink = std::function<void(LogLevel level, const std::string& message)>;

// Sends `message` to the sink. Calls are serialized: devices build their
// programs on parallel threads and each message stays whole.
void log_message(LogLevel level, const std::string& message);

// Replaces the sink; an empty one restores the default (write_log_to_stderr).
void set_log_sink(LogSink sink);

// The default sink: the message with its level's prefix, on stderr.
void write_log_to_stderr(LogLevel level, const std::string& message);

}  // namespace clrt
