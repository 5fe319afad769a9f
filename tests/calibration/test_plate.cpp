// The calibration plate's layout: every requirement checked independently of how design_plate builds it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <unistd.h>

#include "kept_commands.hpp"
#include "stiffpath/calibration/plate.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {
namespace {

compliance::GridBounds region_of(const kinematics::Robot& robot) {
  return compliance::table_region(compliance::robot_table(robot));
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Whether segments ab and cd share a point (closed segments; the classic orientation test).
bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on segment pq, given collinear
    return std::abs(cross(q - p, r - p)) < 1e-15 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b);
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double f = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + f * d)).norm();
}

class PlateOf : public ::testing::TestWithParam<std::string> {};

TEST_P(PlateOf, MeetsEveryRequirementOfTheDesign) {
  const std::string name = GetParam();
  const auto robot = kinematics::load_robot(name == "asym" ? STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json" : name);
  const auto region = region_of(robot);
  const PlateOptions options;
  const PlateDesign plate = design_plate(robot, region, options);
  EXPECT_EQ(plate.geometry_sha256, robot.geometry_hash());

  // At least three fiducials, at least four places, three directions and two accelerations.
  ASSERT_GE(plate.fiducials.size(), 3u);
  std::set<std::string> stations;
  std::set<long> directions;
  std::set<long> accelerations;
  int timing = 0;
  for (const auto& m : plate.strokes) {
    stations.insert(m.id.substr(0, m.id.find('-')));
    const Vec2 u = (m.end_m - m.start_m).normalized();
    if (m.kind != StrokeKind::arc) directions.insert(std::lround(std::fmod(std::atan2(u.y(), u.x()) * 180.0 / M_PI + 360.0, 180.0)));
    accelerations.insert(std::lround(m.acceleration_m_s2));
    timing += m.kind == StrokeKind::timing;
    EXPECT_LE(m.acceleration_m_s2, options.acceleration_m_s2 + 1e-9);
    // Long enough to show its deflection: a stroke, or a timing stroke's motion (its mark is the middle half, switched
    // at speed), or an arc of at least 180° and 2.5 mm radius.
    if (m.kind == StrokeKind::timing) {
      EXPECT_NEAR(m.run_m, 0.5 * (m.end_m - m.start_m).norm(), 1e-9) << m.id;
      EXPECT_GE((m.end_m - m.start_m).norm() + 2.0 * m.run_m, 5e-3) << m.id;
      const auto motion = m.motion_m();
      ASSERT_EQ(motion.size(), 4u);
      EXPECT_NEAR(cross(motion[3] - motion[0], m.end_m - m.start_m), 0.0, 1e-12) << m.id;  // collinear
    } else if (m.kind == StrokeKind::arc) {
      EXPECT_GE(std::abs(m.sweep_rad), M_PI) << m.id;
      EXPECT_GE((m.start_m - m.centre_m).norm(), 2.5e-3) << m.id;
      EXPECT_NEAR((m.end_m - m.centre_m).norm(), (m.start_m - m.centre_m).norm(), 1e-12) << m.id;
      // Its speed makes the planner's share of the level's acceleration across it: v²/r = 0.7·a.
      EXPECT_NEAR(m.feed_m_s * m.feed_m_s / (m.start_m - m.centre_m).norm(), 0.7 * m.acceleration_m_s2, 1e-6 * m.acceleration_m_s2) << m.id;
    } else {
      EXPECT_GE((m.end_m - m.start_m).norm(), 5e-3) << m.id;
    }
    if (m.kind == StrokeKind::ringing) {  // the tail at right angles to the stroke, to its left
      const Vec2 t = m.tail_end_m - m.end_m;
      EXPECT_NEAR(t.dot(u), 0.0, 1e-12) << m.id;
      EXPECT_GT(cross(u, t), 0.0) << m.id;
    }
  }
  EXPECT_GE(stations.size(), 4u);
  EXPECT_GE(directions.size(), 3u);
  EXPECT_GE(accelerations.size(), 2u);
  EXPECT_GT(timing, 0);
  // An arc per station and acceleration level.
  std::map<std::string, std::set<long>> arcs;
  for (const auto& m : plate.strokes) {
    if (m.kind == StrokeKind::arc) arcs[m.id.substr(0, m.id.find('-'))].insert(std::lround(m.acceleration_m_s2));
  }
  EXPECT_EQ(arcs.size(), stations.size());
  for (const auto& [station, levels] : arcs) EXPECT_EQ(levels.size(), options.acceleration_levels.size()) << station;

  // Spread over the measured region: the stations' centres span most of it along both axes.
  double x_lo = 1e9, x_hi = -1e9, y_lo = 1e9, y_hi = -1e9;
  for (const auto& m : plate.strokes) {
    const Vec2 c = 0.5 * (m.start_m + m.end_m);
    x_lo = std::min(x_lo, c.x()), x_hi = std::max(x_hi, c.x()), y_lo = std::min(y_lo, c.y()), y_hi = std::max(y_hi, c.y());
  }
  EXPECT_GT(x_hi - x_lo, 0.4 * (region.x_max - region.x_min));
  EXPECT_GT(y_hi - y_lo, 0.4 * (region.y_max - region.y_min));

  // One A4 sheet holds everything, inside the region where the robot's model was measured.
  EXPECT_NEAR(std::max(plate.sheet.x_max - plate.sheet.x_min, plate.sheet.y_max - plate.sheet.y_min), 0.297, 1e-12);
  EXPECT_NEAR(std::min(plate.sheet.x_max - plate.sheet.x_min, plate.sheet.y_max - plate.sheet.y_min), 0.210, 1e-12);
  const auto inside = [&](const Vec2& p) {
    return plate.sheet.contains(p) && region.contains(p);
  };
  for (const auto& f : plate.fiducials) {
    EXPECT_TRUE(inside(f.centre_m + Vec2(f.ring_radius_m, f.ring_radius_m)) && inside(f.centre_m - Vec2(f.ring_radius_m, f.ring_radius_m)))
        << f.id;
  }
  // Nothing crosses: no two marks touch, and every mark keeps its distance from every fiducial's ring.
  for (std::size_t i = 0; i < plate.strokes.size(); ++i) {
    const auto a = plate.strokes[i].polyline_m();
    for (const Vec2& p : a) EXPECT_TRUE(inside(p)) << plate.strokes[i].id;
    for (std::size_t j = i + 1; j < plate.strokes.size(); ++j) {
      const auto b = plate.strokes[j].polyline_m();
      for (std::size_t s = 0; s + 1 < a.size(); ++s) {
        for (std::size_t t = 0; t + 1 < b.size(); ++t) {
          ASSERT_FALSE(segments_touch(a[s], a[s + 1], b[t], b[t + 1])) << plate.strokes[i].id << " x " << plate.strokes[j].id;
        }
      }
    }
    for (const auto& f : plate.fiducials) {
      for (std::size_t s = 0; s + 1 < a.size(); ++s) {
        EXPECT_GT(segment_distance(f.centre_m, a[s], a[s + 1]), f.ring_radius_m + 1e-3) << plate.strokes[i].id << " " << f.id;
      }
    }
  }
  // Every point of every mark is one the robot reaches within its joint limits.
  for (const auto& m : plate.strokes) {
    for (const Vec2& p : m.polyline_m()) EXPECT_TRUE(robot.refusal(p).empty()) << m.id;
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, PlateOf, ::testing::Values("oc-gu", "sc-gl", "asym"));

TEST(Plate, FileRoundTripsAndItsGcodeNamesEveryMarkAtItsAcceleration) {
  const auto robot = kinematics::load_robot("oc-gu");
  const PlateDesign plate = design_plate(robot, region_of(robot));
  const auto dir = std::filesystem::temp_directory_path() / ("stiffpath_plate_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  core::write_file_atomically(dir / "plate.json", plate_json(plate));
  const PlateDesign back = load_plate((dir / "plate.json").string());
  ASSERT_EQ(back.strokes.size(), plate.strokes.size());
  for (std::size_t i = 0; i < plate.strokes.size(); ++i) {
    EXPECT_EQ(back.strokes[i].id, plate.strokes[i].id);
    EXPECT_EQ(back.strokes[i].kind, plate.strokes[i].kind);
    EXPECT_LT((back.strokes[i].end_m - plate.strokes[i].end_m).norm(), 1e-9);
    EXPECT_NEAR(back.strokes[i].acceleration_m_s2, plate.strokes[i].acceleration_m_s2, 1e-9);
    EXPECT_NEAR(back.strokes[i].run_m, plate.strokes[i].run_m, 1e-12);
    EXPECT_LT((back.strokes[i].centre_m - plate.strokes[i].centre_m).norm(), 1e-9);
    EXPECT_NEAR(back.strokes[i].sweep_rad, plate.strokes[i].sweep_rad, 1e-12);
  }
  ASSERT_EQ(back.fiducials.size(), plate.fiducials.size());
  const std::string g = plate_gcode(plate);
  for (const auto& m : plate.strokes) EXPECT_NE(g.find("; mark " + m.id + "\n"), std::string::npos);
  EXPECT_NE(g.find("G61"), std::string::npos);  // exact stops: the strokes start and end at rest
  std::filesystem::remove_all(dir);
}

// The plate as the planner runs it (2 kHz samples of the job without compensation): a timing stroke's laser switches
// on and off while the tool moves at the stroke's speed; an arc's middle is turned at 0.7 of its level's acceleration
// (v²/r: the planner keeps the rest for the speed along it).
TEST(Plate, TimingStrokesSwitchTheLaserAtSpeedAndArcsTurnAtTheirAcceleration) {
  const auto robot = kinematics::load_robot("oc-gu");
  const PlateDesign plate = design_plate(robot, region_of(robot));
  job::JobSpec spec = job::default_job(robot);
  spec.compensate = false;
  const auto c = test::commands_of(spec, plate_gcode(plate), "plate.gcode");
  const auto speed = [&](std::size_t k) { return (c[std::min(k + 1, c.size() - 1)].target_m - c[k > 0 ? k - 1 : 0].target_m).norm() * 1000.0; };
  int timing = 0, arcs = 0;
  for (const auto& m : plate.strokes) {
    if (m.kind == StrokeKind::timing) {
      ++timing;
      std::size_t rise = c.size(), fall = c.size();
      for (std::size_t k = 1; k < c.size(); ++k) {
        // (the laser switches at the first 2 kHz sample past the point: within one sample's travel of it)
        if (c[k].laser_on && !c[k - 1].laser_on && (c[k].target_m - m.start_m).norm() < 0.5e-3 * m.feed_m_s + 1e-9) rise = k;
        if (rise < c.size() && k > rise && !c[k].laser_on && c[k - 1].laser_on) {
          fall = k;
          break;
        }
      }
      ASSERT_LT(fall, c.size()) << m.id;
      EXPECT_LT((c[fall].target_m - m.end_m).norm(), 0.5e-3 * m.feed_m_s + 1e-9) << m.id;
      EXPECT_GT(speed(rise), 0.9 * m.feed_m_s) << m.id;
      EXPECT_GT(speed(fall), 0.9 * m.feed_m_s) << m.id;
    } else if (m.kind == StrokeKind::arc) {
      ++arcs;
      const double r = (m.start_m - m.centre_m).norm();
      const Vec2 middle = m.centre_m + (m.start_m - m.centre_m) * std::cos(0.5 * m.sweep_rad) +
                          Vec2(-(m.start_m - m.centre_m).y(), (m.start_m - m.centre_m).x()) * std::sin(0.5 * m.sweep_rad);
      std::size_t at = 0;
      for (std::size_t k = 0; k < c.size(); ++k) {
        if (c[k].laser_on && (c[k].target_m - middle).norm() < (c[at].target_m - middle).norm()) at = k;
      }
      ASSERT_LT((c[at].target_m - middle).norm(), 0.5e-3) << m.id;
      const double v = speed(at);
      EXPECT_GT(v * v / r, 0.68 * m.acceleration_m_s2) << m.id;
      EXPECT_LT(v * v / r, 0.71 * m.acceleration_m_s2) << m.id;
    }
  }
  EXPECT_GT(timing, 0);
  EXPECT_GT(arcs, 0);
}

TEST(Plate, ARegionTooSmallOrBadOptionsAreRefusedWithTheReason) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto region = region_of(robot);
  const compliance::GridBounds tiny{region.x_min, region.x_min + 0.03, region.y_min, region.y_min + 0.03};
  try {
    (void)design_plate(robot, tiny);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("strokes of"), std::string::npos) << e.what();
  }
  PlateOptions two_directions;
  two_directions.directions_deg = {0.0, 90.0};
  EXPECT_THROW((void)design_plate(robot, region, two_directions), Error);
  PlateOptions one_level;
  one_level.acceleration_levels = {1.0};
  EXPECT_THROW((void)design_plate(robot, region, one_level), Error);
}

}  // namespace
}  // namespace stiffpath::calibration
