// plate.json: the calibration plate's marks and fiducials in the robot frame, written and read back with located errors.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {

constexpr const char* kFormat = "stiffpath-calibration-plate";
constexpr double kVersion = 1.0;
constexpr double kMaxCoordinate_mm = 1e4;  // ±10 m, as G-code coordinates
constexpr std::size_t kMaxMarks = 10'000;

nlohmann::json mm(const Vec2& p) { return {units::m_to_mm(p.x()), units::m_to_mm(p.y())}; }
nlohmann::json rect_mm(const compliance::GridBounds& b) {
  return {units::m_to_mm(b.x_min), units::m_to_mm(b.x_max), units::m_to_mm(b.y_min), units::m_to_mm(b.y_max)};
}

Vec2 point_mm(const core::JsonObject& o, std::string_view key) {
  const auto [x, y] = o.pair(key);
  if (std::abs(x) > kMaxCoordinate_mm || std::abs(y) > kMaxCoordinate_mm) {
    o.fail(key, fmt::format("RANGE: coordinates must lie within ±{:g} mm, got ({}, {})", kMaxCoordinate_mm, x, y));
  }
  return {units::mm_to_m(x), units::mm_to_m(y)};
}

double bounded(const core::JsonObject& o, std::string_view key, double low, double high) {
  const double v = o.number(key);
  if (!(v >= low && v <= high)) o.fail(key, fmt::format("RANGE: must lie in {:g} … {:g}, got {}", low, high, v));
  return v;
}

compliance::GridBounds rect(const core::JsonObject& o, std::string_view key) {
  const auto& a = o.array(key);
  if (a.size() != 4) o.fail(key, "must be [x_min, x_max, y_min, y_max] in mm");
  double v[4];
  for (std::size_t i = 0; i < 4; ++i) {
    if (!a[i].is_number() || !std::isfinite(a[i].get<double>()) || std::abs(a[i].get<double>()) > kMaxCoordinate_mm) {
      o.fail(key, "must hold four finite numbers within ±10 m");
    }
    v[i] = units::mm_to_m(a[i].get<double>());
  }
  if (!(v[1] > v[0] && v[3] > v[2])) o.fail(key, "must have x_max > x_min and y_max > y_min");
  return {v[0], v[1], v[2], v[3]};
}

const char* kind_name(StrokeKind kind) {
  switch (kind) {
    case StrokeKind::ringing: return "ringing";
    case StrokeKind::timing: return "timing";
    case StrokeKind::arc: return "arc";
  }
  return "?";
}

// An arc's mark: its centre and sweep; its polyline must start and end on the circle where the sweep says.
void read_arc(const core::JsonObject& o, StrokeMark& m) {
  m.centre_m = point_mm(o, "centre_mm");
  m.sweep_rad = units::deg_to_rad(bounded(o, "sweep_deg", -360.0, 360.0));
  const double radius = (m.start_m - m.centre_m).norm();
  if (!(radius >= 0.5e-3)) o.fail("centre_mm", "an arc's radius must be at least 0.5 mm");
  if (std::abs(units::rad_to_deg(m.sweep_rad)) < 10.0) o.fail("sweep_deg", "an arc must turn at least 10 deg");
  const double turned_end_error = (m.end_m - m.centre_m).norm() - radius;
  if (std::abs(turned_end_error) > 1e-6) {
    o.fail("polyline_mm", fmt::format("an arc's end must lie on its circle (radius {:.4f} mm): it is {:.4f} mm off",
                                      units::m_to_mm(radius), units::m_to_mm(turned_end_error)));
  }
  const double c = std::cos(m.sweep_rad), s = std::sin(m.sweep_rad);
  const Vec2 r = m.start_m - m.centre_m;
  const Vec2 swept = m.centre_m + Vec2(c * r.x() - s * r.y(), s * r.x() + c * r.y());
  if ((swept - m.end_m).norm() > 1e-6) {
    o.fail("sweep_deg", fmt::format("the arc from its start turned {:g} deg ends at ({:.4f}, {:.4f}) mm, not at the "
                                    "polyline's end", units::rad_to_deg(m.sweep_rad), units::m_to_mm(swept.x()),
                                    units::m_to_mm(swept.y())));
  }
}

}  // namespace

