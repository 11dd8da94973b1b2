// Rows handed from the simulating thread to a writer thread (issue 36 item 4): the producer
// copies rows into one of a fixed ring of blocks and goes back to the physics; the writer
// thread hands full blocks to a consumer (CsvStream's: format and write), so formatting and
// writing overlap the simulation. Memory: blocks x block_rows x columns doubles, fixed, with
// block_rows lowered to keep a block within kBlockBytes (never below one row).
//
// Failure policy: an exception thrown by the consumer stops the writer; the producer sees it
// (the same exception, rethrown) at its next push() or at close(), so a write error
// surfaces in the thread that owns the run. The destructor without close() (an error or an
// interrupt elsewhere) stops the writer and drops the rows not yet consumed; it never
// throws. The consumer runs on the writer thread only, until close() returns.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace stiction::io {

class BlockPipe {
 public:
  using Consumer = std::function<void(const double* rows, std::size_t count)>;
  static constexpr std::size_t kBlocks = 16;
  static constexpr std::size_t kBlockRows = 256;
  // A block holds at most this many bytes: a scene of 120000 columns (40000 springs) took a
  // 3.9 GB ring at 256 rows a block, whose first touch was most of its run.
  static constexpr std::size_t kBlockBytes = 256 * 1024;

  BlockPipe(std::size_t columns, Consumer consumer, std::size_t blocks = kBlocks,
            std::size_t block_rows = kBlockRows);
  ~BlockPipe();
  BlockPipe(const BlockPipe&) = delete;
  BlockPipe& operator=(const BlockPipe&) = delete;

  // Copies `count` rows of columns() doubles; waits while every block is full. Rethrows the
  // consumer's exception, if it threw.
  void push(const double* rows, std::size_t count);
  // Hands over the last, partly filled block, waits until the consumer has taken every row
  // and stops the writer thread. Rethrows the consumer's exception. Idempotent.
  void close();
  std::size_t columns() const { return columns_; }
  // Seconds of CPU time the writer thread has used (read after close()).
  double writer_cpu_seconds() const { return writer_cpu_seconds_; }

 private:
  void run();
  void hand_over_locked();  // the block being filled becomes ready (mutex held)
  void rethrow_if_failed_locked();

  const std::size_t columns_;
  const std::size_t block_rows_;
  Consumer consumer_;
  std::vector<std::vector<double>> blocks_;
  std::vector<std::size_t> counts_;  // rows in each block handed over
  std::size_t filling_ = 0;          // the block the producer writes into
  std::size_t fill_count_ = 0;       // rows in it (the producer's alone)
  std::size_t next_ = 0;             // the next ready block the writer takes
  std::size_t ready_ = 0;            // blocks handed over, not yet consumed (incl. one in use)
  bool closing_ = false;             // no more blocks: the writer ends once ready_ == 0
  bool abandon_ = false;             // the writer ends now
  bool closed_ = false;
  std::exception_ptr error_;
  double writer_cpu_seconds_ = 0.0;
  std::mutex mutex_;
  std::condition_variable ready_or_end_;  // the writer waits on it
  std::condition_variable room_;          // the producer waits on it
  std::thread thread_;                    // last: starts after everything above is built
};

}  // namespace stiction::io
