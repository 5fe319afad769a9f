// The G-code modal state machine: units, feed, laser, path control, distance mode, homes, G92, dwells, moves and stops.
#include "gcode_interpreter.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace stiffpath::motion {

using detail::code_tenths;
using detail::GcodeBlock;

namespace {
constexpr double inch_m = 0.0254;
constexpr double max_coordinate_mm = max_coordinate_m * 1e3;
// The share of P that merging short lines may use (G64 Q is capped at it); the rest is the blends'.
constexpr double merge_share = 0.5;
}  // namespace

GcodeInterpreter::GcodeInterpreter(const GcodeOptions& options, GcodeWarnings& warnings)
    : options_(options),
      warnings_(warnings),
      mode_(options.initial_mode),
      blend_tolerance_m_(options.default_blend_tolerance_m),
      merge_tolerance_m_(merge_share * options.default_blend_tolerance_m),
      position_m_(options.start_position_m) {}

void GcodeInterpreter::warn(GcodeWarningKind kind, const GcodeBlock& b, const std::string& message) {
  warnings_.add(kind, b.where->line, message);
}

void GcodeInterpreter::execute(const GcodeBlock& b, std::deque<PathSegment>& out) {
  if (b.units != nullptr) scale_m_ = code_tenths(b.units->value) == 200 ? inch_m : 1e-3;
  set_feed(b);
  set_acceleration(b);
  set_laser(b);
  if (b.tool) warn(GcodeWarningKind::tool_ignored, b, "tool selection (T) and tool changes (M6) are ignored");
  if (b.z != nullptr) {
    warn(GcodeWarningKind::z_ignored, b, "Z words are ignored (the robot has no Z axis); a move with only Z takes no time");
  }
  if (b.tool_length != nullptr) {
    warn(GcodeWarningKind::tool_length_ignored, b, "tool length offsets (G43, H) are ignored: they only concern Z");
  }
  if (b.ignored_m != nullptr) {
    warn(GcodeWarningKind::m_code_ignored, b,
         fmt::format("{} and the other configured vendor M-codes are ignored (they do not move the robot)",
                     word_name(*b.ignored_m)));
  }
  set_modes(b);

  bool arc_move = false;
  const int non_modal = b.non_modal != nullptr ? code_tenths(b.non_modal->value) : -1;
  if (b.non_modal != nullptr) {
    if (b.motion != nullptr) b.fail(*b.motion, "cannot share a line with " + word_name(*b.non_modal));
    if (non_modal == 40) {
      dwell(b, out);
    } else if (non_modal == 280 || non_modal == 300) {
      home(b, out);
    } else {
      set_offset(b, out);
    }
  } else {
    if (b.motion != nullptr) motion_ = code_tenths(b.motion->value);
    const bool arc_mode = motion_ == 20 || motion_ == 30;
    const bool centre = b.i != nullptr || b.j != nullptr || b.r != nullptr;
    // X or Y move; so does an arc given only its centre (a full circle, also as a helix with Z).
    // A line with only Z moves nothing in XY and takes no time.
    const bool moves = b.has_axis() || (arc_mode && centre && (b.motion != nullptr || b.z != nullptr));
    if (moves) {
      const GcodeWord& anchor = b.motion != nullptr ? *b.motion : (b.x != nullptr ? *b.x : (b.y != nullptr ? *b.y : *b.z));
      if (motion_ < 0) b.fail(anchor, "no motion mode is active (G0, G1, G2 or G3 must come first)");
      arc_move = arc_mode;
      move(b, anchor, out);
    }
  }
  for (const GcodeWord* word : {b.i, b.j, b.r}) {
    if (word != nullptr && !arc_move) b.fail(*word, "I, J and R belong to G2/G3 arc moves");
  }
  if (b.k != nullptr && !(arc_move && plane_ != 170)) {
    b.fail(*b.k, arc_move ? "arcs are in the XY plane; give their centre with I and J"
                          : "K belongs to G2/G3 arcs in the XZ (G18) or YZ (G19) plane");
  }
  const int pm = b.path_mode != nullptr ? code_tenths(b.path_mode->value) : -1;
  if (b.p != nullptr && b.ignored_m == nullptr) {
    const int laser = b.laser != nullptr ? code_tenths(b.laser->value) : -1;
    if (non_modal != 40 && pm != 640 && laser != 620 && laser != 630 && laser != 1060 && laser != 1070) {
      b.fail(*b.p, "P belongs to G4 (dwell), G64 (blend tolerance) or M62/M63, M106/M107 (output number)");
    }
  }
  if (b.q != nullptr && b.ignored_m == nullptr && pm != 640) {
    b.fail(*b.q, "Q belongs to G64 (the tolerance for merging short lines)");
  }
  program_stop(b, out);
  if (b.stop != nullptr) ended_ = true;
}

