// JobPipeline: a ring of sample blocks shared by the planning thread and the checking/writing thread.
#include "job_pipeline.hpp"

#include <algorithm>

namespace stiffpath::job::detail {

JobPipeline::JobPipeline(const compensation::Compensator& compensator, JointWriter* writer, std::size_t block_samples,
                         std::size_t blocks)
    : compensator_(compensator), writer_(writer), ring_(std::max<std::size_t>(blocks, 2)) {
  for (auto& block : ring_) {
    block.tasks.resize(std::max<std::size_t>(block_samples, 1));
    block.commands.resize(block.tasks.size());
  }
  thread_ = std::thread([this] { run(); });
}

JobPipeline::~JobPipeline() { stop(); }

JobBlock* JobPipeline::claim_planned(bool oldest_first) {
  for (std::uint64_t k = 0; k < planned_ - written_; ++k) {
    JobBlock& block = ring_[(oldest_first ? written_ + k : planned_ - 1 - k) % ring_.size()];
    if (block.state == JobBlock::State::planned) {
      block.state = JobBlock::State::compensating;
      return &block;
    }
  }
  return nullptr;
}

void JobPipeline::compensate(JobBlock& block) {
  for (std::size_t k = 0; k < block.count; ++k) block.commands[k] = compensator_.step(block.tasks[k]);
}

JobBlock* JobPipeline::acquire() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (stopped_) return nullptr;
    if (planned_ - written_ < ring_.size()) return &ring_[planned_ % ring_.size()];
    if (JobBlock* block = claim_planned(false)) {  // every block in use: compensate one rather than wait
      lock.unlock();
      compensate(*block);
      lock.lock();
      block->state = JobBlock::State::compensated;
      changed_.notify_all();
      continue;
    }
    changed_.wait(lock);
  }
}

void JobPipeline::release(JobBlock* block, std::size_t count) {
  std::lock_guard lock(mutex_);
  block->count = count;
  block->state = JobBlock::State::planned;
  ++planned_;
  changed_.notify_all();
}

void JobPipeline::close() {
  std::unique_lock lock(mutex_);
  closed_ = true;
  changed_.notify_all();
  while (!stopped_ && written_ < planned_) {
    if (JobBlock* block = claim_planned(false)) {
      lock.unlock();
      compensate(*block);
      lock.lock();
      block->state = JobBlock::State::compensated;
      changed_.notify_all();
    } else {
      changed_.wait(lock);
    }
  }
  lock.unlock();
  if (thread_.joinable()) thread_.join();
}

void JobPipeline::stop() noexcept {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
}

bool JobPipeline::check_and_write(JobBlock& block) {
  for (std::size_t k = 0; k < block.count; ++k) {
    const JointCommand& c = block.commands[k];
    if (c.status != compensation::Status::ok) {
      refusal_ = c;
      return false;
    }
    JobTotals& t = totals_;
    t.last_t_s = c.t_s;
    t.deflection2 = std::max(t.deflection2, c.deflection_m.squaredNorm());
    t.correction2 = std::max(t.correction2, (c.command_m - c.target_m).squaredNorm());
    t.force2 = std::max(t.force2, c.force_N.squaredNorm());
    t.joint_velocity = std::max(t.joint_velocity, c.qd_rad_s.cwiseAbs().maxCoeff());
    t.joint_acceleration = std::max(t.joint_acceleration, c.qdd_rad_s2.cwiseAbs().maxCoeff());
    t.outside_grid += c.outside_grid ? 1 : 0;
    ++t.samples;
    if (writer_) {
      try {
        writer_->write(c);
      } catch (...) {
        writer_error_ = std::current_exception();
        return false;
      }
    }
  }
  return true;
}

void JobPipeline::run() {
  std::unique_lock lock(mutex_);
  while (!stopped_) {
    JobBlock& oldest = ring_[written_ % ring_.size()];
    if (written_ < planned_ && oldest.state == JobBlock::State::compensated) {  // in order: check and write
      lock.unlock();
      const bool go_on = check_and_write(oldest);
      lock.lock();
      oldest.state = JobBlock::State::free;
      ++written_;
      if (!go_on) stopped_ = true;
      changed_.notify_all();
    } else if (JobBlock* block = claim_planned(true)) {  // nothing to write yet: compensate
      lock.unlock();
      compensate(*block);
      lock.lock();
      block->state = JobBlock::State::compensated;
    } else if (closed_ && written_ == planned_) {
      return;
    } else {
      changed_.wait(lock);
    }
  }
}

}  // namespace stiffpath::job::detail