std::string plate_json(const PlateDesign& plate) {
  nlohmann::json fiducials = nlohmann::json::array(), marks = nlohmann::json::array();
  for (const auto& f : plate.fiducials) {
    fiducials.push_back({{"id", f.id},
                         {"centre_mm", mm(f.centre_m)},
                         {"ring_radius_mm", units::m_to_mm(f.ring_radius_m)},
                         {"cross_arm_mm", units::m_to_mm(f.cross_arm_m)}});
  }
  for (const auto& m : plate.strokes) {
    nlohmann::json polyline = nlohmann::json::array();
    for (const Vec2& p : m.polyline_m()) polyline.push_back(mm(p));
    nlohmann::json mark = {{"id", m.id},
                           {"kind", kind_name(m.kind)},
                           {"polyline_mm", polyline},
                           {"acceleration_mm_s2", m.acceleration_m_s2 * 1e3},
                           {"feed_mm_s", units::m_to_mm(m.feed_m_s)},
                           {"tail_feed_mm_s", units::m_to_mm(m.tail_feed_m_s)}};
    if (m.kind == StrokeKind::timing) mark["run_mm"] = units::m_to_mm(m.run_m);
    if (m.kind == StrokeKind::arc) {
      mark["centre_mm"] = mm(m.centre_m);
      mark["sweep_deg"] = units::rad_to_deg(m.sweep_rad);
    }
    marks.push_back(mark);
  }
  const nlohmann::json doc = {{"format", kFormat},
                              {"version", kVersion},
                              {"robot", {{"name", plate.robot}, {"geometry_sha256", plate.geometry_sha256}}},
                              {"sheet_mm", rect_mm(plate.sheet)},
                              {"area_mm", rect_mm(plate.area)},
                              {"laser_power", plate.laser_power},
                              {"fiducials", fiducials},
                              {"marks", marks}};
  return doc.dump(2) + "\n";
}