void GcodeInterpreter::set_feed(const GcodeBlock& b) {
  if (b.f == nullptr) return;
  if (!(b.f->value > 0.0)) b.fail(*b.f, "feed rate must be positive");
  const double mm_min = b.f->value * scale_m_ * 1e3;
  if (mm_min < min_feed_mm_min) {
    b.fail(*b.f, fmt::format("feed {:g} mm/min is below the slowest accepted, {:g} mm/min", mm_min, min_feed_mm_min));
  }
  if (mm_min > max_feed_mm_min) {
    b.fail(*b.f, fmt::format("feed {:g} mm/min is above the fastest accepted, {:.0f} mm/min", mm_min, max_feed_mm_min));
  }
  feed_m_s_ = b.f->value * scale_m_ / 60.0;  // units per minute
}

void GcodeInterpreter::set_modes(const GcodeBlock& b) {
  if (b.plane != nullptr) plane_ = code_tenths(b.plane->value);
  if (b.path_mode != nullptr) {
    if (code_tenths(b.path_mode->value) == 640) {
      mode_ = JunctionMode::blend;
      blend_tolerance_m_ = options_.default_blend_tolerance_m;
      for (const GcodeWord* word : {b.p, b.q}) {
        if (word == nullptr) continue;
        if (word->value < 0.0) b.fail(*word, "blend tolerance must not be negative");
        if (word->value * scale_m_ > max_blend_tolerance_m) {
          b.fail(*word, fmt::format("blend tolerance above the largest accepted, {:g} mm", max_blend_tolerance_m * 1e3));
        }
      }
      if (b.p != nullptr) blend_tolerance_m_ = b.p->value * scale_m_;
      // Q (LinuxCNC's naive CAM tolerance, P when not given; Q0: no merging) merges short lines; half
      // of P at most, so that the merged lines' blends keep the path within P of the program.
      merge_tolerance_m_ = merge_share * blend_tolerance_m_;
      if (b.q != nullptr) merge_tolerance_m_ = std::min(merge_tolerance_m_, b.q->value * scale_m_);
    } else {
      mode_ = JunctionMode::exact_stop;
    }
  }
  if (b.distance != nullptr) incremental_ = code_tenths(b.distance->value) == 910;
}

void GcodeInterpreter::dwell(const GcodeBlock& b, std::deque<PathSegment>& out) {
  const bool ms = options_.dwell_p_units == DwellUnits::milliseconds;
  const char* units = ms ? "milliseconds" : "seconds";
  if (b.p == nullptr) b.fail(*b.non_modal, fmt::format("a dwell needs P ({})", units));
  if (b.p->value < 0.0) b.fail(*b.p, "dwell time must not be negative");
  const double seconds = ms ? b.p->value * 1e-3 : b.p->value;
  if (seconds > max_block_duration_s) {
    b.fail(*b.p, fmt::format("a dwell of {:g} s is longer than the longest block accepted, {:g} s (P is read in {})",
                             seconds, max_block_duration_s, units));
  }
  if (seconds > long_dwell_warning_s) {
    warn(GcodeWarningKind::long_dwell, b, fmt::format("a dwell of {:g} s, over a minute (G4 P is read in {})", seconds, units));
  }
  // G4 P0 is an exact stop (CAM writes it where G64 must not blend); before the first move the dwell
  // waits for the robot's position, and takes its time there.
  PathSegment segment = make_dwell(position_m_.value_or(Vec2::Zero()), seconds);
  segment.mode = JunctionMode::exact_stop;
  std::deque<PathSegment> one;
  emit(segment, b, one);
  (position_m_ ? out : waiting_).push_back(one.front());
}

void GcodeInterpreter::locate(const Vec2& position_m, std::deque<PathSegment>& out) {
  position_m_ = position_m;
  for (PathSegment& dwell : waiting_) {
    dwell.start_m = dwell.end_m = position_m;
    out.push_back(dwell);
  }
  waiting_.clear();
}

