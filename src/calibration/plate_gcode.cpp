// The calibration plate as G-code: fiducials slowly, then every stroke at its own acceleration, exact stops (timing
// strokes: blended, the laser switched at speed).
#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {
std::string xy(const Vec2& p) { return fmt::format("X{:.4f} Y{:.4f}", units::m_to_mm(p.x()), units::m_to_mm(p.y())); }
double mm_min(double m_s) { return m_s * 60e3; }
}  // namespace

std::string plate_gcode(const PlateDesign& plate, const PlateOptions& options) {
  const double power_s = plate.laser_power * 1000.0;  // S of full power: 1000, the default --s-max
  std::string g = fmt::format(
      "; stiffpath calibration plate for robot {} (geometry {}): {} fiducials, {} strokes\n"
      "; mark it like any job (stiffpath run plate.gcode --robot ...), scan the sheet at 1200 dpi and run\n"
      "; stiffpath calibrate fit plate.json SCAN --joints JOINTS --robot ...\n"
      "G21 G90 G17 G61\nM5\n",
      plate.robot, plate.geometry_sha256.substr(0, 12), plate.fiducials.size(), plate.strokes.size());
  const double slowest = *std::min_element(options.acceleration_levels.begin(), options.acceleration_levels.end()) *
                         options.acceleration_m_s2;
  g += fmt::format("M204 S{:.1f}\n", slowest * 1e3);
  for (const auto& f : plate.fiducials) {
    const Vec2 ring_start = f.centre_m + Vec2(f.ring_radius_m, 0.0);
    const double feed = mm_min(options.fiducial_feed_m_s);
    g += fmt::format("; fiducial {}\nG0 {}\nM3 S{:g}\nG2 {} I{:.4f} J0 F{:.1f}\nM5\n", f.id, xy(ring_start), power_s,
                     xy(ring_start), -units::m_to_mm(f.ring_radius_m), feed);
    for (const Vec2& arm : {Vec2(f.cross_arm_m, 0.0), Vec2(0.0, f.cross_arm_m)}) {
      g += fmt::format("G0 {}\nM3 S{:g}\nG1 {} F{:.1f}\nM5\n", xy(f.centre_m - arm), power_s, xy(f.centre_m + arm), feed);
    }
  }
  for (const auto& m : plate.strokes) {
    if (m.kind == StrokeKind::arc) {
      const Vec2 ij = m.centre_m - m.start_m;
      g += fmt::format("; mark {}\nM204 S{:.1f}\nG0 {}\nM3 S{:g}\n{} {} I{:.4f} J{:.4f} F{:.1f}\nM5\n", m.id,
                       m.acceleration_m_s2 * 1e3, xy(m.start_m), power_s, m.sweep_rad >= 0.0 ? "G3" : "G2", xy(m.end_m),
                       units::m_to_mm(ij.x()), units::m_to_mm(ij.y()), mm_min(m.feed_m_s));
      continue;
    }
    if (m.kind == StrokeKind::timing && m.run_m > 0.0) {
      // Run up, the laser on and off at speed where the mark starts and ends, run out: collinear moves blended (G64),
      // so nothing slows where the laser switches; then exact stops again.
      const auto path = m.motion_m();
      g += fmt::format("; mark {}\nM204 S{:.1f}\nG0 {}\nG64 P0.001\nG1 {} F{:.1f}\nM3 S{:g}\nG1 {}\nM5\nG1 {}\nG61\n", m.id,
                       m.acceleration_m_s2 * 1e3, xy(path[0]), xy(path[1]), mm_min(m.feed_m_s), power_s, xy(path[2]),
                       xy(path[3]));
      continue;
    }
    g += fmt::format("; mark {}\nM204 S{:.1f}\nG0 {}\nM3 S{:g}\nG1 {} F{:.1f}\n", m.id, m.acceleration_m_s2 * 1e3,
                     xy(m.start_m), power_s, xy(m.end_m), mm_min(m.feed_m_s));
    if (m.kind == StrokeKind::ringing) g += fmt::format("G1 {} F{:.1f}\n", xy(m.tail_end_m), mm_min(m.tail_feed_m_s));
    g += "M5\n";
  }
  return g + "M2\n";
}

}  // namespace stiffpath::calibration
