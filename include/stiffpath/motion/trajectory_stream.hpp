// The whole motion pipeline for one G-code program: reader → corner blender → planner → sampler.
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/motion/corner_blend.hpp"
#include "stiffpath/motion/gcode_reader.hpp"
#include "stiffpath/motion/planner.hpp"
#include "stiffpath/motion/sampler.hpp"
#include "stiffpath/motion/trajectory.hpp"

namespace stiffpath::motion {

//! Everything that shapes a planned program. Documented defaults throughout.
struct PlanOptions {
  GcodeOptions gcode;                       //!< work offset, start position, default path mode
  MotionLimits limits;                      //!< v, a, j (defaults: 2 m/s, 5 g, 5 g / 5 ms)
  PlannerOptions planner;                   //!< junction rules, look-ahead bound
  double rate_hz = default_sample_rate_hz;  //!< sampling rate (Hz)
};

//! G-code in, samples out, one at a time: the file is read line by line and segments are released
//! by the look-ahead as soon as their timing is final, so memory stays flat however long the job
//! is (bounded by the look-ahead window; see PlannerOptions::max_lookahead_segments). Errors in the
//! program are thrown as stiffpath::Error "file:line:column: …" when the reader reaches them.
class TrajectoryStream final : public SampleSource {
 public:
  explicit TrajectoryStream(const std::filesystem::path& gcode, const PlanOptions& options = {});
  TrajectoryStream(std::istream& in, std::string label, const PlanOptions& options = {});
  ~TrajectoryStream() override;
  TrajectoryStream(const TrajectoryStream&) = delete;
  TrajectoryStream& operator=(const TrajectoryStream&) = delete;

  std::optional<TrajectorySample> next() override;
  [[nodiscard]] std::uint64_t samples() const noexcept { return sampler_->count(); }
  [[nodiscard]] std::uint64_t segments() const noexcept { return sampler_->segments(); }
  [[nodiscard]] const PlannerStatistics& planner_statistics() const noexcept { return planner_->statistics(); }
  [[nodiscard]] double rate_hz() const noexcept { return sampler_->rate_hz(); }

 private:
  std::unique_ptr<GcodeReader> reader_;
  std::unique_ptr<CornerBlender> blender_;
  std::unique_ptr<Planner> planner_;
  std::unique_ptr<Sampler> sampler_;
};

//! Reads and plans a whole program into memory (for evaluation at any time).
Trajectory plan_gcode(const std::filesystem::path& gcode, const PlanOptions& options = {});
Trajectory plan_gcode(std::istream& in, const std::string& label, const PlanOptions& options = {});

}  // namespace stiffpath::motion