void GcodeInterpreter::finish(std::deque<PathSegment>& out) {
  if (waiting_.empty()) return;
  if (options_.home_position_m) {
    locate(*options_.home_position_m, out);
  } else {
    waiting_.clear();  // no position at all: a program without motion has nothing to time
  }
}

void GcodeInterpreter::set_offset(const GcodeBlock& b, std::deque<PathSegment>& out) {
  if (!b.has_axis()) {
    if (b.z != nullptr) return;  // G92 Z: the robot has no Z axis
    b.fail(*b.non_modal, "G92 needs X and/or Y");
  }
  if (!position_m_) {  // the robot stands where it started: its home unless a start position is given
    if (!options_.home_position_m) {
      b.fail(*b.non_modal, "the current position is unknown (give the start or the home position, or move before G92)");
    }
    const Vec2& home = *options_.home_position_m;
    warn(GcodeWarningKind::start_at_home, b,
         fmt::format("G92 before the first move: the robot starts at its home position ({:g}, {:g}) mm", home.x() * 1e3,
                     home.y() * 1e3));
    locate(home, out);
  }
  const GcodeWord* words[2] = {b.x, b.y};
  for (int k = 0; k < 2; ++k) {
    if (words[k] == nullptr) continue;
    const double v = coordinate_m(b, *words[k]);
    offset_m_[k] = (*position_m_)[k] - options_.work_offset_m[k] - v;
  }
}

void GcodeInterpreter::require_start(const GcodeBlock& b, const GcodeWord& anchor) const {
  if (position_m_) return;
  if (incremental_) b.fail(anchor, "an incremental (G91) first move needs a known start position");
  if (b.x == nullptr || b.y == nullptr) {
    b.fail(anchor, "the first move must give both X and Y (the start position is unknown)");
  }
}

double GcodeInterpreter::coordinate_m(const GcodeBlock& b, const GcodeWord& word) const {
  const double v = word.value * scale_m_;
  if (std::abs(v) > max_coordinate_m) {
    b.fail(word, fmt::format("coordinate beyond ±{:g} mm, the largest accepted", max_coordinate_mm));
  }
  return v;
}

Vec2 GcodeInterpreter::target(const GcodeBlock& b) const {
  Vec2 p = position_m_.value_or(Vec2::Zero());
  const GcodeWord* words[2] = {b.x, b.y};
  for (int k = 0; k < 2; ++k) {
    if (words[k] == nullptr) continue;
    const double v = coordinate_m(b, *words[k]);
    p[k] = incremental_ ? p[k] + v : v + options_.work_offset_m[k] + offset_m_[k];
    if (std::abs(p[k]) > max_coordinate_m) {
      b.fail(*words[k], fmt::format("moves to {:g} mm in the robot frame, beyond ±{:g} mm, the largest accepted",
                                    p[k] * 1e3, max_coordinate_mm));
    }
  }
  return p;
}

void GcodeInterpreter::rapid_to(const Vec2& end, const GcodeBlock& b, std::deque<PathSegment>& out) {
  if (!position_m_) {  // the robot is assumed to stand there already
    locate(end, out);
    return;
  }
  if ((end - *position_m_).norm() < shortest_segment_m) return;
  PathSegment segment = make_line(*position_m_, end);
  segment.rapid = true;
  position_m_ = end;
  emit(segment, b, out);
}

void GcodeInterpreter::home(const GcodeBlock& b, std::deque<PathSegment>& out) {
  if (!b.has_axis() && b.z != nullptr) return;  // G28 Z…: only Z goes home, and the robot has none
  if (!options_.home_position_m) {
    b.fail(*b.non_modal, "the robot's home position is not set (home_mm in the robot file)");
  }
  const Vec2& home = *options_.home_position_m;
  if (b.has_axis()) {  // through the intermediate point; then only the named axes go home
    require_start(b, *b.non_modal);
    rapid_to(target(b), b, out);
    Vec2 end = *position_m_;
    if (b.x != nullptr) end.x() = home.x();
    if (b.y != nullptr) end.y() = home.y();
    rapid_to(end, b, out);
  } else {
    rapid_to(home, b, out);
  }
}

