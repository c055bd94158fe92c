// test_program_cache.cpp - the program cache key, its size limit, info and
// clear (no device needed; the cache on a device is in
// tests/render/test_specialize.cpp).
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cl/program_cache.hpp"
#include "cli_run.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_program_cache {

using namespace clrt;

namespace {

using clrt_test::ScopedEnv;

}  // namespace

TEST_CASE("program cache key covers source, options and device", "[cache]") {
  ProgramCacheKey a{"src", "-DX=1", "dev", "drv", "plat"};
  ProgramCacheKey b = a, c = a, d = a;
  b.options = "-DX=2";
  c.source = "src ";
  d.driver = "drv2";
  CHECK(a.hash() != b.hash());
  CHECK(a.hash() != c.hash());
  CHECK(a.hash() != d.hash());
  // Length-prefixed fields: moving text between fields changes the key.
  ProgramCacheKey e{"srcx", "", "dev", "drv", "plat"}, f{"src", "x", "dev", "drv", "plat"};
  CHECK(e.text() != f.text());
}

// ---- the size limit, info and clear (no device needed) ------------------------

namespace {

namespace fs = std::filesystem;

// An entry file of `bytes` bytes in `dir` whose name is the hash of `seed`,
// last modified `age_s` seconds ago.
std::string make_entry(const clrt_test::TempDir& dir, const std::string& seed, size_t bytes, int age_s) {
  const ProgramCacheKey key{seed, "", "dev", "drv", "plat"};
  const std::string path = dir / (key.hash() + ".bin");
  const std::string text = key.text();
  const size_t overhead = 8 + 8 + text.size() + 8 + 8;
  REQUIRE(bytes > overhead);
  REQUIRE(cache_write_entry(path, text, std::vector<unsigned char>(bytes - overhead, 0x5a)));
  REQUIRE(fs::file_size(path) == bytes);
  fs::last_write_time(path, fs::file_time_type::clock::now() - std::chrono::seconds(age_s));
  return path;
}

}  // namespace

TEST_CASE("cache sizes parse with binary suffixes", "[cache]") {
  CHECK(parse_cache_size("0") == 0u);
  CHECK(parse_cache_size("1048576") == 1048576u);
  CHECK(parse_cache_size("512K") == 512u << 10);
  CHECK(parse_cache_size("256M") == 256u << 20);
  CHECK(parse_cache_size("256MiB") == 256u << 20);
  CHECK(parse_cache_size("2g") == 2ull << 30);
  CHECK(parse_cache_size("7b") == 7u);
  for (const char* bad : {"", "M", "-1", "1.5G", "12x", " 12", "12 ", "1T", "99999999999999999999", "17179869184G"}) {
    INFO(bad);
    CHECK_FALSE(parse_cache_size(bad).has_value());
  }
  CHECK(kDefaultProgramCacheLimit == 256u << 20);
}

TEST_CASE("cache entry names: 16 hex digits and .bin, nothing else", "[cache]") {
  CHECK(is_cache_entry_name("0123456789abcdef.bin"));
  CHECK(is_cache_entry_name(ProgramCacheKey{"s", "o", "d", "v", "p"}.hash() + ".bin"));
  for (const char* other : {"0123456789abcdef.bin.bad", "0123456789abcdef.bin.loading", "0123456789ABCDEF.bin",
                            "0123456789abcde.bin", "0123456789abcdefg.bin", "0123456789abcdef.bin.tmp.1.0",
                            "0123456789abcdef.txt", "x123456789abcdef.bin", ".bin", "notes.txt"}) {
    INFO(other);
    CHECK_FALSE(is_cache_entry_name(other));
  }
}

