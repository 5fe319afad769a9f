// The stored structural fits: each is what the fit gives for its key, and the key changes with anything the fit reads.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/simulation/structural_fit_store.hpp"

namespace stiffpath::simulation {
namespace {

// Every robot whose twin the library ships a fit for. With STIFFPATH_UPDATE_STRUCTURAL_FITS=1 the test writes the
// store anew from fresh fits (after a change to the fit: bump kStructuralFitVersion, run this, commit the file).
const char* const kStoredRobots[] = {"oc-gu", "sc-gu", "oc-gl", "sc-gl"};

TEST(StructuralStore, EveryBuiltInRobotsFitIsStoredAndIsWhatTheFitGives) {
  const auto text = core::find_embedded("twin/structural_fits.json");
  ASSERT_TRUE(text.has_value());
  const nlohmann::json store = nlohmann::json::parse(*text);
  nlohmann::json fresh_store = {{"fit_version", kStructuralFitVersion}, {"fits", nlohmann::json::array()}};
  for (const char* name : kStoredRobots) {
    const kinematics::Robot robot = kinematics::load_robot(name);
    const auto table = compliance::robot_table(robot);
    const std::string key = structural_fit_key(robot, table);
    bool listed = false;
    for (const auto& e : fresh_store["fits"]) listed = listed || e["key"] == key;
    if (listed) continue;  // G_U and G_L share the geometry and the table, so one fit
    const auto fitted = fit_structural_model(robot, table);
    const nlohmann::json fresh = structural_fit_record(*fitted);
    fresh_store["fits"].push_back({{"key", key}, {"robots", name}, {"model", fresh}});
    const nlohmann::json* stored = nullptr;
    for (const auto& e : store.at("fits")) {
      if (e.at("key") == key) stored = &e.at("model");
    }
    if (std::getenv("STIFFPATH_UPDATE_STRUCTURAL_FITS")) continue;
    ASSERT_NE(stored, nullptr) << name << ": no stored fit for key " << key
                               << " (run this test with STIFFPATH_UPDATE_STRUCTURAL_FITS=1)";
    // Where the store was written (this project's machines) the fit reproduces it to the last bit. libm picks
    // its exp/acos/atan2 by the processor's features, so on another processor a last bit may differ; the fit
    // must still land on the same model: C within 1e-9 of itself at every table point.
    if (*stored != fresh) std::printf("%s: the fresh fit differs from the stored one in the last bits\n", name);
    const auto from_store = stored_or_fitted_structural_model(robot, table);
    for (const auto& r : table.rows) {
      const compliance::Vec2 p(r.x_m, r.y_m);
      const compliance::Mat2 want = fitted->compliance(p), got = from_store->compliance(p);
      EXPECT_LE((got - want).norm(), 1e-9 * want.norm()) << name << " at " << r.point;
    }
    EXPECT_EQ(from_store->bounds().x_min, fitted->bounds().x_min);
    EXPECT_EQ(from_store->bounds().y_max, fitted->bounds().y_max);
  }
  if (std::getenv("STIFFPATH_UPDATE_STRUCTURAL_FITS")) {
    std::ofstream(STIFFPATH_SOURCE_DIR "/data/twin/structural_fits.json") << fresh_store.dump(1) << "\n";
    GTEST_SKIP() << "wrote data/twin/structural_fits.json";
  }
}

TEST(StructuralStore, TheKeyChangesWithEverythingTheFitReads) {
  const kinematics::Robot robot = kinematics::load_robot("oc-gu");
  const auto table = compliance::robot_table(robot);
  const std::string key = structural_fit_key(robot, table);
  EXPECT_EQ(key.size(), 64u);
  EXPECT_EQ(structural_fit_key(kinematics::load_robot("oc-gl"), table), key);  // the CG is not the structure's
  EXPECT_NE(structural_fit_key(kinematics::load_robot("sc-gu"), compliance::robot_table(kinematics::load_robot("sc-gu"))), key);
  auto changed = [&](auto&& edit) {
    auto t = table;
    edit(t.rows.at(7));
    return structural_fit_key(robot, t);
  };
  EXPECT_NE(changed([](auto& r) { r.dx_m = *r.dx_m + 1e-12; }), key);
  EXPECT_NE(changed([](auto& r) { r.dy_m.reset(); }), key);
  EXPECT_NE(changed([](auto& r) { r.force_N *= 1.0 + 1e-15; }), key);
  EXPECT_NE(changed([](auto& r) { r.x_m += 1e-9; }), key);
  auto other = robot;
  other.geometry.proximal_m[0] += 1e-6;
  EXPECT_NE(structural_fit_key(other, table), key);
  // The same arms and table with another singularity margin or joint window: other guard points, other angles.
  auto margin = robot;
  margin.margin.min_distance_m += 1e-3;
  EXPECT_NE(structural_fit_key(margin, table), key);
  auto condition = robot;
  condition.margin.max_condition_number *= 2.0;
  EXPECT_NE(structural_fit_key(condition, table), key);
  auto window = robot;
  window.joints[1].min_rad -= 0.1;
  EXPECT_NE(structural_fit_key(window, table), key);
}

TEST(StructuralStore, ARecordReadsBackToTheSameModel) {
  const kinematics::Robot robot = kinematics::load_robot("sc-gu");
  const auto table = compliance::robot_table(robot);
  const auto model = stored_or_fitted_structural_model(robot, table);
  const auto back = structural_model_from_record(robot, nlohmann::json::parse(structural_fit_record(*model).dump()),
                                                 model->bounds());
  EXPECT_EQ(structural_fit_record(*back), structural_fit_record(*model));
  for (const compliance::Vec2& p : {compliance::Vec2(0.2, 0.01), compliance::Vec2(0.26, -0.07)}) {
    EXPECT_EQ(back->compliance(p), model->compliance(p));
  }
  nlohmann::json broken = structural_fit_record(*model);
  broken["arms"][1].erase("distal_axial_per_N");
  EXPECT_THROW((void)structural_model_from_record(robot, broken, model->bounds()), Error);
}

}  // namespace
}  // namespace stiffpath::simulation
