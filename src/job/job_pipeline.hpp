// The offline job's two-thread pipeline: planned blocks, compensated by either thread, checked and written in order.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/job/joint_writer.hpp"

namespace stiffpath::job::detail {

//! One block of the job: planned samples in, their commands out.
struct JobBlock {
  enum class State { free, planned, compensating, compensated };
  std::vector<TaskSample> tasks;
  std::vector<JointCommand> commands;
  std::size_t count = 0;
  State state = State::free;
};

//! What the in-order stage accumulates for the summary (peaks of squared norms: one sqrt at the end).
struct JobTotals {
  double last_t_s = 0.0;
  std::uint64_t samples = 0;
  double deflection2 = 0.0, correction2 = 0.0, force2 = 0.0;
  double joint_velocity = 0.0, joint_acceleration = 0.0;
  std::uint64_t outside_grid = 0;
};

//! The calling thread plans blocks of samples (only it touches the G-code) and hands them over; a
//! second thread checks and writes the compensated blocks strictly in order (summary, first refusal,
//! writer). Compensation (Compensator::step, const and thread-safe) is done by whichever thread has
//! nothing more urgent: the writing thread when the oldest block is not ready yet, the planning
//! thread when all blocks are in use. So the work balances itself over two cores, whether writing
//! (CSV) or compensating (binary) dominates. At most `blocks` blocks exist: memory is flat.
//!
//! After the first refused command or a writer error nothing more is compensated or written, and
//! acquire() returns null so that planning stops too. Destroying the pipeline stops its thread.
class JobPipeline {
 public:
  static constexpr std::size_t kBlockSamples = 1024;  //!< ≈ 0.5 s at 2 kHz
  static constexpr std::size_t kBlocks = 8;            //!< ≈ 2 MB in all

  JobPipeline(const compensation::Compensator& compensator, JointWriter* writer, std::size_t block_samples = kBlockSamples,
              std::size_t blocks = kBlocks);
  ~JobPipeline();
  JobPipeline(const JobPipeline&) = delete;
  JobPipeline& operator=(const JobPipeline&) = delete;

  //! A free block to plan into (its `tasks` sized to the block), or null once the pipeline stopped.
  //! While every block is in use, the calling thread compensates one instead of waiting.
  JobBlock* acquire();
  //! Hands over `block` with its first `count` tasks planned.
  void release(JobBlock* block, std::size_t count);
  //! No more blocks: helps until everything handed over is written (or the pipeline stopped) and
  //! joins the thread.
  void close();

  //! After close(): the first refused command, if any.
  [[nodiscard]] const std::optional<JointCommand>& refusal() const noexcept { return refusal_; }
  //! After close(): what the writer threw, if anything.
  [[nodiscard]] std::exception_ptr writer_error() const noexcept { return writer_error_; }
  [[nodiscard]] const JobTotals& totals() const noexcept { return totals_; }

 private:
  // A planned block, marked compensating (lock held): the writing thread takes the oldest (it needs
  // it next), the planning thread the newest (so that it rarely holds up the writing thread).
  JobBlock* claim_planned(bool oldest_first);
  void compensate(JobBlock& block);    // without the lock
  bool check_and_write(JobBlock& block);  // in order, on the thread; false: stop
  void run();                          // the second thread
  void stop() noexcept;

  const compensation::Compensator& compensator_;
  JointWriter* writer_;
  std::vector<JobBlock> ring_;
  std::uint64_t planned_ = 0;   // blocks handed over so far; block n lives in ring_[n % size]
  std::uint64_t written_ = 0;   // blocks checked and written so far
  bool closed_ = false;         // no more blocks will come
  bool stopped_ = false;        // a refusal, a writer error or destruction: stop all work
  std::optional<JointCommand> refusal_;
  std::exception_ptr writer_error_;
  JobTotals totals_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::thread thread_;
};

}  // namespace stiffpath::job::detail
