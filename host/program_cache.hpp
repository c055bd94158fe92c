// program_cache.hpp - on-disk cache of compiled OpenCL program binaries.
//
// Key: the expanded kernel source, the build options, the device name, the
// driver version and the platform version. The file name is a 64-bit hash of
// that key; the file also stores the full key text and a checksum of the
// binary, so a hash collision, a truncated or a corrupted entry is detected
// on load and the caller falls back to a real build.
//
// Directory: $CLRT_CACHE_DIR, else $XDG_CACHE_HOME/clrt, else ~/.cache/clrt.
// Entries are written to a temporary file and renamed into place, so
// concurrent clrt processes never see a half-written entry.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace clrt {

struct ProgramCacheKey {
  std::string source, options, device, driver, platform;
  std::string text() const;  // the canonical serialization (stored in the entry)
  std::string hash() const;  // 16 hex digits of text()'s 64-bit FNV-1a hash
};

// "" when no directory can be determined (no env variables, no HOME).
std::string program_cache_dir();

// The binary stored for `key`, or nothing (missing, unreadable, corrupted,
// other key). Never throws.
std::optional<std::vector<unsigned char>> cache_load(const ProgramCacheKey& key);

// Stores `binary` for `key`. Failures (read-only directory, full disk) are
// reported once on stderr and otherwise ignored: the cache is an optimization.
void cache_store(const ProgramCacheKey& key, const std::vector<unsigned char>& binary);

// Path of the entry for `key` (for tests and --verbose).
std::string cache_entry_path(const ProgramCacheKey& key);

}  // namespace clrt
