#include "io/block_pipe.hpp"

#include <algorithm>
#include <cstring>
#include <ctime>
#include <stdexcept>

namespace stiction::io {

namespace {
double thread_cpu_seconds() {
  timespec ts{};
  if (::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

BlockPipe::BlockPipe(std::size_t columns, Consumer consumer, std::size_t blocks,
                     std::size_t block_rows)
    : columns_(columns),
      block_rows_(std::max<std::size_t>(
          std::min(block_rows, kBlockBytes / (sizeof(double) * std::max<std::size_t>(columns, 1))),
          1)),
      consumer_(std::move(consumer)),
      blocks_(std::max<std::size_t>(blocks, 2), std::vector<double>(block_rows_ * columns)),
      counts_(blocks_.size(), 0),
      thread_([this] { run(); }) {}

BlockPipe::~BlockPipe() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    abandon_ = true;
  }
  ready_or_end_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void BlockPipe::rethrow_if_failed_locked() {
  if (error_) std::rethrow_exception(error_);
}

void BlockPipe::hand_over_locked() {
  counts_[filling_] = fill_count_;
  fill_count_ = 0;
  ++ready_;
  filling_ = (filling_ + 1) % blocks_.size();
}

void BlockPipe::push(const double* rows, std::size_t count) {
  if (closed_) throw std::logic_error("BlockPipe: push after close");
  while (count > 0) {
    std::unique_lock<std::mutex> lock(mutex_);
    rethrow_if_failed_locked();
    // The block being filled is free while fewer than all blocks are handed over.
    room_.wait(lock, [&] { return ready_ < blocks_.size() || error_; });
    rethrow_if_failed_locked();
    const std::size_t at = fill_count_;
    const std::size_t n = std::min(count, block_rows_ - at);
    lock.unlock();
    // Only this thread touches the block being filled: copy without the lock.
    std::memcpy(blocks_[filling_].data() + at * columns_, rows, n * columns_ * sizeof(double));
    fill_count_ = at + n;
    rows += n * columns_;
    count -= n;
    if (at + n == block_rows_) {
      lock.lock();
      hand_over_locked();
      lock.unlock();
      ready_or_end_.notify_one();
    }
  }
}

void BlockPipe::close() {
  if (closed_) return;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!error_ && fill_count_ > 0) {
      room_.wait(lock, [&] { return ready_ < blocks_.size() || error_; });
      if (!error_) hand_over_locked();
    }
    closing_ = true;
  }
  ready_or_end_.notify_one();
  thread_.join();
  closed_ = true;
  if (error_) std::rethrow_exception(error_);
}

void BlockPipe::run() {
  const double start = thread_cpu_seconds();
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    ready_or_end_.wait(lock, [&] { return abandon_ || ready_ > 0 || closing_; });
    if (abandon_ || ready_ == 0) break;  // abandoned, or closed with every block taken
    const std::size_t b = next_;
    lock.unlock();
    bool failed = false;
    try {
      consumer_(blocks_[b].data(), counts_[b]);
    } catch (...) {
      failed = true;
      lock.lock();
      error_ = std::current_exception();
    }
    if (!failed) lock.lock();
    next_ = (next_ + 1) % blocks_.size();
    --ready_;
    room_.notify_one();
    if (failed) break;
  }
  writer_cpu_seconds_ = thread_cpu_seconds() - start;
}

}  // namespace stiction::io
