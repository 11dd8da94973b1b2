#include "services/owned_files.hpp"

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "scene/toml_reader.hpp"
#include "services/output_dir.hpp"

namespace stiction::services {
namespace fs = std::filesystem;

bool is_inside(const fs::path& relative) {
  if (relative.empty() || relative.is_absolute() || relative.has_root_name()) return false;
  for (const auto& part : relative) {
    if (part == ".." || part == "." || part.empty()) return false;
  }
  return true;
}

bool is_temporary_name(const std::string& name) {
  return (name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos) ||
         name.find(".tmp.") != std::string::npos;
}

bool is_frame_name(const std::string& name) {
  return name.size() == 10 && name.ends_with(".png") &&
         std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
}

bool is_plot_name(const std::string& name) {
  return name.size() > 4 && (name.ends_with(".png") || name.ends_with(".svg") || name.ends_with(".pdf"));
}

void remove_owned_file(const fs::path& path) {
  std::error_code ec;
  // symlink_status: a link is judged (and removed) as a link, never through it.
  const fs::file_status st = fs::symlink_status(path, ec);
  if (ec || fs::is_directory(st)) return;
  fs::remove(path, ec);
}

void remove_temporaries(const fs::path& dir, const std::vector<std::string>& prefixes) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return;
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!is_temporary_name(name)) continue;
    const bool named = prefixes.empty() ||
                       std::any_of(prefixes.begin(), prefixes.end(),
                                   [&](const std::string& p) { return name.rfind(p, 0) == 0; });
    if (named) doomed.push_back(entry.path());
  }
  for (const fs::path& p : doomed) remove_owned_file(p);
}

void make_real_directories(const fs::path& dir, const fs::path& relative) {
  fs::path at = dir;
  for (const auto& part : relative) {
    at /= part;
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(at, ec);
    if (!fs::exists(st)) {
      fs::create_directory(at, ec);
      if (ec) throw io::IoError(at.string() + ": cannot create the directory: " + ec.message());
    } else if (!fs::is_directory(st)) {
      throw io::IoError(at.string() + (fs::is_symlink(st) ? " is a symbolic link" : " is not a directory") +
                        "; nothing is written through it");
    }
  }
}

std::optional<std::vector<std::string>> read_output_manifest(const fs::path& dir) {
  for (const char* name : {kOutputManifest, "summary.json"}) {
    const fs::path path = dir / name;
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(path, ec))) continue;
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (!j.is_object() || !j.contains("files") || !j["files"].is_array()) continue;
    std::vector<std::string> files;
    for (const auto& f : j["files"]) {
      if (f.is_string() && is_inside(fs::path(f.get<std::string>()))) files.push_back(f.get<std::string>());
    }
    return files;
  }
  return std::nullopt;
}

void write_output_manifest(const fs::path& dir, const std::vector<std::string>& files) {
  nlohmann::ordered_json j;
  j["stiction_output"] = 1;
  j["files"] = files;
  io::write_file_atomically(dir / kOutputManifest, j.dump(1) + "\n");
}

bool regular_file_or_absent(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) return false;
  if (!fs::is_regular_file(st)) {
    throw scene::InputError("error: " + path.string() +
                            ": not a regular file (a FIFO, device, socket or directory); only "
                            "regular files are read");
  }
  return true;
}

}  // namespace stiction::services
