// program_cache_size.cpp - the program cache's size limit:
// CLRT_CACHE_MAX_SIZE, parsed, or the default.
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <string>

#include "cl/program_cache.hpp"
#include "util/error.hpp"
#include "util/log.hpp"

namespace clrt {

std::optional<uint64_t> parse_cache_size(const std::string& text) {
  size_t i = 0;
  uint64_t n = 0;
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return std::nullopt;
  for (; i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])); ++i) {
    if (n > (UINT64_MAX - 9) / 10) return std::nullopt;
    n = n * 10 + uint64_t(text[i] - '0');
  }
  std::string unit;
  for (; i < text.size(); ++i) unit += char(std::tolower(static_cast<unsigned char>(text[i])));
  int shift = 0;
  if (unit.empty() || unit == "b")
    shift = 0;
  else if (unit == "k" || unit == "kb" || unit == "kib")
    shift = 10;
  else if (unit == "m" || unit == "mb" || unit == "mib")
    shift = 20;
  else if (unit == "g" || unit == "gb" || unit == "gib")
    shift = 30;
  else
    return std::nullopt;
  if (n > (UINT64_MAX >> shift)) return std::nullopt;
  return n << shift;
}

uint64_t program_cache_limit(bool strict) {
  const char* env = std::getenv("CLRT_CACHE_MAX_SIZE");
  if (!env || !*env) return kDefaultProgramCacheLimit;
  if (auto n = parse_cache_size(env)) return *n;
  std::string value(env);
  const std::string message =
      "CLRT_CACHE_MAX_SIZE: expected a size in bytes, or with K, M or G (got \"" + value.substr(0, 64) + "\")";
  if (strict) throw UserError(message);
  static std::once_flag warned;
  std::call_once(warned, [&] { log_message(LogLevel::Warning, message + "; using 256M"); });
  return kDefaultProgramCacheLimit;
}

}  // namespace clrt