TEST_CASE("eviction deletes the oldest entries until the total is under the limit", "[cache]") {
  clrt_test::TempDir dir;
  const std::string oldest = make_entry(dir, "a", 4000, 400);
  const std::string old = make_entry(dir, "b", 4000, 300);
  const std::string recent = make_entry(dir, "c", 4000, 200);
  const std::string newest = make_entry(dir, "d", 4000, 100);
  const std::string d = dir.path().string();

  CHECK(cache_evict(d, 16000) == 0);  // at the limit: nothing to do
  CHECK(cache_stats(d).entries == 4);
  CHECK(cache_evict(d, 10000) == 2);
  CHECK_FALSE(fs::exists(oldest));
  CHECK_FALSE(fs::exists(old));
  CHECK(fs::exists(recent));
  CHECK(fs::exists(newest));
  const ProgramCacheStats s = cache_stats(d);
  CHECK(s.entries == 2);
  CHECK(s.bytes == 8000);
  CHECK(s.bytes <= 10000);
  CHECK(cache_evict(d, 0) == 2);  // a limit of 0 keeps nothing
  CHECK(cache_stats(d).entries == 0);
  CHECK(cache_evict(dir / "missing", 0) == 0);
}

TEST_CASE("eviction never deletes what is not an entry and follows no link", "[cache]") {
  clrt_test::TempDir outside, dir;
  const std::string d = dir.path().string();
  // Big files that are not entries: other names, markers, a directory.
  const std::string notes = dir.write("notes.txt", std::string(50000, 'x'));
  const std::string upper = dir.write("0123456789ABCDEF.bin", std::string(50000, 'x'));
  const std::string loading = dir.write("0123456789abcdef.bin.loading", "1\n");
  const std::string temp = dir.write("0123456789abcdef.bin.tmp.1.0", std::string(50000, 'x'));
  fs::create_directory(dir / "fedcba9876543210.bin");
  std::ofstream(dir / "fedcba9876543210.bin/inner") << "keep";
  // Links named like entries, to a big file outside and to an entry outside.
  const std::string target = outside.write("precious", std::string(50000, 'p'));
  fs::create_symlink(target, dir / "1111111111111111.bin");
  const ProgramCacheKey key{"outside", "", "dev", "drv", "plat"};
  const std::string outside_entry = outside / (key.hash() + ".bin");
  REQUIRE(cache_write_entry(outside_entry, key.text(), std::vector<unsigned char>(50000, 1)));
  fs::create_symlink(outside_entry, dir / "2222222222222222.bin");
  // One real entry, old.
  const std::string entry = make_entry(dir, "real", 3000, 1000);

  ProgramCacheStats s = cache_stats(d);
  CHECK(s.entries == 1);  // links, directories and other names do not count
  CHECK(s.bytes == 3000);
  CHECK(s.other == 7);

  CHECK(cache_evict(d, 0) == 1);
  CHECK_FALSE(fs::exists(entry));
  for (const auto& kept : {notes, upper, loading, temp, target, outside_entry}) {
    INFO(kept);
    CHECK(fs::exists(kept));
  }
  CHECK(fs::file_size(target) == 50000);
  CHECK(fs::is_symlink(dir / "1111111111111111.bin"));
  CHECK(fs::is_symlink(dir / "2222222222222222.bin"));
  CHECK(fs::exists(dir / "fedcba9876543210.bin/inner"));

  // A link named like an entry is never read as one either.
  std::string text;
  std::vector<unsigned char> bin;
  CHECK(cache_read_entry(outside_entry, text, bin));
  CHECK_FALSE(cache_read_entry(dir / "2222222222222222.bin", text, bin));
}

TEST_CASE("clear deletes entries and bad-key marks only", "[cache]") {
  clrt_test::TempDir outside, dir;
  const std::string d = dir.path().string();
  const std::string a = make_entry(dir, "a", 2000, 10), b = make_entry(dir, "b", 3000, 5);
  const std::string bad = dir.write(fs::path(a).filename().string() + ".bad", "crashed\n");
  const std::string notes = dir.write("notes.txt", "mine");
  const std::string target = outside.write("precious", "p");
  fs::create_symlink(target, dir / "3333333333333333.bin");

  const ProgramCacheCleared c = cache_clear(d);
  CHECK(c.entries == 2);
  CHECK(c.bytes == 5000);
  CHECK(c.bad_markers == 1);
  CHECK_FALSE(fs::exists(a));
  CHECK_FALSE(fs::exists(b));
  CHECK_FALSE(fs::exists(bad));
  CHECK(fs::exists(notes));
  CHECK(fs::exists(target));
  CHECK(fs::is_symlink(dir / "3333333333333333.bin"));
  const ProgramCacheStats s = cache_stats(d);
  CHECK(s.entries == 0);
  CHECK(s.other == 2);
}

