// A calibration plate rendered from known marked paths, turned and mirrored on the bed: registered, and each stroke measured in robot metres against the paths drawn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <unistd.h>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/segment_distance.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/render/calibration_plate.hpp"
#include "stiffpath/vision/scan/plate_marks.hpp"

namespace stiffpath::vision {
namespace {

using calibration::ObservedMark;
using calibration::PlateDesign;
using calibration::StrokeKind;
using calibration::StrokeMark;
using calibration::Vec2;

constexpr double kPi = std::numbers::pi;

StrokeMark stroke(const std::string& id, StrokeKind kind, Vec2 start_mm, double deg, double length_mm, double tail_mm) {
  const Vec2 u(std::cos(deg * kPi / 180), std::sin(deg * kPi / 180)), n(-u.y(), u.x());
  StrokeMark m;
  m.id = id;
  m.kind = kind;
  m.start_m = start_mm * 1e-3;
  m.end_m = m.start_m + length_mm * 1e-3 * u;
  m.tail_end_m = m.end_m + tail_mm * 1e-3 * n;
  return m;
}

// A 70 × 50 mm sheet (robot frame, y up) with four fiducials on the corners of a rectangle (a symmetric layout:
// the strokes must tell its placements apart), two ringing strokes and a timing stroke.
PlateDesign small_plate() {
  PlateDesign plate;
  plate.robot = "test";
  plate.sheet = {0.100, 0.170, 0.050, 0.100};
  plate.area = plate.sheet;
  const Vec2 corners_mm[4] = {{108, 58}, {162, 58}, {162, 92}, {108, 92}};
  for (int k = 0; k < 4; ++k) {
    calibration::FiducialMark f;
    f.id = "F" + std::to_string(k + 1);
    f.centre_m = corners_mm[k] * 1e-3;
    plate.fiducials.push_back(f);
  }
  plate.strokes = {stroke("S1-D000-A1-R", StrokeKind::ringing, {112, 64}, 0, 18, 4),
                   stroke("S1-D120-A1-R", StrokeKind::ringing, {152, 62}, 120, 14, 4),
                   stroke("S1-D000-A1-T", StrokeKind::timing, {118, 81}, 0, 30, 0)};
  return plate;
}

// What the robot marked: each stroke bent sideways by a smooth bump (120 µm), its start and end moved along it
// (the laser's timing, the overshoot), and the tail waving along the stroke's direction with a decaying ringing.
std::vector<ObservedMark> marked_paths(const PlateDesign& plate) {
  std::vector<ObservedMark> out;
  for (const auto& s : plate.strokes) {
    const Vec2 d = s.end_m - s.start_m;
    const double length = d.norm();
    const Vec2 u = d / length, n(-u.y(), u.x());
    const bool timing = s.kind == StrokeKind::timing;
    const double early = timing ? -60e-6 : 40e-6, late = timing ? 90e-6 : 0.0;  // start and end moved along u
    ObservedMark m{s.id, {}};
    const int steps = 2000;
    for (int k = 0; k <= steps; ++k) {
      const double f = static_cast<double>(k) / steps;
      const double along = early + f * (length + late - early);
      m.points_m.push_back(s.start_m + along * u + 120e-6 * std::sin(kPi * f) * n);
    }
    if (!timing) {
      const Vec2 t = s.tail_end_m - s.end_m;
      const double tail = t.norm();
      for (int k = 1; k <= steps; ++k) {
        const double a = tail * k / steps;
        const double wave = 150e-6 * std::exp(-a / 1.5e-3) * std::sin(2 * kPi * a / 1.2e-3);
        m.points_m.push_back(s.end_m + a * t / tail + wave * u);
      }
    }
    out.push_back(std::move(m));
  }
  return out;
}


Plate on_bed(const PlateDesign& design, const std::vector<ObservedMark>& marked, double angle_deg, bool mirror) {
  Plate plate = calibration_render_plate(design, marked);
  ScannerBed bed;
  bed.width_m = 80e-3;
  bed.height_m = 62e-3;
  bed.page_at_m = {6e-3, 5e-3};
  bed.page_angle_rad = angle_deg * kPi / 180;
  bed.mirror = mirror;
  plate.bed = bed;
  return plate;
}

// A calibration plate as laid out for a robot (an A4 sheet) on a bed 16 mm larger than the page, its corner at `at`.
Plate sheet_on_bed(const PlateDesign& design, const std::vector<ObservedMark>& marked, Vec2 at, double angle_deg, bool mirror) {
  Plate plate = calibration_render_plate(design, marked);
  ScannerBed bed;
  bed.width_m = plate.width_m + 16e-3;
  bed.height_m = plate.height_m + 16e-3;
  bed.page_at_m = at;
  bed.page_angle_rad = angle_deg * kPi / 180;
  bed.mirror = mirror;
  plate.bed = bed;
  return plate;
}

RenderOptions scanner(double dpi, std::uint64_t seed) {
  RenderOptions o;
  o.dpi = dpi;
  o.seed = seed;
  return o;
}

// The accuracy case (1200 dpi, page turned 2.5°): the registration within 10 µm, every stroke's centre line within
// 5 µm rms of the path drawn, and its two ends within 10 µm of the drawn ends.
TEST(PlateMarks, RegisteredStrokesMatchThePathsDrawnInRobotMetres) {
  const PlateDesign design = small_plate();
  const auto truth = marked_paths(design);
  const RenderedPlate rendered = render_plate(on_bed(design, truth, 2.5, false), scanner(1200, 31));
  const PlateObservation seen = observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
  for (const auto& w : seen.warnings) std::printf("[warning] %s\n", w.c_str());
  const PlateRegistration& reg = seen.registration;
  std::printf("[accuracy] registration: %d fiducials, residual %.3f um rms, %.3f um max, %s\n", reg.fiducials,
              reg.residual_rms_m * 1e6, reg.residual_max_m * 1e6, reg.mirrored ? "mirrored" : "not mirrored");
  EXPECT_EQ(reg.fiducials, 4);
  EXPECT_FALSE(reg.mirrored);  // the sheet as seen from above: y down on the image, up in the robot frame
  EXPECT_NEAR(reg.linear.determinant(), -1.0, 1e-12);
  EXPECT_LE(reg.residual_rms_m, 10e-6);
  // The renderer's placement, page → image, composed with page → robot is the truth of scan → robot.
  for (const auto& f : design.fiducials) {
    const Point2 image = rendered.placement.apply(calibration_page_point(design, f.centre_m));
    EXPECT_LT((reg.to_robot(image) - f.centre_m).norm(), 5e-6) << f.id;
  }
  ASSERT_EQ(seen.marks.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& got = seen.marks[i];
    EXPECT_EQ(got.id, truth[i].id);
    ASSERT_GT(got.points_m.size(), 100u) << got.id;
    double sum2 = 0, worst = 0;
    for (const auto& p : got.points_m) {
      const double e = evaluation::polyline_distance(p, truth[i].points_m);
      sum2 += e * e;
      worst = std::max(worst, e);
    }
    const double rms = std::sqrt(sum2 / static_cast<double>(got.points_m.size()));
    const double start = (got.points_m.front() - truth[i].points_m.front()).norm();
    const double end = (got.points_m.back() - truth[i].points_m.back()).norm();
    std::printf("[accuracy] %s: %zu points, %.2f um rms (max %.2f um) from the path drawn; start off by %.2f um, end by %.2f um\n",
                got.id.c_str(), got.points_m.size(), rms * 1e6, worst * 1e6, start * 1e6, end * 1e6);
    EXPECT_LE(rms, 5e-6) << got.id;
    EXPECT_LE(start, 10e-6) << got.id;
    EXPECT_LE(end, 10e-6) << got.id;
  }
}

// Mirrored by the scanner, at 600 dpi: found mirrored, the same placement as the renderer's, every stroke in order.
TEST(PlateMarks, AMirroredScanIsRegisteredWithItsMirror) {
  const PlateDesign design = small_plate();
  const auto truth = marked_paths(design);
  const RenderedPlate rendered = render_plate(on_bed(design, truth, -3.0, true), scanner(600, 32));
  const PlateObservation seen = observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
  EXPECT_TRUE(seen.registration.mirrored);
  EXPECT_NEAR(seen.registration.linear.determinant(), 1.0, 1e-12);
  EXPECT_LE(seen.registration.residual_rms_m, 10e-6);
  for (const auto& f : design.fiducials) {
    const Point2 image = rendered.placement.apply(calibration_page_point(design, f.centre_m));
    EXPECT_LT((seen.registration.to_robot(image) - f.centre_m).norm(), 10e-6) << f.id;
  }
  ASSERT_EQ(seen.marks.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_EQ(seen.marks[i].id, truth[i].id);
    EXPECT_LT((seen.marks[i].points_m.front() - truth[i].points_m.front()).norm(), 30e-6) << truth[i].id;
    EXPECT_LT((seen.marks[i].points_m.back() - truth[i].points_m.back()).norm(), 30e-6) << truth[i].id;
  }
}

// A stroke the robot did not mark: the others measured, a warning naming it.
TEST(PlateMarks, AMissingStrokeIsNamedInAWarning) {
  const PlateDesign design = small_plate();
  auto truth = marked_paths(design);
  truth.erase(truth.begin() + 1);
  const RenderedPlate rendered = render_plate(on_bed(design, truth, 1.0, false), scanner(400, 33));
  const PlateObservation seen = observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
  ASSERT_EQ(seen.marks.size(), 2u);
  EXPECT_EQ(seen.marks[0].id, "S1-D000-A1-R");
  EXPECT_EQ(seen.marks[1].id, "S1-D000-A1-T");
  bool named = false;
  for (const auto& w : seen.warnings) named |= w.find("S1-D120-A1-R") != std::string::npos && w.find("not measured") != std::string::npos;
  EXPECT_TRUE(named);
}

std::string refusal(const PlateDesign& design, const Plate& plate) {
  const RenderedPlate rendered = render_plate(plate, scanner(400, 34));
  try {
    observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A fiducial missing (not marked, or covered): refused, naming the file and how many were found.
TEST(PlateMarks, AMissingFiducialIsRefusedWithTheReason) {
  const PlateDesign design = small_plate();
  Plate plate = on_bed(design, marked_paths(design), 1.0, false);
  plate.fiducials.erase(plate.fiducials.begin() + 2);
  const std::string why = refusal(design, plate);
  EXPECT_NE(why.find("plate.png"), std::string::npos) << why;
  EXPECT_NE(why.find("fiducials missing: found 3"), std::string::npos) << why;
}

// A symmetric layout and no stroke to tell its placements apart: ambiguous, refused with both candidates.
TEST(PlateMarks, ASymmetricLayoutWithoutStrokesIsAmbiguous) {
  const PlateDesign design = small_plate();
  const std::string why = refusal(design, on_bed(design, {}, 1.0, false));
  EXPECT_NE(why.find("ambiguous"), std::string::npos) << why;
  EXPECT_NE(why.find("F1"), std::string::npos) << why;
}

// Fiducials where no rigid motion puts them (the scan's scale is not the resolution's): refused with the residual.
TEST(PlateMarks, AScanAtAnotherScaleIsRefusedWithItsResidual) {
  const PlateDesign design = small_plate();
  const RenderedPlate rendered = render_plate(on_bed(design, marked_paths(design), 1.0, false), scanner(400, 35));
  try {
    observe_calibration_plate(design, rendered.image, rendered.dpi * 1.01, "plate.png");
    FAIL() << "a scan 1 % off in scale was registered";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit the plate's by any rigid motion"), std::string::npos) << e.what();
  }
}

// The plate `calibrate plate` lays out for a preset (an A4 sheet, four fiducials on a rectangle's corners, strokes
// in a grid of cells), each stroke marked as commanded, mirrored and turned on the bed, at 300 dpi: the strokes tell
// the rectangle's four placements apart, and every stroke is found on its command.
TEST(PlateMarks, ThePresetsPlateIsRegisteredAndEveryStrokeFound) {
  const auto robot = kinematics::load_robot("oc-gu");
  const PlateDesign design = calibration::design_plate(robot, compliance::table_region(compliance::robot_table(robot)));
  std::vector<ObservedMark> commanded;
  for (const auto& s : design.strokes) commanded.push_back({s.id, s.polyline_m()});
  const RenderedPlate rendered = render_plate(sheet_on_bed(design, commanded, {11e-3, 4e-3}, 1.5, true), scanner(300, 36));
  const PlateObservation seen = observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
  std::printf("[info] %zu warnings at %.0f dpi (sharp corners, ends not round at this resolution)\n", seen.warnings.size(),
              rendered.dpi);
  EXPECT_TRUE(seen.registration.mirrored);
  EXPECT_LE(seen.registration.residual_rms_m, 10e-6);
  ASSERT_EQ(seen.marks.size(), design.strokes.size());
  double worst = 0, worst_end = 0;
  for (std::size_t i = 0; i < design.strokes.size(); ++i) {
    EXPECT_EQ(seen.marks[i].id, design.strokes[i].id);
    for (const auto& p : seen.marks[i].points_m) worst = std::max(worst, evaluation::polyline_distance(p, commanded[i].points_m));
    if (design.strokes[i].kind == calibration::StrokeKind::arc) continue;  // measured 1 mm short of its ends
    worst_end = std::max({worst_end, (seen.marks[i].points_m.front() - commanded[i].points_m.front()).norm(),
                          (seen.marks[i].points_m.back() - commanded[i].points_m.back()).norm()});
  }
  std::printf("[accuracy] %zu strokes at %.0f dpi: farthest point %.2f um from its command, farthest end %.2f um\n",
              design.strokes.size(), rendered.dpi, worst * 1e6, worst_end * 1e6);
  // 300 dpi keeps the test quick; a pixel is 85 µm, the mark 2.4 px wide (600 dpi: 8.3 µm, both).
  EXPECT_LT(worst, 60e-6);
  EXPECT_LT(worst_end, 80e-6);
}

// The plate's arcs drawn exactly on their circles (the page turned on the bed), at 600 and 1200 dpi: the radial
// profiles put the centre line on the circle, without a bias in or out (a bias would read as a deflection).
TEST(PlateMarks, AnArcIsMeasuredOnItsCircleWithoutABias) {
  const auto robot = kinematics::load_robot("oc-gu");
  const PlateDesign design = calibration::design_plate(robot, compliance::table_region(compliance::robot_table(robot)));
  std::vector<ObservedMark> drawn;
  for (const auto& s : design.strokes) {
    if (s.kind != calibration::StrokeKind::arc) continue;
    ObservedMark m{s.id, {}};
    const Vec2 r0 = s.start_m - s.centre_m;
    for (int k = 0; k <= 2000; ++k) {  // 0.13° apart: chords 15 µm long, 4 nm from the circle
      const double a = s.sweep_rad * k / 2000.0;
      m.points_m.push_back(s.centre_m + Vec2(std::cos(a) * r0.x() - std::sin(a) * r0.y(), std::sin(a) * r0.x() + std::cos(a) * r0.y()));
    }
    drawn.push_back(std::move(m));
  }
  for (const double dpi : {600.0, 1200.0}) {
    const RenderedPlate rendered = render_plate(sheet_on_bed(design, drawn, {9e-3, 6e-3}, 0.8, false), scanner(dpi, 41));
    const PlateObservation seen = observe_calibration_plate(design, rendered.image, rendered.dpi, "plate.png");
    double sum = 0, sum2 = 0, worst = 0;
    std::size_t n = 0;
    for (const auto& m : seen.marks) {
      const auto it = std::find_if(design.strokes.begin(), design.strokes.end(), [&](const auto& s) { return s.id == m.id; });
      ASSERT_NE(it, design.strokes.end());
      if (it->kind != calibration::StrokeKind::arc) continue;
      const double r = (it->start_m - it->centre_m).norm();
      EXPECT_GT(m.points_m.size(), static_cast<std::size_t>(0.9 * (std::abs(it->sweep_rad) * r - 2e-3) / 0.1e-3)) << m.id;
      for (const auto& p : m.points_m) {
        const double e = (p - it->centre_m).norm() - r;
        sum += e, sum2 += e * e, worst = std::max(worst, std::abs(e)), ++n;
      }
    }
    ASSERT_GT(n, 0u);
    const double rms = std::sqrt(sum2 / n);
    std::printf("[accuracy] arcs at %.0f dpi: %zu points, mean radial error %+.3f um, rms %.2f um, largest %.2f um\n",
                dpi, n, sum / n * 1e6, rms * 1e6, worst * 1e6);
    // No bias (it would read as a deflection); the scatter (the paper's grain) within the identification's 3 µm.
    EXPECT_LT(std::abs(sum / n), 0.5e-6);
    EXPECT_LT(rms, 3e-6);
    EXPECT_LT(worst, 10e-6);
  }
}

// From a file: its resolution read from the file, the same marks as from memory; a file without one refused.
TEST(PlateMarks, AScanFileGivesItsResolutionOrIsRefused) {
  const PlateDesign design = small_plate();
  const RenderedPlate rendered = render_plate(on_bed(design, marked_paths(design), 1.0, false), scanner(400, 37));
  const auto dir = std::filesystem::temp_directory_path() / ("stiffpath_plate_marks_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_image(dir / "plate.png", rendered.image, rendered.dpi);
  cv::imwrite((dir / "bare.png").string(), rendered.image);  // no pHYs chunk
  const PlateObservation from_file = observe_calibration_plate(design, dir / "plate.png");
  const PlateObservation from_memory = observe_calibration_plate(design, rendered.image, rendered.dpi, "x");
  ASSERT_EQ(from_file.marks.size(), from_memory.marks.size());
  for (std::size_t i = 0; i < from_file.marks.size(); ++i) {
    EXPECT_EQ(from_file.marks[i].points_m, from_memory.marks[i].points_m);
  }
  try {
    observe_calibration_plate(design, dir / "bare.png");
    ADD_FAILURE() << "a scan without a resolution was registered";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bare.png: the file stores no resolution"), std::string::npos) << e.what();
  }
  PlateScanOptions given;
  given.dpi = rendered.dpi;
  EXPECT_EQ(observe_calibration_plate(design, dir / "bare.png", given).marks.size(), design.strokes.size());
  std::filesystem::remove_all(dir);
}

// The page frame: the sheet seen from above, robot y up.
TEST(PlateMarks, ThePageFrameIsTheSheetSeenFromAbove) {
  const PlateDesign design = small_plate();
  EXPECT_LT(calibration_page_point(design, {0.100, 0.100}).norm(), 1e-15);
  EXPECT_LT((calibration_page_point(design, {0.170, 0.050}) - Point2(0.070, 0.050)).norm(), 1e-15);
  EXPECT_THROW(calibration_render_plate(design, {{"S9", {{0.11, 0.06}, {0.12, 0.06}}}}), Error);
  EXPECT_THROW(calibration_render_plate(design, {{"S1-D000-A1-T", {{0.11, 0.06}, {0.19, 0.06}}}}), Error);
}

}  // namespace
}  // namespace stiffpath::vision
