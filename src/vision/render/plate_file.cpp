// Reading a plate description (JSON) and a mark's path (CSV) for the synthetic scanner.
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/vision/render/plate.hpp"

namespace stiffpath::vision {

namespace {

Point2 point_mm(const core::JsonObject& o, std::string_view key) {
  const auto& v = o.array(key);
  if (v.size() != 2 || !v[0].is_number() || !v[1].is_number() || !std::isfinite(v[0].get<double>()) || !std::isfinite(v[1].get<double>())) {
    o.fail(key, "expected [x, y] in mm");
  }
  return {v[0].get<double>() * 1e-3, v[1].get<double>() * 1e-3};
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

PlateMarkPath shape_mark(const core::JsonObject& m) {
  const std::string shape = m.string("shape");
  PathShape nominal;
  if (shape == "line") {
    nominal = line_shape(m.positive("length_mm") * 1e-3);
  } else if (shape == "triangle") {
    nominal = triangle_shape(m.positive("side_mm") * 1e-3);
  } else if (shape == "polyline") {
    const auto& v = m.array("vertices_mm");
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_array() || v[i].size() != 2 || !v[i][0].is_number() || !v[i][1].is_number()) {
        m.fail("vertices_mm", fmt::format("vertex {} is not [x, y] in mm", i + 1));
      }
      nominal.vertices.emplace_back(v[i][0].get<double>() * 1e-3, v[i][1].get<double>() * 1e-3);
    }
    if (nominal.vertices.size() < 2) m.fail("vertices_mm", "a polyline needs at least two vertices");
    if (m.has("closed")) {
      if (!m.raw()["closed"].is_boolean()) m.fail("closed", "expected true or false");
      nominal.closed = m.raw()["closed"].get<bool>();
      if (nominal.closed && nominal.vertices.size() < 3) m.fail("closed", "a closed polyline needs at least three vertices");
    }
  } else {
    m.fail("shape", fmt::format("expected line, triangle or polyline, got '{}'", shape));
  }
  Wiggle wiggle;
  if (m.has("wiggle_mm")) wiggle.amplitude_m = m.number("wiggle_mm") * 1e-3;
  if (m.has("wiggle_wavelength_mm")) wiggle.wavelength_m = m.positive("wiggle_wavelength_mm") * 1e-3;
  if (m.has("wiggle_decay_mm")) wiggle.decay_length_m = m.positive("wiggle_decay_mm") * 1e-3;
  PlateMarkPath mark{sample_shape(nominal, wiggle), nominal.closed};
  place(mark, m.has("angle_deg") ? m.number("angle_deg") * std::numbers::pi / 180 : 0.0, point_mm(m, "at_mm"));
  return mark;
}

}  // namespace

PlateMarkPath load_mark_csv(const std::filesystem::path& path, int sides) {
  if (sides < 1 || sides > 64) throw Error(SourceLocation{path.string(), 0, 0}, fmt::format("sides must be 1..64, got {}", sides));
  core::CsvReader csv(path.string());
  const auto cx = csv.column("x_mm"), cy = csv.column("y_mm");
  std::vector<Point2> points;
  while (csv.next()) {
    const Point2 p{csv.number(cx) * 1e-3, csv.number(cy) * 1e-3};
    if (points.empty() || (p - points.back()).norm() > 1e-12) points.push_back(p);  // a robot at rest repeats points
  }
  if (points.size() < 2) throw Error(SourceLocation{path.string(), 0, 0}, "a path needs at least two distinct points");
  const std::vector<Point2> dense = resample_path(points);
  if (sides == 1) return {{dense}, false};
  auto split = evaluation::split_polyline(dense, sides);
  return {std::move(split.sides), split.closed};
}

Plate load_plate(const std::filesystem::path& path) {
  const nlohmann::json doc = core::read_json_file(path.string());
  const core::JsonObject root(doc, path.string());
  Plate plate;
  const auto& page = root.array("page_mm");
  if (page.size() != 2 || !page[0].is_number() || !page[1].is_number() || !(page[0].get<double>() > 0) || !(page[1].get<double>() > 0)) {
    root.fail("page_mm", "expected [width, height] in mm, both positive");
  }
  plate.width_m = page[0].get<double>() * 1e-3;
  plate.height_m = page[1].get<double>() * 1e-3;
  const auto& marks = root.array("marks");
  for (std::size_t i = 0; i < marks.size(); ++i) {
    if (!marks[i].is_object()) root.fail("marks", fmt::format("entry {} is not an object", i));
    const core::JsonObject m(marks[i], fmt::format("{}: marks[{}]", path.string(), i));
    if (m.has("path_csv")) {
      const double sides = m.has("sides") ? m.positive("sides") : 1.0;
      if (sides != std::floor(sides) || sides > 64) m.fail("sides", fmt::format("expected a whole number 1..64, got {}", sides));
      PlateMarkPath mark = load_mark_csv(path.parent_path() / m.string("path_csv"), static_cast<int>(sides));
      if (m.has("at_mm") || m.has("angle_deg")) {
        const Point2 at = m.has("at_mm") ? point_mm(m, "at_mm") : mark.sides.front().front();
        place(mark, m.has("angle_deg") ? m.number("angle_deg") * std::numbers::pi / 180 : 0.0, at);
      }
      plate.marks.push_back(std::move(mark));
    } else {
      plate.marks.push_back(shape_mark(m));
    }
  }
  if (root.has("labels")) {
    const auto& labels = root.array("labels");
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (!labels[i].is_object()) root.fail("labels", fmt::format("entry {} is not an object", i));
      const core::JsonObject l(labels[i], fmt::format("{}: labels[{}]", path.string(), i));
      plate.labels.push_back({l.string("text"), point_mm(l, "at_mm"), l.has("height_mm") ? l.positive("height_mm") * 1e-3 : 4e-3});
    }
  }
  return plate;
}

}  // namespace stiffpath::vision
