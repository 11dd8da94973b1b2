// H.264 (libx264) in MP4 through libavcodec/libavformat (FFmpeg 5.1 send/receive API),
// yuv420p tagged BT.709 limited range. The file is written under a temporary name in the
// same directory and renamed by finish(); an encoder destroyed without finish() deletes its
// temporary file, so a partial video never looks complete. The file is written with
// `+faststart` (the index, `moov`, before the media data, `mdat`) so a browser can start
// playing it before it has downloaded all of it. Not thread-safe: one thread
// encodes (render_outputs runs it on its own worker thread).
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "image/image.hpp"

namespace stiction::render {

// Codec missing, unwritable output, muxing failure (exit code 1).
class VideoError : public std::runtime_error {
 public:
  explicit VideoError(const std::string& message) : std::runtime_error(message) {}
};

struct VideoOptions {
  int width = 1280;   // even
  int height = 720;   // even
  double fps = 60.0;
  int crf = 21;
  std::string preset = "superfast";  // "ultrafast" keeps deblocking on (see open())
  // libx264 threads; 0: encoder_threads() (the cores the renderer leaves over, at least 1);
  // -1: libx264's own default.
  int threads = 0;
};

// Threads for the encoder when a renderer runs beside it: the machine's cores minus those
// llvmpipe rasterizes with (LP_NUM_THREADS, default: all cores), at least one. x264's own
// default (1.5 threads per core plus lookahead threads) oversubscribes the cores the
// renderer is using and slows both down.
int encoder_threads();

class VideoEncoder {
 public:
  // Opens `path`'s temporary sibling for writing. Throws VideoError.
  VideoEncoder(std::filesystem::path path, const VideoOptions& options);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // Encodes one frame (RGBA, the size given at construction).
  void encode(const image::Image& frame);
  // Drains the encoder, writes the trailer and renames the file to the path given at
  // construction, or to `final_path` if not empty (e.g. video.partial.mp4 after Ctrl-C).
  std::filesystem::path finish(const std::filesystem::path& final_path = {});

  long frames_written() const;
  const std::filesystem::path& temporary_path() const { return temp_; }

 private:
  struct State;
  void open(const std::string& url, const VideoOptions& options);  // the rest of the constructor
  void drain(bool flush);
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::unique_ptr<State> state_;
};

}  // namespace stiction::render