void GcodeInterpreter::move(const GcodeBlock& b, const GcodeWord& anchor, std::deque<PathSegment>& out) {
  const bool rapid = motion_ == 0, arc = motion_ == 20 || motion_ == 30;
  if (!rapid && !feed_m_s_) b.fail(anchor, "no feed rate (F) has been programmed");
  if (!position_m_) {  // the robot is assumed to stand at the first absolute target
    if (arc) b.fail(anchor, "an arc cannot be the first move: its start point is unknown (move there first)");
    require_start(b, anchor);
    locate(target(b), out);
    return;
  }
  const Vec2 start = *position_m_;
  const Vec2 end = target(b);
  PathSegment segment;
  if (arc && plane_ != 170) {  // an arc in XZ or YZ: its XY projection, along the line between its ends
    warn(GcodeWarningKind::plane_arc_as_line, b,
         "arcs in the XZ (G18) and YZ (G19) planes move along the straight line between their ends in XY");
    if ((end - start).norm() < shortest_segment_m) return;
    segment = make_line(start, end);
  } else if (arc) {
    segment = build_arc(b, anchor, motion_ == 20, start, end, scale_m_, options_.arc_tolerance_m);
  } else {
    // A move below 1 nm is dropped; the position stays, so the next move starts where the last ended.
    if ((end - start).norm() < shortest_segment_m) return;
    segment = make_line(start, end);
  }
  if (!rapid && segment.length_m / *feed_m_s_ > max_block_duration_s) {
    b.fail(anchor, fmt::format("a move of {:g} mm at {:g} mm/min lasts {:g} s, longer than the longest block accepted, {:g} s",
                               segment.length_m * 1e3, *feed_m_s_ * 6e4, segment.length_m / *feed_m_s_,
                               max_block_duration_s));
  }
  position_m_ = segment.end_m;
  segment.rapid = rapid;
  segment.feed_m_s = rapid ? std::numeric_limits<double>::infinity() : *feed_m_s_;
  emit(segment, b, out);
}

void GcodeInterpreter::program_stop(const GcodeBlock& b, std::deque<PathSegment>& out) {
  if (b.pause == nullptr) return;
  const auto& dwell_s = options_.program_stop_dwell_s;
  warn(GcodeWarningKind::program_stop, b,
       dwell_s ? fmt::format("M0/M1 are taken as a dwell of {:g} s with the laser off", *dwell_s)
               : std::string("M0/M1: the robot comes to rest and the job goes on at once (the pause is not in the output)"));
  PathSegment segment = make_dwell(position_m_.value_or(Vec2::Zero()), dwell_s.value_or(0.0));
  segment.line = b.where->line;
  segment.mode = JunctionMode::exact_stop;
  if (position_m_) {
    out.push_back(segment);  // laser off, power 0
  } else if (dwell_s) {
    waiting_.push_back(segment);  // before the first move: the dwell takes its time where the robot stands
  }
}

// M204 S<acceleration>: program units per s² (Marlin's, RepRapFirmware's), the limit of the moves that follow
// until the next M204; it only lowers the machine's limit.
void GcodeInterpreter::set_acceleration(const GcodeBlock& b) {
  if (b.acceleration == nullptr) return;
  if (b.s == nullptr) b.fail(*b.acceleration, "M204 needs S, the acceleration in program units per s^2");
  const double a = b.s->value * scale_m_;
  if (!(a >= min_acceleration_limit_m_s2 && a <= max_acceleration_limit_m_s2)) {
    b.fail(*b.s, fmt::format("acceleration {:g} m/s^2 is outside {:g} … {:g} m/s^2", a, min_acceleration_limit_m_s2,
                             max_acceleration_limit_m_s2));
  }
  acceleration_m_s2_ = a;
}

void GcodeInterpreter::emit(PathSegment segment, const GcodeBlock& b, std::deque<PathSegment>& out) {
  const double power = power_fraction();
  segment.line = b.where->line;
  segment.laser_on = laser_ != Laser::off && power > 0.0 && !segment.rapid;
  segment.power = segment.laser_on ? power : 0.0;
  segment.dynamic_power = segment.laser_on && dynamic_;
  if (segment.kind != SegmentKind::dwell) {
    segment.mode = mode_;
    if (laser_ != Laser::off && power == 0.0 && !segment.rapid) {
      warn(GcodeWarningKind::laser_without_power, b, "a feed move with the laser on at S0: the laser does not fire");
    }
  }
  segment.blend_tolerance_m = blend_tolerance_m_;
  segment.merge_tolerance_m = segment.mode == JunctionMode::blend ? merge_tolerance_m_ : 0.0;
  segment.max_acceleration_m_s2 = acceleration_m_s2_;
  out.push_back(segment);
}

}  // namespace stiffpath::motion
