// Plates and marked paths from files: a plate description (JSON) and a mark's path (CSV), ready for the synthetic scanner.
#pragma once

#include <filesystem>
#include <vector>

#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::vision {

//! A marked path read from a CSV file with columns x_mm, y_mm (y down, in marking order; e.g. the
//! digital twin's --marks-csv), repeated points dropped, resampled every 20 µm of its length
//! (resample_path) and cut into `sides` sides at its corners (evaluation::split_polyline; closed when
//! its ends meet). Throws stiffpath::Error naming the file, line and column of a bad value.
PlateMarkPath load_mark_csv(const std::filesystem::path& path, int sides);

//! Reads a plate description (JSON; docs/vision.md "Plates"): page_mm [width, height]; marks, each a
//! nominal shape ("shape": "line" with length_mm, "triangle" with side_mm, "polyline" with
//! vertices_mm and optional closed; optional angle_deg and wiggle_mm, wiggle_wavelength_mm, wiggle_decay_mm) or a path
//! ("path_csv": file relative to the plate file, "sides"), placed with its first point at at_mm
//! (a path without at_mm keeps its own coordinates); labels with text, at_mm (bottom-left) and
//! height_mm. Throws stiffpath::Error naming the file and the field.
Plate load_plate(const std::filesystem::path& path);

}  // namespace stiffpath::vision
