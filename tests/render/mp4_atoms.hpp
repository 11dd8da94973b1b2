// The top-level boxes ("atoms") of an MP4 file, in file order: enough to check that the
// index (`moov`) comes before the media data (`mdat`), i.e. the file is web-streamable.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace stiction::render::testing {

struct Mp4Box {
  std::string type;
  std::uint64_t offset = 0;
  std::uint64_t size = 0;
};

// Throws std::runtime_error on a truncated or malformed box header.
inline std::vector<Mp4Box> mp4_top_level_boxes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  const std::uint64_t file_size = std::filesystem::file_size(path);
  std::vector<Mp4Box> boxes;
  std::uint64_t offset = 0;
  auto be = [](const unsigned char* p, int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
    return v;
  };
  while (offset < file_size) {
    unsigned char header[16];
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(reinterpret_cast<char*>(header), 8))
      throw std::runtime_error("truncated box header");
    Mp4Box box;
    box.offset = offset;
    box.size = be(header, 4);
    box.type.assign(reinterpret_cast<const char*>(header + 4), 4);
    if (box.size == 1) {  // 64-bit size follows the type
      if (!in.read(reinterpret_cast<char*>(header + 8), 8))
        throw std::runtime_error("truncated box size");
      box.size = be(header + 8, 8);
    } else if (box.size == 0) {  // extends to the end of the file
      box.size = file_size - offset;
    }
    if (box.size < 8 || offset + box.size > file_size) {
      throw std::runtime_error("bad size of box '" + box.type + "' at " + std::to_string(offset));
    }
    boxes.push_back(box);
    offset += box.size;
  }
  return boxes;
}

inline int box_index(const std::vector<Mp4Box>& boxes, const std::string& type) {
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].type == type) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace stiction::render::testing
