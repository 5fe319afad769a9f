// The G-code modal state machine: units, feed, laser, path control, distance mode, G92, dwells and moves.
#include "gcode_interpreter.hpp"

#include <cmath>
#include <limits>

namespace stiffpath::motion {

using detail::code_tenths;
using detail::GcodeBlock;

namespace {
constexpr double inch_m = 0.0254;
}  // namespace

GcodeInterpreter::GcodeInterpreter(const GcodeOptions& options)
    : options_(options),
      mode_(options.initial_mode),
      blend_tolerance_m_(options.default_blend_tolerance_m),
      position_m_(options.start_position_m) {}

std::optional<PathSegment> GcodeInterpreter::execute(const GcodeBlock& b) {
  if (b.units != nullptr) scale_m_ = code_tenths(b.units->value) == 200 ? inch_m : 1e-3;
  if (b.f != nullptr) {
    if (!(b.f->value > 0.0)) b.fail(*b.f, "feed rate must be positive");
    feed_m_s_ = b.f->value * scale_m_ / 60.0;  // units per minute
  }
  if (b.s != nullptr) {
    if (b.s->value < 0.0) b.fail(*b.s, "laser power must not be negative");
    power_ = b.s->value;
  }
  if (b.spindle != nullptr) laser_ = code_tenths(b.spindle->value) != 50;
  set_modes(b);

  std::optional<PathSegment> segment;
  bool arc_move = false;
  if (b.non_modal != nullptr) {
    if (b.motion != nullptr) b.fail(*b.motion, "cannot share a line with " + word_name(*b.non_modal));
    if (code_tenths(b.non_modal->value) == 40) {
      segment = dwell(b);
    } else {
      set_offset(b);
    }
  } else {
    if (b.motion != nullptr) motion_ = code_tenths(b.motion->value);
    const bool arc_mode = motion_ == 20 || motion_ == 30;
    const bool moves = b.has_axis() || (arc_mode && b.motion != nullptr && (b.i || b.j || b.r));
    if (moves) {
      const GcodeWord& anchor = b.motion != nullptr ? *b.motion : (b.x != nullptr ? *b.x : *b.y);
      if (motion_ < 0) b.fail(anchor, "no motion mode is active (G0, G1, G2 or G3 must come first)");
      arc_move = arc_mode;
      segment = move(b, anchor);
    }
  }
  for (const GcodeWord* word : {b.i, b.j, b.r}) {
    if (word != nullptr && !arc_move) b.fail(*word, "I, J and R belong to G2/G3 arc moves");
  }
  if (b.p != nullptr) {
    const int nm = b.non_modal != nullptr ? code_tenths(b.non_modal->value) : -1;
    const int pm = b.path_mode != nullptr ? code_tenths(b.path_mode->value) : -1;
    if (nm != 40 && pm != 640) b.fail(*b.p, "P belongs to G4 (dwell seconds) or G64 (blend tolerance)");
  }
  if (b.stop != nullptr) ended_ = true;
  return segment;
}

void GcodeInterpreter::set_modes(const GcodeBlock& b) {
  if (b.path_mode != nullptr) {
    if (code_tenths(b.path_mode->value) == 640) {
      mode_ = JunctionMode::blend;
      blend_tolerance_m_ = options_.default_blend_tolerance_m;
      if (b.p != nullptr) {
        if (b.p->value < 0.0) b.fail(*b.p, "blend tolerance must not be negative");
        blend_tolerance_m_ = b.p->value * scale_m_;
      }
    } else {
      mode_ = JunctionMode::exact_stop;
    }
  }
  if (b.distance != nullptr) incremental_ = code_tenths(b.distance->value) == 910;
}

std::optional<PathSegment> GcodeInterpreter::dwell(const GcodeBlock& b) {
  if (b.p == nullptr) b.fail(*b.non_modal, "a dwell needs P (seconds)");
  if (b.p->value < 0.0) b.fail(*b.p, "dwell time must not be negative");
  if (!position_m_ || b.p->value == 0.0) return std::nullopt;  // before the first move nothing is timed
  PathSegment segment = make_dwell(*position_m_, b.p->value);
  decorate(segment, b.where->line);
  segment.laser_on = laser_ && power_ > 0.0;
  segment.mode = JunctionMode::exact_stop;
  return segment;
}

void GcodeInterpreter::set_offset(const GcodeBlock& b) {
  if (!b.has_axis()) b.fail(*b.non_modal, "G92 needs X and/or Y");
  if (!position_m_) {
    b.fail(*b.non_modal, "the current position is unknown (give the start position, or move before G92)");
  }
  if (b.x != nullptr) offset_m_.x() = position_m_->x() - options_.work_offset_m.x() - b.x->value * scale_m_;
  if (b.y != nullptr) offset_m_.y() = position_m_->y() - options_.work_offset_m.y() - b.y->value * scale_m_;
}

Vec2 GcodeInterpreter::target(const GcodeBlock& b) const {
  Vec2 p = position_m_.value_or(Vec2::Zero());
  const GcodeWord* words[2] = {b.x, b.y};
  for (int k = 0; k < 2; ++k) {
    if (words[k] == nullptr) continue;
    const double v = words[k]->value * scale_m_;
    p[k] = incremental_ ? p[k] + v : v + options_.work_offset_m[k] + offset_m_[k];
  }
  return p;
}

std::optional<PathSegment> GcodeInterpreter::move(const GcodeBlock& b, const GcodeWord& anchor) {
  const bool rapid = motion_ == 0, arc = motion_ == 20 || motion_ == 30;
  if (!rapid && !feed_m_s_) b.fail(anchor, "no feed rate (F) has been programmed");
  if (!position_m_) {  // the robot is assumed to stand at the first absolute target
    if (arc) b.fail(anchor, "an arc cannot be the first move: its start point is unknown (move there first)");
    if (incremental_) b.fail(anchor, "an incremental (G91) first move needs a known start position");
    if (b.x == nullptr || b.y == nullptr) {
      b.fail(anchor, "the first move must give both X and Y (the start position is unknown)");
    }
    position_m_ = target(b);
    return std::nullopt;
  }
  const Vec2 start = *position_m_;
  const Vec2 end = target(b);
  PathSegment segment;
  if (arc) {
    segment = build_arc(b, anchor, motion_ == 20, start, end, scale_m_, options_.arc_tolerance_m);
  } else {
    // A move below 1 nm is dropped; the position stays, so the next move starts where the last ended.
    if ((end - start).norm() < shortest_segment_m) return std::nullopt;
    segment = make_line(start, end);
  }
  position_m_ = segment.end_m;
  segment.rapid = rapid;
  segment.feed_m_s = rapid ? std::numeric_limits<double>::infinity() : *feed_m_s_;
  decorate(segment, b.where->line);
  return segment;
}

void GcodeInterpreter::decorate(PathSegment& segment, int line) const {
  segment.line = line;
  segment.laser_power = power_;
  segment.laser_on = laser_ && power_ > 0.0 && !segment.rapid;
  segment.mode = mode_;
  segment.blend_tolerance_m = blend_tolerance_m_;
}

}  // namespace stiffpath::motion