TEST_CASE("storing enforces the limit of CLRT_CACHE_MAX_SIZE", "[cache]") {
  clrt_test::TempDir dir;
  const std::string d = dir.path().string();
  const std::string old1 = make_entry(dir, "old1", 3000, 300), old2 = make_entry(dir, "old2", 3000, 200);
  const std::string keep = dir.write("notes.txt", std::string(10000, 'x'));
  ScopedEnv cache_dir("CLRT_CACHE_DIR", d.c_str()), limit("CLRT_CACHE_MAX_SIZE", "7K");
  CHECK(program_cache_limit() == 7168);
  const ProgramCacheKey key{"new", "-DX", "dev", "drv", "plat"};
  REQUIRE(cache_store(key, std::vector<unsigned char>(2000, 7)));
  // 3000 + 3000 + ~2100 > 7168: the oldest went, the new entry stays.
  CHECK_FALSE(fs::exists(old1));
  CHECK(fs::exists(old2));
  CHECK(fs::exists(cache_entry_path(key)));
  CHECK(fs::exists(keep));
  CHECK(cache_stats(d).bytes <= 7168);
  REQUIRE(cache_load(key).has_value());

  // A binary larger than the limit is not stored at all.
  const ProgramCacheKey big{"big", "", "dev", "drv", "plat"};
  CHECK_FALSE(cache_store(big, std::vector<unsigned char>(8000, 1)));
  CHECK_FALSE(fs::exists(cache_entry_path(big)));

  ScopedEnv bad_limit("CLRT_CACHE_MAX_SIZE", "lots");
  CHECK_THROWS_AS(program_cache_limit(/*strict=*/true), UserError);
}

TEST_CASE("processes loading one entry at the same moment never take each other for a crash", "[cache]") {
  // The ranks of an MPI job on one machine load the same cached binary at
  // once. The load marker must hold its pid from the moment it exists: a
  // process that read it empty took the loader for a crashed one and
  // discarded a good entry (found with mpirun -np 3).
  clrt_test::TempDir dir;
  ScopedEnv env("CLRT_CACHE_DIR", dir.path().c_str());
  const ProgramCacheKey key{"race", "", "dev", "drv", "plat"};
  REQUIRE(cache_write_entry(cache_entry_path(key), key.text(), std::vector<unsigned char>(64, 1)));
  constexpr int kProcesses = 6, kRounds = 300;
  std::vector<pid_t> children;
  for (int p = 0; p < kProcesses; ++p) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      int crashes = 0;
      for (int i = 0; i < kRounds; ++i) {
        std::string note;
        if (cache_begin_load(key, &note)) cache_end_load(key, true);
        crashes += !note.empty();
      }
      ::_exit(crashes ? 1 : 0);
    }
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    CHECK((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  }
  CHECK(fs::exists(cache_entry_path(key)));
  CHECK_FALSE(fs::exists(cache_entry_path(key) + ".bad"));
  for (const auto& name : dir.entries()) CHECK(name.find(".loading") == std::string::npos);
}

// ---- a directory others can write, planted links and FIFOs -------------------

namespace {

// A pid that no process has: a child that has exited and been reaped.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

}  // namespace

