// Encodes and writes frames on a thread of its own, so rendering (on the caller's thread)
// and encoding overlap: render_outputs (one run) and compare_video (runs side by side) both
// hand their frames to it. push() blocks while `capacity` frames wait, so memory stays
// bounded and the renderer is paced by the encoder when it is slower.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "image/image.hpp"
#include "render/render_outputs.hpp"
#include "render/time_warp.hpp"
#include "render/video_encoder.hpp"

namespace stiction::render {

class FrameWorker {
 public:
  // `encoder` may be null (frames only); `frames_dir`: write frames/NNNNNN.png there.
  FrameWorker(VideoEncoder* encoder, std::optional<std::filesystem::path> frames_dir);
  ~FrameWorker();
  FrameWorker(const FrameWorker&) = delete;
  FrameWorker& operator=(const FrameWorker&) = delete;

  void push(int index, image::Image&& frame);
  // Takes back an image buffer that the worker is done with (avoids reallocation).
  bool recycle(image::Image& into);
  // Waits for the queue to empty and the thread to end.
  void stop();
  // Rethrows the worker's error, if it had one.
  void rethrow();
  // The worker thread's CPU time; valid after stop().
  double cpu_seconds() const { return cpu_seconds_; }

 private:
  static constexpr std::size_t kCapacity = 3;
  struct Job {
    int index;
    image::Image frame;
  };
  void run();

  VideoEncoder* encoder_;
  std::optional<std::filesystem::path> frames_dir_;
  std::mutex mutex_;
  std::condition_variable ready_, space_;
  std::deque<Job> queue_;
  std::vector<image::Image> spare_;
  std::exception_ptr error_;
  bool done_ = false;
  double cpu_seconds_ = 0.0;
  std::thread thread_;  // last: starts after everything above is built
};

// The encoder's options from a video's [render] settings.
VideoOptions video_options(const RenderSettings& settings);

// The loop both videos share (`run`'s video.mp4, `compare --video`'s compare.mp4): draws the
// frame of each time with `draw` and hands it to a worker over `encoder` (and `frames_dir`),
// reporting progress, until done or *cancel. Sets result.frames, .interrupted and
// .worker_cpu_seconds; rethrows the worker's error.
void render_frame_sequence(const std::vector<FrameTime>& times,
                           const std::function<void(const FrameTime&, image::Image&)>& draw,
                           VideoEncoder* encoder, std::optional<std::filesystem::path> frames_dir,
                           const std::atomic<bool>* cancel,
                           const std::function<void(const RenderProgress&)>& progress,
                           std::chrono::steady_clock::time_point started, RenderResult& result);

}  // namespace stiction::render
