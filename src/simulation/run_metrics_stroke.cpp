// One stroke's metrics as it is marked: pieces between command vertices, sides between corners, chains of sides.
#include "run_metrics_stroke.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/iso9283.hpp"

namespace stiffpath::simulation::detail {

namespace {

// A command whose ends are closer than this is a closed path (m).
constexpr double kClosedGap_m = 1e-6;

// The command's own largest distance from its fitted sides above which its line metrics are refused
// (m): a contour that is not straight sides (an arc, a rounded rectangle taken as one side) would
// report its own shape as the robot's deviation.
constexpr double kStraightCommand_m = 50e-6;

std::string plural(std::size_t n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

}  // namespace

std::vector<Vec2> StrokeMeter::Trace::take() {
  finder.finish(settled);
  std::vector<Vec2> out;
  out.reserve(settled.size());
  for (const auto& v : settled) out.push_back(v.point);
  settled.clear();
  finder = evaluation::VertexFinder(finder_tolerance(), 64);
  return out;
}

StrokeMeter::StrokeMeter(int sides, const evaluation::PathMetricsOptions& options)
    : sides_wanted_(sides),
      options_(options),
      piece_commands_(options.trace_tolerance_m),
      piece_marks_(options.trace_tolerance_m),
      mark_chain_(options,
                  [this](std::size_t, evaluation::SideMetrics&& side) {
                    length_m_ += side.length_m;
                    area_m2_ += side.deviation_area_m2;
                    max_deviation_m_ = std::max(max_deviation_m_, side.max_deviation_m);
                  }),
      command_chain_(options, [this](std::size_t, evaluation::SideMetrics&& side) {
        commanded_m_ += side.length_m;
        command_deviation_m_ = std::max(command_deviation_m_, side.max_offset_m);
      }) {}

void StrokeMeter::refuse(const std::string& why) {
  if (refusal_.empty()) refusal_ = why;
}

void StrokeMeter::command(const Vec2& target_m) {
  const std::size_t index = commands_++;
  if (index == 0) first_command_ = target_m;
  last_command_ = target_m;
  pending_commands_.emplace_back(index, target_m);
  std::vector<evaluation::Vertex> vertices;
  std::vector<evaluation::SharpCorner> corners;
  finder_.add(target_m, vertices, corners);
  settle(vertices, 0);
  for (const auto& c : corners) cut(c.first_index, c.last_index, c);
  assign_until(finder_.frontier());
  if (!pieces_.empty() && (side_length_m_ > kMaxSide_m || side_points_ > kMaxSidePoints)) {
    refuse(side_length_m_ > kMaxSide_m
               ? fmt::format("its command runs more than {:g} m without a sharp corner", kMaxSide_m)
               : fmt::format("a side's mark holds more than {} distinct points", kMaxSidePoints));
    cut(pieces_.back().end, pieces_.back().end, std::nullopt);
  }
}

void StrokeMeter::mark(const Vec2& tip_m) {
  ++marks_;
  // The marks of the interval the last command started (the job's first mark: of its first interval).
  pending_marks_.emplace_back(commands_ == 0 ? 0 : commands_ - 1, tip_m);
  if (pending_marks_.front().first < finder_.frontier()) assign_until(finder_.frontier());
}

void StrokeMeter::settle(const std::vector<evaluation::Vertex>& vertices, std::size_t from) {
  for (std::size_t i = from; i < vertices.size(); ++i) close_piece(vertices[i].index);
}

// Commands before sample `frontier` and the marks of the intervals before it join the open piece.
void StrokeMeter::assign_until(std::size_t frontier) {
  while (!pending_commands_.empty() && pending_commands_.front().first < frontier) {
    const Vec2 p = pending_commands_.front().second;
    if (piece_last_command_) piece_length_m_ += (p - *piece_last_command_).norm();
    piece_last_command_ = p;
    if (piece_commands_.settled.size() < kMaxSidePoints) piece_commands_.add(p);
    pending_commands_.pop_front();
  }
  while (!pending_marks_.empty() && pending_marks_.front().first < frontier) {
    if (piece_marks_.settled.size() < kMaxSidePoints) {
      piece_marks_.add(pending_marks_.front().second);
    } else {
      refuse(fmt::format("a side's mark holds more than {} distinct points", kMaxSidePoints));
    }
    pending_marks_.pop_front();
  }
}

// A command vertex at sample `end`: the open piece ends there, and the next starts there.
void StrokeMeter::close_piece(std::size_t end) {
  assign_until(end);
  const Vec2 vertex = pending_commands_.front().second;  // sample `end` itself
  if (end == piece_start_ && !piece_last_command_) {   // the stroke's first sample
    piece_commands_.add(vertex);
    piece_last_command_ = vertex;
    pending_commands_.pop_front();
    return;
  }
  // The vertex closes this piece (its marks, of the interval it starts, open the next).
  if (piece_last_command_) piece_length_m_ += (vertex - *piece_last_command_).norm();
  piece_commands_.add(vertex);
  pending_commands_.pop_front();
  Piece piece;
  piece.start = piece_start_;
  piece.end = end;
  piece.commands = piece_commands_.take();
  piece.marks = piece_marks_.take();
  piece.command_length_m = piece_length_m_;
  side_length_m_ += piece.command_length_m;
  side_points_ += piece.marks.size();
  pieces_.push_back(std::move(piece));
  piece_start_ = end;
  piece_length_m_ = 0.0;
  piece_commands_.add(vertex);  // and opens the next
  piece_last_command_ = vertex;
}

// The closed pieces up to sample `until`, joined.
StrokeMeter::Part StrokeMeter::take_pieces(std::size_t until) {
  Part part;
  while (!pieces_.empty() && pieces_.front().end <= until) {
    Piece& piece = pieces_.front();
    const std::size_t skip = part.commands.empty() ? 0 : 1;  // the vertex both pieces share
    part.commands.insert(part.commands.end(), piece.commands.begin() + static_cast<std::ptrdiff_t>(std::min(skip, piece.commands.size())),
                         piece.commands.end());
    part.marks.insert(part.marks.end(), piece.marks.begin(), piece.marks.end());
    side_length_m_ -= piece.command_length_m;
    side_points_ -= piece.marks.size();
    pieces_.pop_front();
  }
  if (pieces_.empty()) side_length_m_ = 0.0;
  return part;
}

// A corner (its first and last vertex) ends the current side; or, without a corner, a cut.
void StrokeMeter::cut(std::size_t first, std::size_t last, const std::optional<evaluation::SharpCorner>& corner) {
  first = std::max(first, side_start_);
  last = std::max(last, first);
  Part side = take_pieces(first);
  Part turn = take_pieces(last);
  side_start_ = last;
  if (corner && corner->turn_rad > std::numbers::pi - evaluation::kReversalAngle_rad) reversal_ = true;
  // The previous corner's marks: the side before it, its turn, and this side (up to this corner).
  if (corner_) {
    std::vector<Vec2> window = std::move(before_corner_->marks);
    window.insert(window.end(), turn_->marks.begin(), turn_->marks.end());
    window.insert(window.end(), side.marks.begin(), side.marks.end());
    measure_corner(*corner_, corner ? &*corner : nullptr, window);
  }
  measure_side(side);
  corner_ = corner;
  if (corner) {
    before_corner_ = Part{{}, std::move(side.marks)};
    turn_ = std::move(turn);
  } else {
    before_corner_.reset();
    turn_.reset();
  }
}

void StrokeMeter::measure_corner(const evaluation::SharpCorner& corner, const evaluation::SharpCorner* next,
                                 const std::vector<Vec2>& window) {
  RunMetrics& m = result_.metrics;
  ++m.corners;
  if (window.size() < 2) return;
  std::size_t cursor = 0;
  const auto d = evaluation::corner_deviation(corner, next, window, cursor);
  m.cornering_round_off_m = std::max(m.cornering_round_off_m, d.round_off_m);
  m.cornering_overshoot_m = std::max(m.cornering_overshoot_m, d.overshoot_m);
}

void StrokeMeter::measure_side(Part& side) {
  ++sides_;
  if (side.commands.size() >= 2 && side.marks.size() >= 2) {
    try {
      const double at = evaluation::iso9283_path_accuracy(side.commands, {side.marks}).accuracy_m;
      result_.metrics.path_accuracy_m = std::max(result_.metrics.path_accuracy_m, at);
      result_.path_accuracy = true;
    } catch (const Error&) {
      // no normal plane of this side crossed its mark
    }
  }
  if (!refusal_.empty()) return;
  try {
    mark_chain_.add_trace(side.marks);
    command_chain_.add_trace(side.commands);
  } catch (const Error& e) {
    refuse(e.message());
  }
}

StrokeMetrics StrokeMeter::finish(bool strict) {
  StrokeMetrics& s = result_;
  s.marked_points = marks_;
  if (marks_ < 4 || commands_ < 2) {
    s.refusal = fmt::format("the laser marked {} points ({} commanded); nothing to measure", marks_, commands_);
    if (strict) throw Error("simulation: " + s.refusal);
    s.metrics = {};
    return s;
  }
  std::vector<evaluation::Vertex> vertices;
  std::vector<evaluation::SharpCorner> corners;
  finder_.finish(vertices, corners);
  settle(vertices, 0);
  for (const auto& c : corners) cut(c.first_index, c.last_index, c);
  if (piece_start_ + 1 < commands_) close_piece(commands_ - 1);
  assign_until(commands_);
  Part last = take_pieces(commands_);
  if (corner_) {
    std::vector<Vec2> window = std::move(before_corner_->marks);
    window.insert(window.end(), turn_->marks.begin(), turn_->marks.end());
    window.insert(window.end(), last.marks.begin(), last.marks.end());
    measure_corner(*corner_, nullptr, window);
  }
  measure_side(last);
  RunMetrics& m = s.metrics;
  m.strokes = 1;
  const std::size_t n = sides_;
  if (refusal_.empty() && sides_wanted_ > 0 && n != static_cast<std::size_t>(sides_wanted_)) {
    refuse(fmt::format("its command has {}, so {}", plural(m.corners, "sharp corner", "sharp corners"),
                       plural(n, "side", "sides")));
  }
  if (refusal_.empty()) {
    const bool closed = n >= 3 && !reversal_ && (last_command_ - first_command_).norm() < kClosedGap_m;
    try {
      mark_chain_.finish(closed);
      command_chain_.finish(closed);
    } catch (const Error& e) {
      refuse(e.message());
    }
  }
  if (refusal_.empty() && command_deviation_m_ > kStraightCommand_m) {
    refuse(fmt::format("the command itself lies up to {:.3f} mm from its {} fitted side{} (more than {:g} mm): "
                       "its shape would be read as deviation",
                       command_deviation_m_ * 1e3, n, n == 1 ? "" : "s", kStraightCommand_m * 1e3));
  }
  if (!refusal_.empty()) {
    const std::size_t wanted = sides_wanted_ > 0 ? static_cast<std::size_t>(sides_wanted_) : n;
    s.refusal = fmt::format("not {} straight side{}: {}", wanted, wanted == 1 ? "" : "s", refusal_);
    if (strict) throw Error("simulation: " + s.refusal);
    return s;
  }
  m.length_m = length_m_;
  m.commanded_length_m = commanded_m_;
  m.length_error_m = length_m_ - commanded_m_;
  m.deviation_area_m2 = area_m2_;
  m.max_deviation_m = max_deviation_m_;
  m.line_strokes = 1;
  s.sides = static_cast<int>(n);
  return s;
}

}  // namespace stiffpath::simulation::detail
