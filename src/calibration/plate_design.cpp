// Lays out the calibration plate over a robot's measured region: fiducials in the corners, strokes and arcs in cells of their own.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/motion/segment_limits.hpp"

namespace stiffpath::calibration {

namespace {

constexpr double kPaperEdge_m = 10e-3;       // kept free along the sheet's edges (feeding, scanning)
constexpr double kShortestStroke_m = 5e-3;   // below this a stroke shows too little of its deflection
constexpr double kPointSpacing_m = 0.5e-3;   // a mark's reach is checked every half millimetre

void check_options(const PlateOptions& o) {
  const auto fail = [](const std::string& what) { throw Error("calibration plate: " + what); };
  if (!(o.acceleration_m_s2 >= 0.1 && o.acceleration_m_s2 <= 1e3)) {
    fail(fmt::format("the acceleration must lie in 0.1 … 1000 m/s², got {}", o.acceleration_m_s2));
  }
  if (o.acceleration_levels.size() < 2) fail("at least two acceleration levels are needed");
  for (const double f : o.acceleration_levels) {
    if (!(f > 0.0 && f <= 1.0)) fail(fmt::format("an acceleration level must lie in (0, 1], got {}", f));
  }
  if (o.directions_deg.size() < 3) fail("at least three stroke directions are needed");
  for (const double d : o.directions_deg) {
    if (!(d >= 0.0 && d < 180.0)) fail(fmt::format("a direction must lie in [0, 180) deg, got {}", d));
  }
  if (o.stations_x < 1 || o.stations_y < 1 || o.stations_x * o.stations_y < 4 || o.stations_x * o.stations_y > 64) {
    fail(fmt::format("stations: at least four places and at most 64, got {} x {}", o.stations_x, o.stations_y));
  }
  if (!(o.arc_sweep_deg >= 180.0 && o.arc_sweep_deg <= 300.0)) {
    fail(fmt::format("an arc's sweep must lie in 180 … 300 deg (every direction across it, its ends apart), got {}",
                     o.arc_sweep_deg));
  }
  if (!(o.tail_length_m >= 1e-3 && o.tail_length_m <= 50e-3)) fail("the tail must be 1 … 50 mm long");
  if (!(o.tail_feed_m_s >= 1e-3 && o.tail_feed_m_s <= 0.5)) fail("the tail's speed must lie in 1 … 500 mm/s");
  if (!(o.fiducial_feed_m_s >= 1e-3 && o.fiducial_feed_m_s <= 0.1)) fail("the fiducials' speed must lie in 1 … 100 mm/s");
  if (!(o.sheet_short_m > 0.05 && o.sheet_long_m >= o.sheet_short_m && o.sheet_long_m < 2.0)) fail("bad sheet size");
  if (!(o.margin_m >= 0.5e-3 && o.margin_m <= 20e-3)) fail("the margin must lie in 0.5 … 20 mm");
}

compliance::GridBounds intersect(const compliance::GridBounds& a, const compliance::GridBounds& b) {
  return {std::max(a.x_min, b.x_min), std::min(a.x_max, b.x_max), std::max(a.y_min, b.y_min), std::min(a.y_max, b.y_max)};
}

// Every point of a polyline, every half millimetre, must be one the robot accepts (reach and joint limits).
void check_reach(const kinematics::Robot& robot, const std::vector<Vec2>& points, const std::string& what) {
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const Vec2 d = points[k + 1] - points[k];
    const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / kPointSpacing_m)));
    for (int i = 0; i <= n; ++i) {
      const Vec2 p = points[k] + d * (static_cast<double>(i) / n);
      if (const std::string why = robot.refusal(p); !why.empty()) {
        throw Error(fmt::format("calibration plate: {} passes (x = {:.3f} mm, y = {:.3f} mm), which robot '{}' refuses: {}",
                                what, units::m_to_mm(p.x()), units::m_to_mm(p.y()), robot.name, why));
      }
    }
  }
}

std::vector<Vec2> ring_points(const FiducialMark& f) {
  std::vector<Vec2> out;
  for (int k = 0; k <= 72; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 72.0;
    out.emplace_back(f.centre_m + f.ring_radius_m * Vec2(std::cos(a), std::sin(a)));
  }
  return out;
}

// The longest stroke of tail `tail` that fits a cell of w × h in every direction, with the margin all round.
double longest_stroke(const std::vector<double>& directions_deg, double tail, double w, double h, double margin) {
  double best = 1e9;
  for (const double deg : directions_deg) {
    const double c = std::abs(std::cos(units::deg_to_rad(deg))), s = std::abs(std::sin(units::deg_to_rad(deg)));
    // Extent of stroke L along u = (c, s) and tail T along the normal: x: L·c + T·s, y: L·s + T·c.
    if (c > 1e-9) best = std::min(best, (w - 2.0 * margin - tail * s) / c);
    if (s > 1e-9) best = std::min(best, (h - 2.0 * margin - tail * c) / s);
  }
  return best;
}

}  // namespace

