#include "services/step_check_cache.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "io/atomic_file.hpp"
#include "services/text_hash.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

fs::path cache_directory() {
  if (const char* dir = std::getenv("STICTION_CACHE_DIR"); dir != nullptr && *dir != '\0') {
    if (std::string(dir) == "off") return {};
    return fs::path(dir);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg == '/') {
    return fs::path(xdg) / "stiction";
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home == '/') {
    return fs::path(home) / ".cache" / "stiction";
  }
  return {};
}

// The file holding this code: the `stiction` executable, or the Python extension that links
// the services (there /proc/self/exe is the interpreter, which a rebuild does not change).
std::string code_file() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<const void*>(&code_file), &info) != 0 && info.dli_fname != nullptr &&
      info.dli_fname[0] == '/') {
    return info.dli_fname;
  }
  return "/proc/self/exe";
}

// The running program: a rebuilt binary has another path, size or modification time.
std::string program_identity() {
  const std::string file = code_file();
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return "unknown program";
  return file + ":" + std::to_string(st.st_size) + ":" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec);
}

}  // namespace

StepCheckCache::StepCheckCache(std::string key) : key_(program_identity() + "\n" + std::move(key)) {
  const fs::path dir = cache_directory();
  if (!dir.empty()) file_ = (dir / "step_check" / (text_hash(key_) + ".json")).string();
}

std::optional<nlohmann::json> StepCheckCache::load() const {
  if (file_.empty()) return std::nullopt;
  std::ifstream in(file_, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json entry = nlohmann::json::parse(text.str(), nullptr, false);
  if (entry.is_discarded() || !entry.is_object() || !entry.contains("key") ||
      !entry.contains("value") || entry["key"] != key_) {
    return std::nullopt;
  }
  return entry["value"];
}

void StepCheckCache::store(const nlohmann::json& value) const {
  if (file_.empty()) return;
  try {
    std::error_code ec;
    fs::create_directories(fs::path(file_).parent_path(), ec);
    if (ec) return;
    const nlohmann::json entry{{"key", key_}, {"value", value}};
    io::write_file_atomically(file_, entry.dump());
  } catch (const std::exception&) {
    // A cache that cannot be written only costs time.
  }
}

}  // namespace stiction::services