PlateDesign load_plate(const std::string& path) {
  const core::JsonDocument doc = core::parse_json_document(core::read_data(core::parse_data_ref(path)), path);
  const core::JsonObject root(doc);
  root.allow_only({"format", "version", "robot", "sheet_mm", "area_mm", "laser_power", "fiducials", "marks"});
  if (root.string("format") != kFormat) root.fail("format", std::string("must be \"") + kFormat + "\"");
  if (root.number("version") != kVersion) root.fail("version", "this stiffpath reads version 1");
  PlateDesign plate;
  const core::JsonObject robot = root.object("robot");
  robot.allow_only({"name", "geometry_sha256"});
  plate.robot = robot.string("name");
  plate.geometry_sha256 = robot.string("geometry_sha256");
  plate.sheet = rect(root, "sheet_mm");
  plate.area = rect(root, "area_mm");
  plate.laser_power = bounded(root, "laser_power", 1e-6, 1.0);
  const auto& fiducials = root.array("fiducials");
  if (fiducials.size() < 3 || fiducials.size() > 100) root.fail("fiducials", "must list 3 … 100 fiducials");
  for (std::size_t k = 0; k < fiducials.size(); ++k) {
    const core::JsonObject f = root.element("fiducials", k);
    f.allow_only({"id", "centre_mm", "ring_radius_mm", "cross_arm_mm"});
    FiducialMark m;
    m.id = f.string("id");
    m.centre_m = point_mm(f, "centre_mm");
    m.ring_radius_m = units::mm_to_m(bounded(f, "ring_radius_mm", 0.5, 50.0));
    m.cross_arm_m = units::mm_to_m(bounded(f, "cross_arm_mm", 0.0, 50.0));
    if (!(m.cross_arm_m < m.ring_radius_m)) f.fail("cross_arm_mm", "must stop short of the ring");
    plate.fiducials.push_back(m);
  }
  const auto& marks = root.array("marks");
  if (marks.empty() || marks.size() > kMaxMarks) root.fail("marks", fmt::format("must list 1 … {} marks", kMaxMarks));
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const core::JsonObject o = root.element("marks", k);
    o.allow_only({"id", "kind", "polyline_mm", "acceleration_mm_s2", "feed_mm_s", "tail_feed_mm_s", "centre_mm", "sweep_deg",
                  "run_mm"});
    StrokeMark m;
    m.id = o.string("id");
    const std::string kind = o.string("kind");
    if (kind != "ringing" && kind != "timing" && kind != "arc") o.fail("kind", "must be ringing, timing or arc, got '" + kind + "'");
    m.kind = kind == "ringing" ? StrokeKind::ringing : kind == "timing" ? StrokeKind::timing : StrokeKind::arc;
    for (const char* key : {"centre_mm", "sweep_deg"}) {
      if ((m.kind == StrokeKind::arc) != o.has(key)) o.fail(key, m.kind == StrokeKind::arc ? "an arc needs it" : "only an arc has it");
    }
    const auto& poly = o.array("polyline_mm");
    const std::size_t n = m.kind == StrokeKind::ringing ? 3 : 2;
    if (m.kind == StrokeKind::arc ? poly.size() < 2 || poly.size() > 1000 : poly.size() != n) {
      o.fail("polyline_mm", m.kind == StrokeKind::arc
                                ? fmt::format("must list 2 … 1000 points along the arc, got {}", poly.size())
                                : fmt::format("must list {} points for a {} stroke (its start and end{}), got {}", n, kind,
                                              n == 3 ? ", the tail's end" : "", poly.size()));
    }
    Vec2 p[3];
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = m.kind == StrokeKind::arc && j == 1 ? poly.size() - 1 : j;  // an arc: its start and end
      if (!poly[i].is_array() || poly[i].size() != 2 || !poly[i][0].is_number() || !poly[i][1].is_number()) {
        o.fail("polyline_mm", fmt::format("point {} must be [x, y] in mm", i));
      }
      const double x = poly[i][0].get<double>(), y = poly[i][1].get<double>();
      if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > kMaxCoordinate_mm || std::abs(y) > kMaxCoordinate_mm) {
        o.fail("polyline_mm", fmt::format("RANGE: point {} must lie within ±{:g} mm", i, kMaxCoordinate_mm));
      }
      p[j] = {units::mm_to_m(x), units::mm_to_m(y)};
    }
    if (n == 2) p[2] = p[1];
    if ((p[1] - p[0]).norm() < 1e-4 || (n == 3 && (p[2] - p[1]).norm() < 1e-4)) {
      o.fail("polyline_mm", "a stroke or tail shorter than 0.1 mm");
    }
    m.start_m = p[0], m.end_m = p[1], m.tail_end_m = p[2];
    if (m.kind == StrokeKind::arc) read_arc(o, m);
    if (o.has("run_mm")) {
      if (m.kind != StrokeKind::timing) o.fail("run_mm", "only a timing stroke has it");
      m.run_m = units::mm_to_m(bounded(o, "run_mm", 0.0, 1000.0));
    }
    m.acceleration_m_s2 = bounded(o, "acceleration_mm_s2", 100.0, 1e6) * 1e-3;
    m.feed_m_s = units::mm_to_m(bounded(o, "feed_mm_s", 1.0, 1e5));
    m.tail_feed_m_s = units::mm_to_m(bounded(o, "tail_feed_mm_s", 1.0, 1e5));
    plate.strokes.push_back(m);
  }
  return plate;
}

}  // namespace stiffpath::calibration
