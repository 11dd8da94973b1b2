#include "services/output_dir.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "io/atomic_file.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

// A relative path inside the directory, no "..", no absolute part: what an earlier
// summary.json may name for removal (the file could have been edited by anyone).
bool is_inside(const fs::path& relative) {
  if (relative.empty() || relative.is_absolute()) return false;
  for (const auto& part : relative) {
    if (part == ".." || part == ".") return false;
  }
  return true;
}

bool is_temporary(const std::string& name) {
  return (name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos) ||
         name.find(".tmp.") != std::string::npos;
}

bool is_frame(const std::string& name) {  // NNNNNN.png
  return name.size() == 10 && name.ends_with(".png") &&
         std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
}

bool is_plot(const std::string& name) {
  return name.size() > 4 && (name.ends_with(".png") || name.ends_with(".svg") || name.ends_with(".pdf"));
}

bool run_output(const std::string& dir, const std::string& name) {
  if (is_temporary(name)) return true;
  if (dir.empty()) {
    return name == "trajectory.csv" || name == "summary.json" || name == "video.mp4" ||
           name == "video.partial.mp4";
  }
  if (dir == "frames") return is_frame(name);
  if (dir == "plots") return is_plot(name);
  return false;
}

void remove_entry(const fs::path& p) {
  std::error_code ec;
  // symlink_status: a link is judged (and removed) as a link, never through it.
  const fs::file_status st = fs::symlink_status(p, ec);
  if (ec || fs::is_directory(st)) return;
  fs::remove(p, ec);
}

}  // namespace

OutputDirectory::OutputDirectory(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw io::IoError(dir_.string() + ": cannot create the output directory: " + ec.message());
  // The lock is on the directory itself: no lock file to leave behind, and nothing a
  // planted symlink could redirect.
  lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0) {
    throw io::IoError(dir_.string() + ": cannot open the output directory: " + std::strerror(errno));
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw io::IoError(dir_.string() + ": another stiction run is writing into this directory "
                        "(it holds its lock); wait for it or choose another --out");
    }
    throw io::IoError(dir_.string() + ": cannot lock the output directory: " + std::strerror(error));
  }
  remove_earlier_outputs();
}

OutputDirectory::~OutputDirectory() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock
}

void OutputDirectory::remove_earlier_outputs() {
  // What the last complete run said it wrote.
  try {
    std::ifstream in(dir_ / "summary.json");
    if (in) {
      const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
      if (summary.is_object() && summary.contains("files") && summary["files"].is_array()) {
        for (const auto& f : summary["files"]) {
          if (f.is_string() && is_inside(fs::path(f.get<std::string>()))) {
            remove_entry(dir_ / f.get<std::string>());
          }
        }
      }
    }
  } catch (const std::exception&) {
    // An unreadable summary names nothing: the known names below still go.
  }
  for (const char* sub : {"", "plots", "frames"}) {
    const fs::path d = dir_ / sub;
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(d, ec))) continue;
    std::vector<fs::path> doomed;
    for (const auto& entry : fs::directory_iterator(d, ec)) {
      if (run_output(sub, entry.path().filename().string())) doomed.push_back(entry.path());
    }
    for (const fs::path& p : doomed) remove_entry(p);
    if (*sub != '\0') fs::remove(d, ec);  // only if now empty
  }
}

void OutputDirectory::wrote(const fs::path& file) {
  // Callers pass paths built as dir / name; anything else is kept as given.
  fs::path relative = file.lexically_relative(dir_);
  if (relative.empty() || *relative.begin() == "..") relative = file;
  const std::string name = relative.generic_string();
  if (std::find(files_.begin(), files_.end(), name) == files_.end()) files_.push_back(name);
}

nlohmann::ordered_json OutputDirectory::files() const {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const std::string& f : files_) list.push_back(f);
  return list;
}

}  // namespace stiction::services