TEST_CASE("a cache directory others may write holds this user's entries in a private subdirectory", "[cache][hardening]") {
  // CLRT_CACHE_DIR=/tmp-like: sticky and world-writable. Everything clrt
  // creates must be beneath a directory nobody else can enter, or another
  // user could plant a link at the next name it writes.
  clrt_test::TempDir dir;
  const fs::path shared = dir.path() / "shared";
  fs::create_directory(shared);
  REQUIRE(::chmod(shared.c_str(), 01777) == 0);
  ScopedEnv env("CLRT_CACHE_DIR", shared.c_str());
  const std::string victim = dir.write("victim", "precious");
  const ProgramCacheKey key{"shared", "", "dev", "drv", "plat"};
  // What another user would plant at the names a naive cache uses.
  fs::create_symlink(victim, shared / (key.hash() + ".bin"));
  fs::create_symlink(victim, shared / (key.hash() + ".bin.loading"));

  REQUIRE(cache_store(key, std::vector<unsigned char>(100, 3)));
  const fs::path mine = shared / ("clrt-" + std::to_string(::geteuid()));
  CHECK(cache_entry_path(key) == (mine / (key.hash() + ".bin")).string());
  struct stat st {};
  REQUIRE(::lstat(mine.c_str(), &st) == 0);
  CHECK(S_ISDIR(st.st_mode));
  CHECK((st.st_mode & 0777) == 0700);
  CHECK(st.st_uid == ::geteuid());
  REQUIRE(cache_load(key).has_value());
  std::string note;
  CHECK(cache_begin_load(key, &note));
  cache_end_load(key, true);
  CHECK(clrt_test::slurp(victim) == "precious");
  const ProgramCacheLocation loc = program_cache_location();
  CHECK(loc.shared);
  CHECK(loc.problem.empty());

  SECTION("a subdirectory someone else made, or a link in its place, is not used") {
    fs::remove_all(mine);
    const fs::path elsewhere = dir.path() / "elsewhere";
    fs::create_directory(elsewhere);
    fs::create_symlink(elsewhere, mine);
    CHECK_FALSE(cache_store(key, std::vector<unsigned char>(100, 3)));
    CHECK(fs::is_empty(elsewhere));
    CHECK_FALSE(cache_load(key).has_value());
    CHECK_FALSE(program_cache_location().problem.empty());
    fs::remove(mine);
    fs::create_directory(mine);
    REQUIRE(::chmod(mine.c_str(), 0777) == 0);  // one others may write
    CHECK_FALSE(cache_store(key, std::vector<unsigned char>(100, 3)));
    CHECK(fs::is_empty(mine));
  }
}

TEST_CASE("the cache never writes through a link at an entry's name", "[cache][hardening]") {
  clrt_test::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  fs::create_directory(cache);
  ScopedEnv env("CLRT_CACHE_DIR", cache.c_str());
  const std::string victim = dir.write("victim", "precious");
  const ProgramCacheKey key{"link", "", "dev", "drv", "plat"};
  fs::create_symlink(victim, cache / (key.hash() + ".bin"));
  CHECK_FALSE(cache_load(key).has_value());  // a link named like an entry is not one
  REQUIRE(cache_store(key, std::vector<unsigned char>(100, 4)));
  CHECK(clrt_test::slurp(victim) == "precious");
  CHECK(fs::is_regular_file(fs::symlink_status(cache / (key.hash() + ".bin"))));
  // The test API's path form does not follow a link either.
  const std::string planted = (cache / "1111111111111111.bin").string();
  fs::create_symlink(victim, planted);
  REQUIRE(cache_write_entry(planted, key.text(), std::vector<unsigned char>(8, 1)));
  CHECK(clrt_test::slurp(victim) == "precious");
}

TEST_CASE("a dangling link at a mark's name makes the cache create nothing", "[cache][hardening]") {
  clrt_test::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  fs::create_directory(cache);
  ScopedEnv env("CLRT_CACHE_DIR", cache.c_str());
  const ProgramCacheKey key{"mark", "", "dev", "drv", "plat"};
  const std::string entry = (cache / (key.hash() + ".bin")).string();
  REQUIRE(cache_write_entry(entry, key.text(), std::vector<unsigned char>(64, 1)));
  // The marker of a load that crashed (its process is gone) makes the cache
  // mark the key bad: through a planted link, that created the link's target.
  std::ofstream(entry + ".loading") << dead_pid() << "\n";
  const fs::path target = dir.path() / "created-by-clrt";
  fs::create_symlink(target, entry + ".bad");
  std::string note;
  CHECK_FALSE(cache_begin_load(key, &note));
  CHECK_FALSE(fs::exists(fs::symlink_status(target)));
  CHECK_FALSE(cache_store(key, std::vector<unsigned char>(64, 1)));  // the key stays marked
  CHECK_FALSE(fs::exists(fs::symlink_status(target)));

  // Without the link: the crashed load is found, the entry goes, the mark is
  // a regular file.
  fs::remove(entry + ".bad");
  CHECK_FALSE(cache_begin_load(key, &note));
  CHECK_THAT(note, Catch::Contains("crashed an earlier run"));
  CHECK(fs::is_regular_file(fs::symlink_status(entry + ".bad")));
  CHECK_FALSE(fs::exists(entry));

  // A dangling link as the load marker: no load, nothing created.
  const ProgramCacheKey other{"mark2", "", "dev", "drv", "plat"};
  const std::string entry2 = (cache / (other.hash() + ".bin")).string();
  REQUIRE(cache_write_entry(entry2, other.text(), std::vector<unsigned char>(64, 1)));
  const fs::path target2 = dir.path() / "created-too";
  fs::create_symlink(target2, entry2 + ".loading");
  CHECK_FALSE(cache_begin_load(other, &note));
  cache_end_load(other, true);
  CHECK_FALSE(fs::exists(fs::symlink_status(target2)));
}

