// TrajectoryStream and plan_gcode: the motion stages chained for one program.
#include "stiffpath/motion/trajectory_stream.hpp"

#include <cmath>
#include <optional>

#include "stiffpath/motion/junction.hpp"

namespace stiffpath::motion {

std::unique_ptr<CornerBlender> make_blender(PathSource& source, const PlanOptions& options) {
  const CornerSpeedModel model{options.limits, options.planner.junction.junction_time_s};
  const JunctionRules& rules = options.planner.junction;
  const ChordFitting fitting = rules.fit_chords          ? ChordFitting::all
                               : rules.fit_merged_chords ? ChordFitting::merged
                                                         : ChordFitting::none;
  return std::make_unique<CornerBlender>(source, rules.corner_angle_rad, fitting, model);
}

TrajectoryStream::TrajectoryStream(const std::filesystem::path& gcode, const PlanOptions& options)
    : reader_(std::make_unique<GcodeReader>(gcode, options.gcode)),
      clock_(std::make_unique<FeedClock>(*reader_, options.limits)),
      merger_(std::make_unique<LineMerger>(*clock_)),
      blender_(make_blender(*merger_, options)),
      planner_(std::make_unique<Planner>(*blender_, options.limits, options.planner)),
      tap_(std::make_unique<SlowdownTap>(*planner_, *clock_, options.limits)),
      sampler_(std::make_unique<Sampler>(*tap_, options.rate_hz)) {}

TrajectoryStream::TrajectoryStream(std::istream& in, std::string label, const PlanOptions& options)
    : reader_(std::make_unique<GcodeReader>(in, std::move(label), options.gcode)),
      clock_(std::make_unique<FeedClock>(*reader_, options.limits)),
      merger_(std::make_unique<LineMerger>(*clock_)),
      blender_(make_blender(*merger_, options)),
      planner_(std::make_unique<Planner>(*blender_, options.limits, options.planner)),
      tap_(std::make_unique<SlowdownTap>(*planner_, *clock_, options.limits)),
      sampler_(std::make_unique<Sampler>(*tap_, options.rate_hz)) {}

TrajectoryStream::~TrajectoryStream() = default;

std::optional<TrajectorySample> TrajectoryStream::next() { return sampler_->next(); }

namespace {
Trajectory plan_from(GcodeReader& reader, const PlanOptions& options) {
  LineMerger merger(reader);
  const auto blender = make_blender(merger, options);
  return Trajectory::plan(*blender, options.limits, options.planner);
}

PlanSize measure(GcodeReader& reader, const PlanOptions& options, std::uint64_t rest_samples) {
  LineMerger merger(reader);
  const auto blender = make_blender(merger, options);
  Planner planner(*blender, options.limits, options.planner);
  PlanSize size;
  std::optional<PathSegment> moved;  // the last move: a stop from here on is between two moves
  double stop_s = -1.0;              // the stop being passed and its dwells so far (s); < 0 while moving
  bool fires = false;                // the stop holds a dwell with the laser on
  while (auto segment = planner.next()) {
    const bool dwell = segment->path.kind == SegmentKind::dwell;
    // A stop: the plan rests, or (between two moves) turns a corner at speed (as job::TaskSource restarts).
    const bool corner = moved && !dwell && stop_s < 0.0 &&
                        turn_angle_rad(end_tangent(*moved), start_tangent(segment->path)) >
                            options.planner.junction.corner_angle_rad;
    if (moved && stop_s < 0.0 && (!(segment->entry_speed_m_s > 0.0) || corner)) stop_s = 0.0;
    if (dwell) {
      if (stop_s >= 0.0) {
        stop_s += segment->duration_s;
        fires = fires || segment->path.laser_on;
      }
    } else {
      if (stop_s >= 0.0) {  // the stop ends: a move follows
        ++size.stops;
        const double rested = fires ? 0.0 : std::floor(stop_s * options.rate_hz);
        if (static_cast<double>(rest_samples) > rested) {
          size.rest_samples_added += rest_samples - static_cast<std::uint64_t>(rested);
        }
      }
      stop_s = -1.0;
      fires = false;
      moved = segment->path;
    }
    ++size.segments;
    size.duration_s = segment->end_time_s();
  }
  size.samples = size.segments == 0 ? 0 : sample_count(size.duration_s, options.rate_hz);
  return size;
}

GcodeOptions quiet(GcodeOptions options) {
  options.on_warnings = nullptr;
  return options;
}
}  // namespace

PlanSize measure_plan(const std::filesystem::path& gcode, const PlanOptions& options, std::uint64_t rest_samples) {
  GcodeReader reader(gcode, quiet(options.gcode));
  return measure(reader, options, rest_samples);
}

PlanSize measure_plan(std::istream& in, const std::string& label, const PlanOptions& options,
                      std::uint64_t rest_samples) {
  GcodeReader reader(in, label, quiet(options.gcode));
  return measure(reader, options, rest_samples);
}

Trajectory plan_gcode(const std::filesystem::path& gcode, const PlanOptions& options) {
  GcodeReader reader(gcode, options.gcode);
  return plan_from(reader, options);
}

Trajectory plan_gcode(std::istream& in, const std::string& label, const PlanOptions& options) {
  GcodeReader reader(in, label, options.gcode);
  return plan_from(reader, options);
}

}  // namespace stiffpath::motion
