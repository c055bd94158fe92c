// image_io.cpp - finds and loads the imaging module (see image_io.hpp).
#include "image/image_io.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "util/error.hpp"

#ifndef CLRT_IMAGEIO_BUILD_DIR
#define CLRT_IMAGEIO_BUILD_DIR ""
#endif
// The module's install directory relative to the executable's (CMakeLists.txt,
// "install"): an installed tree finds it wherever its prefix is moved.
#ifndef CLRT_IMAGEIO_FROM_BIN
#define CLRT_IMAGEIO_FROM_BIN ""
#endif

namespace clrt {
namespace imageio {

namespace {

constexpr const char* kFileName = "clrt_imageio.so";

std::atomic<bool> g_loaded{false};

// set_library_location(): the library's folder ("" in the clrt binary) and
// the module's place relative to it.
std::mutex g_library_mutex;
std::string g_library_dir, g_module_from_library;

std::string executable_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

std::string where_looked(const std::vector<std::string>& candidates) {
  std::string s;
  for (const auto& c : candidates) s += (s.empty() ? "" : ", ") + c;
  return s;
}

// Why code at `path` could be someone else's: the file or its folder
// belongs to another user than this one or root, or others may write it.
// "" when neither holds.
std::string planted_risk(const std::string& path) {
  const std::filesystem::path p(path);
  for (const std::string& f : {path, p.parent_path().empty() ? std::string(".") : p.parent_path().string()}) {
    struct stat st {};
    if (::stat(f.c_str(), &st) != 0) return f + ": " + std::strerror(errno);
    if (st.st_uid != 0 && st.st_uid != ::geteuid()) return f + " belongs to another user";
    if (st.st_mode & (S_IWGRP | S_IWOTH)) return f + " may be written by others";
  }
  return "";
}

// The first candidate that exists, or UserError naming every place looked.
// One that exists but could have been planted is refused, saying why (the
// module is code clrt runs).
std::string find_module() {
  const std::vector<std::string> candidates = module_candidates();
  for (const auto& c : candidates) {
    if (::access(c.c_str(), R_OK) != 0) continue;
    if (std::getenv("CLRT_IMAGEIO_MODULE") == nullptr || !*std::getenv("CLRT_IMAGEIO_MODULE")) {
      const std::string risk = planted_risk(c);
      if (!risk.empty())
        throw UserError("the imaging module " + c + " is not loaded: " + risk +
                        " (name a module you trust with CLRT_IMAGEIO_MODULE)");
    }
    return c;
  }
  throw UserError("the imaging module " + std::string(kFileName) +
                  " (OpenImageIO, needed to read and write images) was not found (looked for " +
                  where_looked(candidates) + "); build the target clrt_imageio, keep it beside the clrt binary, or " +
                  "name it with CLRT_IMAGEIO_MODULE");
}

Module* load() {
  const std::string path = find_module();
  // RTLD_NOW: an unresolved symbol is an error here, not a crash later.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* err = ::dlerror();
    throw UserError("cannot load the imaging module " + path + ": " + (err ? err : "unknown error"));
  }
  using Entry = Module* (*)(int);
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, kImageIoEntry));
  Module* m = entry ? entry(kImageIoAbi) : nullptr;
  if (!m)
    throw UserError(path + " is not a clrt imaging module of this build (interface " + std::to_string(kImageIoAbi) +
                    "); rebuild the target clrt_imageio");
  // Never unloaded: OpenImageIO keeps threads and caches to the end.
  return m;
}

}  // namespace

std::vector<std::string> module_candidates() {
  const char* env = std::getenv("CLRT_IMAGEIO_MODULE");
  if (env && *env) return {env};
  std::vector<std::string> out;
  const std::string build_dir = CLRT_IMAGEIO_BUILD_DIR;
  const auto in_build_dir = [&](const std::string& dir) {
    return !build_dir.empty() && !dir.empty() && dir.rfind(build_dir + "/", 0) == 0;
  };
  std::string code_dir;  // the folder of the file that holds this code
  {
    std::lock_guard<std::mutex> lock(g_library_mutex);
    code_dir = g_library_dir;
    // (A library in the build tree has no installed tree around it.)
    if (!code_dir.empty() && !g_module_from_library.empty() && !in_build_dir(code_dir))
      out.push_back((std::filesystem::path(code_dir) / g_module_from_library / kFileName).lexically_normal().string());
  }
  if (code_dir.empty()) {
    code_dir = executable_dir();
    if (!code_dir.empty()) out.push_back(code_dir + "/" + kFileName);
    const std::string from_bin = CLRT_IMAGEIO_FROM_BIN;
    if (!code_dir.empty() && !from_bin.empty())
      out.push_back((std::filesystem::path(code_dir) / from_bin / kFileName).lexically_normal().string());
  }
  // The build tree's module only for a binary (or library) inside that tree
  // (a test or benchmark in a folder of it): a copied or installed clrt
  // never loads a module from a build folder, which anyone may recreate once
  // it is gone.
  if (in_build_dir(code_dir)) out.push_back(build_dir + "/" + kFileName);
  return out;
}

void set_library_location(const std::string& library_dir, const std::string& module_from_library) {
  std::lock_guard<std::mutex> lock(g_library_mutex);
  g_library_dir = library_dir;
  g_module_from_library = module_from_library;
}

void check_module_present() {
  if (!g_loaded.load()) (void)find_module();
}

Module& module() {
  // A failed load is remembered and reported the same way on every call.
  static std::once_flag once;
  static Module* m = nullptr;
  static std::string error;
  std::call_once(once, [] {
    try {
      m = load();
      g_loaded.store(true);
    } catch (const UserError& e) {
      error = e.what();
    }
  });
  if (!m) throw UserError(error);
  return *m;
}

bool module_loaded() {
  return g_loaded.load();
}

}  // namespace imageio
}  // namespace clrt
