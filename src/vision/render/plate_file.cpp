// Reading a plate description (JSON) and a mark's path (CSV) for the synthetic scanner, every value checked and located.
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/vision/render/plate.hpp"

namespace stiffpath::vision {

namespace {

// No page, bed or mark is larger than this (mm): an A0 sheet is 1189 mm long.
constexpr double kMaxPlateMm = 2000.0;

// A number within [lo, hi] (finite), refused at its key otherwise.
double within(const core::JsonObject& o, std::string_view key, double lo, double hi, const char* unit) {
  const double x = o.number(key);
  if (!(x >= lo) || !(x <= hi)) o.fail(key, fmt::format("RANGE: must be within [{}, {}]{}, got {}", lo, hi, unit, o.raw()[key].dump()));
  return x;
}

// "[x, y]" in mm, each within ±kMaxPlateMm.
Point2 point_mm(const core::JsonObject& o, std::string_view key) {
  const auto& v = o.array(key);
  if (v.size() != 2 || !v[0].is_number() || !v[1].is_number()) o.fail(key, "expected [x, y] in mm, got " + v.dump());
  const double x = v[0].get<double>(), y = v[1].get<double>();
  if (!(std::abs(x) <= kMaxPlateMm) || !(std::abs(y) <= kMaxPlateMm)) {
    o.fail(key, fmt::format("RANGE: {} is beyond ±{} mm, larger than any plate", v.dump(), kMaxPlateMm));
  }
  return {x * 1e-3, y * 1e-3};
}

bool boolean(const core::JsonObject& o, std::string_view key, bool fallback) {
  if (!o.has(key)) return fallback;
  if (!o.raw()[std::string(key)].is_boolean()) o.fail(key, "expected true or false, got " + o.raw()[std::string(key)].dump());
  return o.raw()[std::string(key)].get<bool>();
}

// Rotates the sides about their first point by `angle` (clockwise on screen) and moves that point to `at`.
void place(PlateMarkPath& mark, double angle, const Point2& at) {
  const Point2 first = mark.sides.front().front();
  const double c = std::cos(angle), s = std::sin(angle);
  for (auto& side : mark.sides) {
    for (auto& p : side) {
      const Point2 d = p - first;
      p = at + Point2{c * d.x() - s * d.y(), s * d.x() + c * d.y()};
    }
  }
}

double angle_of(const core::JsonObject& m) { return m.has("angle_deg") ? within(m, "angle_deg", -3600, 3600, " deg") * std::numbers::pi / 180 : 0.0; }

PlateMarkPath shape_mark(const core::JsonObject& m) {
  m.allow_only({"id", "comment", "shape", "length_mm", "side_mm", "vertices_mm", "closed", "at_mm", "angle_deg", "wiggle_mm",
                "wiggle_wavelength_mm", "wiggle_decay_mm"});
  const std::string shape = m.string("shape");
  PathShape nominal;
  if (shape == "line") {
    nominal = line_shape(within(m, "length_mm", 1e-3, kMaxPlateMm, " mm") * 1e-3);
  } else if (shape == "triangle") {
    nominal = triangle_shape(within(m, "side_mm", 1e-3, kMaxPlateMm, " mm") * 1e-3);
  } else if (shape == "polyline") {
    const auto& v = m.array("vertices_mm");
    if (v.size() < 2) m.fail("vertices_mm", "a polyline needs at least two vertices");
    if (v.size() > 100000) m.fail("vertices_mm", fmt::format("RANGE: {} vertices, more than the 100000 a mark may have", v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string key = fmt::format("vertices_mm[{}]", i);
      if (!v[i].is_array() || v[i].size() != 2 || !v[i][0].is_number() || !v[i][1].is_number()) {
        m.fail(key, "expected [x, y] in mm, got " + v[i].dump());
      }
      const double x = v[i][0].get<double>(), y = v[i][1].get<double>();
      if (!(std::abs(x) <= kMaxPlateMm) || !(std::abs(y) <= kMaxPlateMm)) {
        m.fail(key, fmt::format("RANGE: {} is beyond ±{} mm, larger than any plate", v[i].dump(), kMaxPlateMm));
      }
      nominal.vertices.emplace_back(x * 1e-3, y * 1e-3);
      if (i > 0 && nominal.vertices[i] == nominal.vertices[i - 1]) m.fail(key, "repeats the vertex before it: a side of zero length");
    }
    nominal.closed = boolean(m, "closed", false);
    if (nominal.closed && nominal.vertices.size() < 3) m.fail("closed", "a closed polyline needs at least three vertices");
  } else {
    m.fail("shape", fmt::format("expected line, triangle or polyline, got '{}'", shape));
  }
  Wiggle wiggle;
  if (m.has("wiggle_mm")) wiggle.amplitude_m = within(m, "wiggle_mm", -100, 100, " mm") * 1e-3;
  if (m.has("wiggle_wavelength_mm")) wiggle.wavelength_m = within(m, "wiggle_wavelength_mm", 1e-3, 1e4, " mm") * 1e-3;
  if (m.has("wiggle_decay_mm")) wiggle.decay_length_m = within(m, "wiggle_decay_mm", 1e-3, 1e6, " mm") * 1e-3;
  PlateMarkPath mark;
  try {
    mark.sides = sample_shape(nominal, wiggle);  // refuses, before sampling, a path beyond the point budget
  } catch (const Error& e) {
    m.fail("shape", e.message());
  }
  mark.closed = nominal.closed;
  place(mark, angle_of(m), point_mm(m, "at_mm"));
  return mark;
}

PlateMarkPath csv_mark(const core::JsonObject& m, const std::filesystem::path& plate_file) {
  m.allow_only({"id", "comment", "path_csv", "sides", "at_mm", "angle_deg"});
  const double sides = m.has("sides") ? within(m, "sides", 1, 64, "") : 1.0;
  if (sides != std::floor(sides)) m.fail("sides", fmt::format("expected a whole number 1..64, got {}", sides));
  PlateMarkPath mark = load_mark_csv(plate_file.parent_path() / m.string("path_csv"), static_cast<int>(sides));
  if (m.has("at_mm") || m.has("angle_deg")) {
    const Point2 at = m.has("at_mm") ? point_mm(m, "at_mm") : mark.sides.front().front();
    place(mark, angle_of(m), at);
  }
  return mark;
}

PlateFiducial fiducial(const core::JsonObject& f) {
  f.allow_only({"id", "comment", "at_mm", "radius_mm", "cross", "cross_arm_mm"});
  PlateFiducial out;
  out.at_m = point_mm(f, "at_mm");
  if (f.has("radius_mm")) out.shape.ring_radius_m = within(f, "radius_mm", 0.5, 50, " mm") * 1e-3;
  out.shape.cross = boolean(f, "cross", true);
  out.shape.cross_arm_m = f.has("cross_arm_mm") ? within(f, "cross_arm_mm", 0.01, 50, " mm") * 1e-3 : out.shape.ring_radius_m / 2;
  return out;
}

ScannerBed scanner(const core::JsonObject& s) {
  s.allow_only({"comment", "bed_mm", "page_at_mm", "page_angle_deg", "mirror", "lid_level", "edge_shadow", "edge_shadow_mm", "curl_mm",
                "curl_shading", "smudges"});
  ScannerBed bed;
  const Point2 size = point_mm(s, "bed_mm");
  if (!(size.x() > 0) || !(size.y() > 0)) s.fail("bed_mm", "expected [width, height] in mm, both positive");
  bed.width_m = size.x(), bed.height_m = size.y();
  if (s.has("page_at_mm")) bed.page_at_m = point_mm(s, "page_at_mm");
  if (s.has("page_angle_deg")) bed.page_angle_rad = within(s, "page_angle_deg", -360, 360, " deg") * std::numbers::pi / 180;
  bed.mirror = boolean(s, "mirror", false);
  if (s.has("lid_level")) bed.lid_level = within(s, "lid_level", 0, 1, "");
  if (s.has("edge_shadow")) bed.edge_shadow = within(s, "edge_shadow", 0, 1, "");
  if (s.has("edge_shadow_mm")) bed.edge_shadow_m = within(s, "edge_shadow_mm", 0, 10, " mm") * 1e-3;
  if (s.has("curl_mm")) bed.curl_m = within(s, "curl_mm", 0, 100, " mm") * 1e-3;
  if (s.has("curl_shading")) bed.curl_shading = within(s, "curl_shading", 0, 0.5, "");
  if (s.has("smudges")) bed.smudges = static_cast<int>(within(s, "smudges", 0, 1000, ""));
  return bed;
}

}  // namespace

PlateMarkPath load_mark_csv(const std::filesystem::path& path, int sides) {
  if (sides < 1 || sides > 64) throw Error(SourceLocation{path.string(), 0, 0}, fmt::format("sides must be 1..64, got {}", sides));
  core::CsvReader csv(path.string());
  const auto cx = csv.column("x_mm"), cy = csv.column("y_mm");
  std::vector<Point2> points;
  double length = 0;  // m, for the budget of the resampled path
  while (csv.next()) {
    for (const auto col : {cx, cy}) {
      if (!(std::abs(csv.number(col)) <= kMaxPlateMm)) {
        csv.fail(col, fmt::format("RANGE: {} mm is beyond ±{} mm, farther than any marked path", csv.text(col), kMaxPlateMm));
      }
    }
    const Point2 p{csv.number(cx) * 1e-3, csv.number(cy) * 1e-3};
    if (!points.empty()) length += (p - points.back()).norm();
    if (length / 20e-6 > static_cast<double>(kMaxRenderPathPoints) || points.size() >= kMaxRenderPathPoints) {
      throw Error(csv.where(), fmt::format("RANGE: the path is {:.0f} mm long by this line, more than the {} points of the render "
                                           "budget at a 20 µm step ({:.0f} mm)", length * 1e3, kMaxRenderPathPoints,
                                           kMaxRenderPathPoints * 20e-3));
    }
    if (points.empty() || (p - points.back()).norm() > 1e-12) points.push_back(p);  // a robot at rest repeats points
  }
  if (points.size() < 2) throw Error(SourceLocation{path.string(), 0, 0}, "a path needs at least two distinct points");
  const std::vector<Point2> dense = resample_path(points);
  if (sides == 1) return {{dense}, false, {}, {}};
  auto split = evaluation::split_polyline(dense, sides);
  return {std::move(split.sides), split.closed, {}, {}};
}

Plate load_plate(const std::filesystem::path& path) {
  const core::JsonDocument doc = core::read_json_document(path.string());
  // Where an entry of the file is, so that the renderer's refusals (off the page, off the bed) name it.
  const auto locate = [&](const std::string& entry) {
    const auto at = core::locate_json_path(doc.text, entry);
    return at ? SourceLocation{path.string(), at->first, at->second} : SourceLocation{path.string(), 0, 0};
  };
  const core::JsonObject root(doc);
  root.allow_only({"comment", "page_mm", "marks", "fiducials", "labels", "scanner"});
  Plate plate;
  const Point2 page = point_mm(root, "page_mm");
  if (!(page.x() > 0) || !(page.y() > 0)) root.fail("page_mm", "expected [width, height] in mm, both positive");
  plate.width_m = page.x();
  plate.height_m = page.y();
  std::size_t points = 0;
  const auto& marks = root.array("marks");
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const core::JsonObject m = root.element("marks", i);
    PlateMarkPath mark = m.has("path_csv") ? csv_mark(m, path) : shape_mark(m);
    if (m.has("id")) mark.id = m.string("id");
    mark.where = locate(fmt::format("marks[{}]", i));
    for (const auto& side : mark.sides) points += side.size();
    if (points > kMaxRenderPathPoints) {
      m.fail(m.has("path_csv") ? "path_csv" : "shape",
             fmt::format("RANGE: the plate's marks take {} points by this one, more than the render budget of {}", points, kMaxRenderPathPoints));
    }
    plate.marks.push_back(std::move(mark));
  }
  if (root.has("fiducials")) {
    for (std::size_t i = 0; i < root.array("fiducials").size(); ++i) {
      plate.fiducials.push_back(fiducial(root.element("fiducials", i)));
      plate.fiducials.back().where = locate(fmt::format("fiducials[{}]", i));
    }
  }
  if (root.has("labels")) {
    for (std::size_t i = 0; i < root.array("labels").size(); ++i) {
      const core::JsonObject l = root.element("labels", i);
      l.allow_only({"comment", "text", "at_mm", "height_mm"});
      plate.labels.push_back({l.string("text"), point_mm(l, "at_mm"), l.has("height_mm") ? within(l, "height_mm", 0.1, 100, " mm") * 1e-3 : 4e-3,
                              locate(fmt::format("labels[{}]", i))});
    }
  }
  if (root.has("scanner")) plate.bed = scanner(root.object("scanner"));
  return plate;
}

}  // namespace stiffpath::vision
