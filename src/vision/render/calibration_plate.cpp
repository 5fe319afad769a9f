// A calibration plate turned into the synthetic scanner's plate: the sheet as the page, fiducials, marked strokes.
#include "stiffpath/vision/render/calibration_plate.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::vision {

Point2 calibration_page_point(const calibration::PlateDesign& plate, const calibration::Vec2& robot_m) {
  return {robot_m.x() - plate.sheet.x_min, plate.sheet.y_max - robot_m.y()};
}

Plate calibration_render_plate(const calibration::PlateDesign& plate, const std::vector<calibration::ObservedMark>& marked) {
  Plate out;
  out.width_m = plate.sheet.x_max - plate.sheet.x_min;
  out.height_m = plate.sheet.y_max - plate.sheet.y_min;
  if (!(out.width_m > 0 && out.height_m > 0)) throw Error("calibration plate: its sheet is empty");
  for (const auto& f : plate.fiducials) {
    out.fiducials.push_back({calibration_page_point(plate, f.centre_m), {f.ring_radius_m, true, f.cross_arm_m}});
  }
  for (const auto& m : marked) {
    const bool known = std::any_of(plate.strokes.begin(), plate.strokes.end(), [&](const auto& s) { return s.id == m.id; });
    if (!known) throw Error(fmt::format("calibration plate: marked path \"{}\" is not a stroke of the plate", m.id));
    std::vector<Point2> page;
    for (const auto& p : m.points_m) {
      const Point2 q = calibration_page_point(plate, p);
      if (!(q.x() >= 0 && q.x() <= out.width_m && q.y() >= 0 && q.y() <= out.height_m)) {
        throw Error(fmt::format("calibration plate: marked path \"{}\" leaves the sheet at x = {:.3f} mm, y = {:.3f} mm",
                                m.id, p.x() * 1e3, p.y() * 1e3));
      }
      page.push_back(q);
    }
    PlateMarkPath path;
    path.sides = {resample_path(page)};
    path.id = m.id;
    out.marks.push_back(std::move(path));
  }
  return out;
}

}  // namespace stiffpath::vision
