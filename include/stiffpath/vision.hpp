// The vision module in one include: scans read with their resolution, marks measured on them, synthetic scans drawn.
#pragma once

#include "stiffpath/vision/io/image_io.hpp"     // load_scan, write_image, PngRowWriter
#include "stiffpath/vision/io/resolution.hpp"   // the resolution stored in PNG, TIFF and JPEG files
#include "stiffpath/vision/render/plate.hpp"    // plate files (JSON) and marked paths (CSV) for the renderer
#include "stiffpath/vision/render/render.hpp"   // render_scan, render_plate: synthetic scans with their ground truth
#include "stiffpath/vision/scan/overlay.hpp"    // draw_overlay: a picture of what was measured
#include "stiffpath/vision/scan/scan.hpp"       // analyse_scan, analyse_plate: the marks' metrics
