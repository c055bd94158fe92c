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

// Stores `binary` for `key`; false when nothing was stored. Failures
// (read-only directory, full disk) are reported once on stderr and otherwise
// ignored: the cache is an optimization.
bool cache_store(const ProgramCacheKey& key, const std::vector<unsigned char>& binary);

// A cached binary is untrusted input that the driver parses natively: a
// well-formed entry holding a bad binary can crash the process inside the
// driver (PoCL asserts, rusticl panics), on every run until it is deleted.
// So the first load of an entry is guarded by a marker file next to it
// (ENTRY.loading, holding the loading process's pid):
// - cache_begin_load() returns false - build from source - when the entry is
//   marked bad (ENTRY.bad), or another live process is loading it; when the
//   marker of a process that no longer runs is found, that load crashed: the
//   entry is deleted and marked bad for good. Otherwise it writes the marker
//   and returns true.
// - cache_end_load(ok) removes the marker; ok = false (the driver rejected
//   the binary without crashing) deletes the entry, to be rebuilt.
bool cache_begin_load(const ProgramCacheKey& key, std::string* note = nullptr);
void cache_end_load(const ProgramCacheKey& key, bool ok);

// The entry file format, for tests: magic, u64 key length, key text, u64
// binary length, binary, u64 FNV-1a of the binary. read returns false for
// anything malformed.
bool cache_read_entry(const std::string& path, std::string& key_text, std::vector<unsigned char>& binary);
bool cache_write_entry(const std::string& path, const std::string& key_text, const std::vector<unsigned char>& binary);

// Path of the entry for `key` (for tests and --verbose).
std::string cache_entry_path(const ProgramCacheKey& key);

}  // namespace clrt
