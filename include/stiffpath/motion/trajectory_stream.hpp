// The whole motion pipeline for one G-code program: reader → corner blender → planner → sampler.
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/motion/corner_blend.hpp"
#include "stiffpath/motion/gcode_reader.hpp"
#include "stiffpath/motion/line_merge.hpp"
#include "stiffpath/motion/planner.hpp"
#include "stiffpath/motion/sampler.hpp"
#include "stiffpath/motion/slowdown.hpp"
#include "stiffpath/motion/trajectory.hpp"

namespace stiffpath::motion {

//! Everything that shapes a planned program. Documented defaults throughout.
struct PlanOptions {
  GcodeOptions gcode;                       //!< work offset, start and home positions, dialect
  MotionLimits limits;                      //!< v, a, j (defaults: 2 m/s, 5 g, 5 g / 5 ms)
  PlannerOptions planner;                   //!< junction rules, look-ahead bound
  double rate_hz = default_sample_rate_hz;  //!< sampling rate (Hz)
};

//! The corner blender of a plan (with the chord fitter when asked for), deciding each G64 corner
//! with the planner's limits (CornerSpeedModel), reading from `source` (a LineMerger).
std::unique_ptr<CornerBlender> make_blender(PathSource& source, const PlanOptions& options);

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
  //! The sampler's planned segments (SampleSource::keep_segments).
  const SegmentHistory* keep_segments(double seconds) override { return sampler_->keep_segments(seconds); }
  [[nodiscard]] std::uint64_t samples() const noexcept { return sampler_->count(); }
  [[nodiscard]] std::uint64_t segments() const noexcept { return sampler_->segments(); }
  [[nodiscard]] const PlannerStatistics& planner_statistics() const noexcept { return planner_->statistics(); }
  [[nodiscard]] double rate_hz() const noexcept { return sampler_->rate_hz(); }
  //! The reader's warnings, one per kind (complete once next() has returned nullopt).
  [[nodiscard]] const std::vector<GcodeWarning>& warnings() const noexcept { return reader_->warnings(); }
  //! Where the plan loses time against the programmed feeds, and why (complete once next() has
  //! returned nullopt).
  [[nodiscard]] const SlowdownReport* slowdowns() const noexcept override { return &tap_->report(); }

 private:
  std::unique_ptr<GcodeReader> reader_;
  std::unique_ptr<FeedClock> clock_;
  std::unique_ptr<LineMerger> merger_;
  std::unique_ptr<CornerBlender> blender_;
  std::unique_ptr<Planner> planner_;
  std::unique_ptr<SlowdownTap> tap_;
  std::unique_ptr<Sampler> sampler_;
};

//! The size of a planned job, known before any sample is made.
struct PlanSize {
  std::uint64_t segments = 0;  //!< planned segments (the sampler's count)
  double duration_s = 0.0;     //!< end of the last segment (s)
  std::uint64_t samples = 0;   //!< what a TrajectoryStream with the same options hands out
  //! Stops between two moves: where the plan rests (exact stops, dwells) or turns a corner at speed.
  std::uint64_t stops = 0;
  //! What resting `rest_samples` at every stop adds (see measure_plan): at most Σ max(0, rest_samples − ⌊d·rate⌋)
  //! over the stops, d a stop's duration (its dwells; 0 for a dwell with the laser on, which rests that much more).
  std::uint64_t rest_samples_added = 0;
};

//! Reads and plans the whole program without sampling it (flat memory, time proportional to the
//! number of segments, not to the duration) and returns its size, so a caller can refuse a job
//! before writing anything. Throws the program's refusals (GcodeErrors) like the stream does;
//! options.gcode.on_warnings is not called. `rest_samples`: how long a consumer rests at every stop between
//! two moves (a reference filter restarted there, job::TaskSource), counted in rest_samples_added.
PlanSize measure_plan(const std::filesystem::path& gcode, const PlanOptions& options = {}, std::uint64_t rest_samples = 0);
PlanSize measure_plan(std::istream& in, const std::string& label, const PlanOptions& options = {},
                      std::uint64_t rest_samples = 0);

//! Reads and plans a whole program into memory (for evaluation at any time).
Trajectory plan_gcode(const std::filesystem::path& gcode, const PlanOptions& options = {});
Trajectory plan_gcode(std::istream& in, const std::string& label, const PlanOptions& options = {});

}  // namespace stiffpath::motion
