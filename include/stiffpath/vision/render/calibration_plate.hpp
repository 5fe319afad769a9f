// A calibration plate as the synthetic scanner draws it: its sheet, its fiducials and each stroke as the robot marked it.
#pragma once

#include <vector>

#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::vision {

//! Where a robot point lies on the plate's sheet (page frame: m from the sheet's top-left corner, x right, y
//! down), the sheet seen from above with the robot frame's x to the right and its y up: (x − x_min, y_max − y)
//! of plate.sheet.
Point2 calibration_page_point(const calibration::PlateDesign& plate, const calibration::Vec2& robot_m);

//! The renderer's plate of a calibration plate as marked: plate.sheet as the page, the plate's fiducials (ring
//! and cross), and each marked path — `marked`, in the robot frame (m), points in marking order (e.g. a twin's
//! marks), given the id of its plate stroke — as a mark of that id, resampled every 20 µm. No bed: set
//! Plate::bed to place the sheet on a scanner. Throws stiffpath::Error for a marked id not on the plate, a path
//! of fewer than two distinct points, or a point off the sheet.
Plate calibration_render_plate(const calibration::PlateDesign& plate, const std::vector<calibration::ObservedMark>& marked);

}  // namespace stiffpath::vision
