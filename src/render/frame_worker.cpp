#include "render/frame_worker.hpp"

#include <cstdio>
#include <ctime>

#include "image/png.hpp"
#include "render/video_encoder.hpp"

namespace stiction::render {
namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

FrameWorker::FrameWorker(VideoEncoder* encoder, std::optional<std::filesystem::path> frames_dir)
    : encoder_(encoder), frames_dir_(std::move(frames_dir)), thread_([this] { run(); }) {}

FrameWorker::~FrameWorker() { stop(); }

void FrameWorker::push(int index, image::Image&& frame) {
  std::unique_lock lock(mutex_);
  space_.wait(lock, [&] { return queue_.size() < kCapacity || error_; });
  if (error_) std::rethrow_exception(error_);
  queue_.push_back({index, std::move(frame)});
  ready_.notify_one();
}

bool FrameWorker::recycle(image::Image& into) {
  std::lock_guard lock(mutex_);
  if (spare_.empty()) return false;
  into = std::move(spare_.back());
  spare_.pop_back();
  return true;
}

void FrameWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    done_ = true;
    ready_.notify_one();
  }
  if (thread_.joinable()) thread_.join();
}

void FrameWorker::rethrow() {
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void FrameWorker::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [&] { return !queue_.empty() || done_; });
      if (queue_.empty()) {
        cpu_seconds_ = thread_cpu_seconds();
        return;
      }
      job = std::move(queue_.front());
      queue_.pop_front();
      space_.notify_one();
    }
    try {
      if (encoder_) encoder_->encode(job.frame);
      if (frames_dir_) {
        char name[32];
        std::snprintf(name, sizeof name, "%06d.png", job.index);
        image::write_png(*frames_dir_ / name, job.frame, image::PngSpeed::fast);
      }
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      space_.notify_all();
      return;
    }
    std::lock_guard lock(mutex_);
    if (spare_.size() < kCapacity) spare_.push_back(std::move(job.frame));
  }
}

VideoOptions video_options(const RenderSettings& settings) {
  VideoOptions v;
  v.width = settings.width;
  v.height = settings.height;
  v.fps = settings.fps;
  v.crf = settings.crf;
  v.preset = settings.preset;
  v.threads = settings.encoder_threads;
  return v;
}

void render_frame_sequence(const std::vector<FrameTime>& times,
                           const std::function<void(const FrameTime&, image::Image&)>& draw,
                           VideoEncoder* encoder, std::optional<std::filesystem::path> frames_dir,
                           const std::atomic<bool>* cancel,
                           const std::function<void(const RenderProgress&)>& progress,
                           std::chrono::steady_clock::time_point started, RenderResult& result) {
  const int count = static_cast<int>(times.size());
  FrameWorker worker(encoder, std::move(frames_dir));
  image::Image frame;
  for (int i = 0; i < count; ++i) {
    if (cancel && cancel->load()) {
      result.interrupted = true;
      break;
    }
    worker.recycle(frame);
    draw(times[static_cast<std::size_t>(i)], frame);
    worker.push(i, std::move(frame));
    frame = image::Image();
    result.frames = i + 1;
    if (progress) {
      RenderProgress p;
      p.frames_done = i + 1;
      p.frame_count = count;
      p.elapsed_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      p.frames_per_second = p.elapsed_seconds > 0.0 ? p.frames_done / p.elapsed_seconds : 0.0;
      p.eta_seconds =
          p.frames_per_second > 0.0 ? (count - p.frames_done) / p.frames_per_second : 0.0;
      progress(p);
    }
  }
  worker.stop();
  worker.rethrow();
  result.worker_cpu_seconds = worker.cpu_seconds();
}

}  // namespace stiction::render