TEST_CASE("a FIFO at an entry's or a marker's name never blocks a render", "[cache][hardening]") {
  // Opening a FIFO for reading blocks until a writer comes: before, one at
  // ENTRY.loading hung every render of that entry. (Were it to block again,
  // this test would hang and CTest's timeout fail it.)
  clrt_test::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  fs::create_directory(cache);
  ScopedEnv env("CLRT_CACHE_DIR", cache.c_str());
  const ProgramCacheKey key{"fifo", "", "dev", "drv", "plat"};
  const std::string entry = (cache / (key.hash() + ".bin")).string();
  REQUIRE(cache_write_entry(entry, key.text(), std::vector<unsigned char>(64, 1)));
  REQUIRE(::mkfifo((entry + ".loading").c_str(), 0600) == 0);
  std::string note;
  CHECK_FALSE(cache_begin_load(key, &note));
  CHECK(note.empty());
  CHECK(fs::exists(entry));  // not taken for a crashed load

  const ProgramCacheKey other{"fifo2", "", "dev", "drv", "plat"};
  REQUIRE(::mkfifo((cache / (other.hash() + ".bin")).c_str(), 0600) == 0);
  CHECK_FALSE(cache_load(other).has_value());
  REQUIRE(::mkfifo((cache / (other.hash() + ".bin.bad")).c_str(), 0600) == 0);
  CHECK_FALSE(cache_begin_load(other, &note));
  CHECK_FALSE(cache_store(other, std::vector<unsigned char>(64, 1)));  // a mark in any form
}

TEST_CASE("an entry that is not this user's file is not loaded", "[cache][hardening]") {
  if (::geteuid() != 0) {
    SUCCEED("needs root to give a file to another user");
    return;
  }
  clrt_test::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  fs::create_directory(cache);
  ScopedEnv env("CLRT_CACHE_DIR", cache.c_str());
  const ProgramCacheKey key{"owner", "", "dev", "drv", "plat"};
  const std::string entry = (cache / (key.hash() + ".bin")).string();
  REQUIRE(cache_write_entry(entry, key.text(), std::vector<unsigned char>(64, 1)));
  REQUIRE(cache_load(key).has_value());
  REQUIRE(::chown(entry.c_str(), 65534, 65534) == 0);
  CHECK_FALSE(cache_load(key).has_value());
}

TEST_CASE("cache info says when the cache cannot be created", "[cli][cache][hardening]") {
  clrt_test::TempDir dir;
  const std::string home = dir.write("home-is-a-file", "x");
  const clrt_test::RunResult r =
      clrt_test::run_clrt({"cache", "info"}, "env -u CLRT_CACHE_DIR -u XDG_CACHE_HOME HOME=" + clrt_test::shell_quote(home));
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("cannot be created: " + home + " is not a directory"));
  CHECK_THAT(r.out, !Catch::Contains("does not exist yet"));
  const clrt_test::RunResult c =
      clrt_test::run_clrt({"cache", "clear"}, "env -u CLRT_CACHE_DIR -u XDG_CACHE_HOME HOME=" + clrt_test::shell_quote(home));
  CHECK(c.status == 2);
  CHECK_THAT(c.err, Catch::StartsWith("clrt: error: "));
}

}  // namespace test_program_cache