PlateDesign design_plate(const kinematics::Robot& robot, const compliance::GridBounds& region, const PlateOptions& o) {
  check_options(o);
  if (!(region.x_max > region.x_min && region.y_max > region.y_min)) {
    throw Error("calibration plate: the robot's measured region is empty (it needs compliance data over an area)");
  }
  PlateDesign plate;
  plate.robot = robot.name;
  plate.geometry_sha256 = robot.geometry_hash();

  // The sheet centred on the region, its long side along the region's longer one; the marks where both are.
  const Vec2 centre(0.5 * (region.x_min + region.x_max), 0.5 * (region.y_min + region.y_max));
  const bool wide = region.x_max - region.x_min >= region.y_max - region.y_min;
  const double half_x = 0.5 * (wide ? o.sheet_long_m : o.sheet_short_m);
  const double half_y = 0.5 * (wide ? o.sheet_short_m : o.sheet_long_m);
  plate.sheet = {centre.x() - half_x, centre.x() + half_x, centre.y() - half_y, centre.y() + half_y};
  plate.area = intersect(region.grown(-o.margin_m), plate.sheet.grown(-kPaperEdge_m));

  // Fiducials in the corners of the area; the strokes' band leaves them room along the longer side. The fourth is
  // moved inwards along the shorter side by a ring's radius and the margin, so that the four are no rectangle:
  // a rectangle fits a scan equally well turned by 180° or mirrored, and only the strokes could tell which.
  const FiducialMark shape;
  const double corner = shape.ring_radius_m + o.margin_m;
  const Vec2 inwards = wide ? Vec2(0.0, -corner) : Vec2(corner, 0.0);
  const Vec2 corners[4] = {{plate.area.x_min + corner, plate.area.y_min + corner},
                           {plate.area.x_max - corner, plate.area.y_min + corner},
                           {plate.area.x_max - corner, plate.area.y_max - corner},
                           Vec2(plate.area.x_min + corner, plate.area.y_max - corner) + inwards};
  for (int k = 0; k < 4; ++k) {
    FiducialMark f = shape;
    f.id = fmt::format("F{}", k + 1);
    f.centre_m = corners[k];
    check_reach(robot, ring_points(f), "fiducial " + f.id);
    plate.fiducials.push_back(f);
  }
  compliance::GridBounds band = plate.area;
  const double clear = 2.0 * corner;
  if (band.x_max - band.x_min >= band.y_max - band.y_min) {
    band.x_min += clear, band.x_max -= clear;
  } else {
    band.y_min += clear, band.y_max -= clear;
  }

  // Stations, and in each one cell per (direction, level) and per level's arc: the columns and rows that give the
  // longest common stroke that fits every cell.
  const std::size_t straight = o.directions_deg.size() * (o.acceleration_levels.size() + 1);
  const std::size_t per_station = straight + o.acceleration_levels.size();
  const double station_w = (band.x_max - band.x_min) / o.stations_x, station_h = (band.y_max - band.y_min) / o.stations_y;
  int columns = 1;
  double stroke = -1.0;
  for (int c = 1; c <= static_cast<int>(per_station); ++c) {
    const auto r = static_cast<int>((per_station + static_cast<std::size_t>(c) - 1) / static_cast<std::size_t>(c));
    const double length = longest_stroke(o.directions_deg, o.tail_length_m, station_w / c, station_h / r, o.margin_m);
    if (length > stroke) stroke = length, columns = c;
  }
  const int rows = static_cast<int>((per_station + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
  const double cell_w = station_w / columns, cell_h = station_h / rows;
  const double arc_radius = 0.5 * std::min(cell_w, cell_h) - o.margin_m;
  if (!(stroke >= kShortestStroke_m) || !(arc_radius >= 0.5 * kShortestStroke_m)) {
    throw Error(fmt::format("calibration plate: the measured region ({:.0f} x {:.0f} mm) leaves cells of {:.1f} x {:.1f} mm "
                            "for {} marks per station: strokes of {:.1f} mm, shorter than {:.0f} mm (fewer stations, "
                            "directions or levels)",
                            units::m_to_mm(region.x_max - region.x_min), units::m_to_mm(region.y_max - region.y_min),
                            units::m_to_mm(cell_w), units::m_to_mm(cell_h), per_station, units::m_to_mm(stroke),
                            units::m_to_mm(kShortestStroke_m)));
  }
  for (int sy = 0; sy < o.stations_y; ++sy) {
    for (int sx = 0; sx < o.stations_x; ++sx) {
      const int station = sy * o.stations_x + sx + 1;
      std::size_t k = 0;
      const auto next_cell = [&] {
        const int col = static_cast<int>(k % static_cast<std::size_t>(columns));
        const int row = static_cast<int>(k / static_cast<std::size_t>(columns));
        ++k;
        return Vec2(band.x_min + sx * station_w + (col + 0.5) * cell_w, band.y_min + sy * station_h + (row + 0.5) * cell_h);
      };
      // Every level's ringing strokes, then the timing strokes at the highest level (its first), then an arc per level.
      for (std::size_t slot = 0; slot <= o.acceleration_levels.size(); ++slot) {
        const bool timing = slot == o.acceleration_levels.size();
        const std::size_t level = timing ? 0 : slot;
        for (const double deg : o.directions_deg) {
          const Vec2 cell_centre = next_cell();
          const Vec2 u(std::cos(units::deg_to_rad(deg)), std::sin(units::deg_to_rad(deg)));
          const Vec2 n(-u.y(), u.x());
          StrokeMark m;
          m.kind = timing ? StrokeKind::timing : StrokeKind::ringing;
          m.id = fmt::format("S{}-D{:03.0f}-A{}-{}", station, deg, level + 1, timing ? 'T' : 'R');
          // The stroke and its tail centred in the cell; a timing stroke's mark is its middle half, run up to and
          // out of at speed over a quarter each side.
          const double tail = timing ? 0.0 : o.tail_length_m;
          const Vec2 middle = cell_centre - 0.5 * tail * n;
          const double mark = timing ? 0.5 * stroke : stroke;
          m.start_m = middle - 0.5 * mark * u;
          m.end_m = middle + 0.5 * mark * u;
          m.tail_end_m = m.end_m + tail * n;
          m.run_m = timing ? 0.25 * stroke : 0.0;
          m.acceleration_m_s2 = o.acceleration_m_s2 * o.acceleration_levels[level];
          // The speed a rest-to-rest stroke of this length peaks at (accelerate half, decelerate half); a timing
          // stroke the speed its run-up reaches with room to spare for the jerk (v² = a·run, half of 2·a·run).
          m.feed_m_s = std::min(2.0, std::sqrt(m.acceleration_m_s2 * (timing ? m.run_m : stroke)));
          m.tail_feed_m_s = o.tail_feed_m_s;
          check_reach(robot, m.motion_m(), "mark " + m.id);
          plate.strokes.push_back(m);
        }
      }
      for (std::size_t level = 0; level < o.acceleration_levels.size(); ++level) {
        // Counter-clockwise about the cell's centre, the gap to the left (-x): from 180° + gap/2 round to 180° − gap/2.
        StrokeMark m;
        m.kind = StrokeKind::arc;
        m.id = fmt::format("S{}-A{}-C", station, level + 1);
        m.centre_m = next_cell();
        m.sweep_rad = units::deg_to_rad(o.arc_sweep_deg);
        const double from = std::numbers::pi + 0.5 * (2.0 * std::numbers::pi - m.sweep_rad);
        m.start_m = m.centre_m + arc_radius * Vec2(std::cos(from), std::sin(from));
        m.end_m = m.centre_m + arc_radius * Vec2(std::cos(from + m.sweep_rad), std::sin(from + m.sweep_rad));
        m.tail_end_m = m.end_m;
        m.acceleration_m_s2 = o.acceleration_m_s2 * o.acceleration_levels[level];
        // The fastest the planner turns it: the centripetal share of the level's acceleration (the rest is left for
        // speeding up along the arc), v²/r = 0.7·a.
        m.feed_m_s = std::min(2.0, std::sqrt(motion::arc_centripetal_acceleration_share * m.acceleration_m_s2 * arc_radius));
        m.tail_feed_m_s = o.tail_feed_m_s;
        check_reach(robot, m.polyline_m(), "mark " + m.id);
        plate.strokes.push_back(m);
      }
    }
  }
  return plate;
}

compliance::GridBounds plate_region(const kinematics::Robot& robot) {
  if (!robot.compliance.table.empty()) return compliance::table_region(compliance::robot_table(robot));
  if (!robot.compliance.model.empty()) return compliance::load_robot_model(robot).model->bounds();
  throw Error(SourceLocation{robot.file.label()},
              fmt::format("robot '{}' has no compliance data: the plate is laid out over its measured region", robot.name));
}

}  // namespace stiffpath::calibration
