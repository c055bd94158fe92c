// program_cache.hpp - on-disk cache of compiled OpenCL program binaries.
//
// Key: the expanded kernel source, the build options, the device name, the
// driver version and the platform version. The file name is a 64-bit hash of
// that key; the file also stores the full key text and a checksum of the
// binary, so a hash collision, a truncated or a corrupted entry is detected
// on load and the caller falls back to a real build.
//
// Directory: $CLRT_CACHE_DIR, else $XDG_CACHE_HOME/clrt, else ~/.cache/clrt
// (created mode 0700). When that directory is not this user's own or others
// may write it (a shared CLRT_CACHE_DIR, /tmp), the entries go to its
// subdirectory clrt-<uid>, created 0700 and used only while it is a real
// directory of this user that nobody else may enter; otherwise nothing is
// cached (a warning, once). Every file is opened beneath that directory's
// descriptor, never through a link, never blocking (a FIFO or device at a
// name is refused), and read only when it is a regular file of this user.
// Entries are written to a temporary file (random name, O_EXCL) and renamed
// into place, so concurrent clrt processes never see a half-written entry
// and a name planted by someone else is never written through.
//
// Size: after each store, the oldest entries (by modification time; a load
// refreshes it) are deleted until the entries total at most the limit,
// $CLRT_CACHE_MAX_SIZE (bytes, or with a K, M or G suffix: binary units),
// else 256 MiB. Every file in the directory is untrusted: an entry is a
// regular file named <16 hex digits>.bin, nothing else is ever deleted, and
// no symbolic link is followed (a link named like an entry is not one).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace clrt {

struct ProgramCacheKey {
  std::string source, options, device, driver, platform;
  std::string text() const;  // the canonical serialization (stored in the entry)
  std::string hash() const;  // 16 hex digits of text()'s 64-bit FNV-1a hash
};

// The configured directory; "" when none can be determined (no env
// variables, no HOME).
std::string program_cache_dir();

// Where the entries are, found without creating anything.
struct ProgramCacheLocation {
  std::string configured;  // program_cache_dir()
  std::string path;        // the entries' directory ("" when there is none)
  bool shared = false;     // path is configured's private clrt-<uid> subdirectory
  bool missing = false;    // not created yet (the first store creates it)
  std::string problem;     // why there can be no cache here ("" when none)
};
ProgramCacheLocation program_cache_location();

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

// ---- size limit, `clrt cache info` and `clrt cache clear` ------------------

constexpr uint64_t kDefaultProgramCacheLimit = 256ull << 20;

// "1048576", "512K", "256M", "1G" (K/M/G: 2^10, 2^20, 2^30; also "KiB",
// "MB", ... case-insensitive) -> bytes; nothing for anything else.
std::optional<uint64_t> parse_cache_size(const std::string& text);

// The limit in bytes: $CLRT_CACHE_MAX_SIZE, else kDefaultProgramCacheLimit.
// A value that does not parse throws UserError when `strict`; otherwise it
// is reported once (a warning) and the default is used.
uint64_t program_cache_limit(bool strict = false);

// A cache entry's file name: 16 lowercase hex digits and ".bin".
bool is_cache_entry_name(const std::string& name);

struct ProgramCacheStats {
  bool exists = false;     // the directory exists
  size_t entries = 0;      // regular files with an entry's name
  uint64_t bytes = 0;      // their total size
  size_t bad_markers = 0;  // ENTRY.bad: keys never cached again
  size_t other = 0;        // anything else (markers, temp files, links, foreign files)
};

// What `dir` holds; reads names and lstat()s only.
ProgramCacheStats cache_stats(const std::string& dir);

// Deletes the oldest entries of `dir` until its entries total at most
// `limit` bytes; returns how many were deleted. Never throws.
size_t cache_evict(const std::string& dir, uint64_t limit);

// Deletes every entry of `dir` and every ENTRY.bad marker (nothing else);
// returns how many entries were deleted and their bytes.
struct ProgramCacheCleared {
  size_t entries = 0, bad_markers = 0;
  uint64_t bytes = 0;
};
ProgramCacheCleared cache_clear(const std::string& dir);

}  // namespace clrt
