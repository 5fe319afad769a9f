// Structural fits kept with the data they were fitted to (data/twin/structural_fits.json), keyed by what the fit reads.
#include "stiffpath/simulation/structural_fit_store.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/sha256.hpp"

namespace stiffpath::simulation {
namespace {

constexpr const char* kStorePath = "twin/structural_fits.json";

const char* const kArmKeys[ArmCompliance::count] = {"actuator_rad_per_Nm",  "proximal_bending_per_Nm2",
                                                    "proximal_axial_per_N", "distal_axial_per_N",
                                                    "proximal_bar_m_per_N", "distal_bar_m_per_N"};

compliance::Vec2 vec2(const nlohmann::json& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }

}  // namespace

std::string structural_fit_key(const kinematics::Robot& robot, const measurement::DisplacementTable& table) {
  const auto& g = robot.geometry;
  std::string text = fmt::format("structural-fit {}\ngeometry {}\n", kStructuralFitVersion, robot.geometry_hash());
  for (std::size_t i = 0; i < 2; ++i) {  // the hash rounds to 1 nm; the fit reads the exact values
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", g.actuator_m[i].x(), g.actuator_m[i].y(), g.proximal_m[i],
                        g.distal_m[i]);
  }
  // The fit solves the inverse kinematics of robot.five_bar(): the margin decides which guard points are reachable,
  // the joints' lower limits the window the angles are wrapped into.
  const auto& m = robot.margin;
  text += fmt::format("margin {:.17g},{:.17g},{:.17g}\nangle floor {:.17g},{:.17g}\n", m.min_distance_m,
                      m.max_condition_number, m.min_distal_angle_rad, robot.joints[0].min_rad, robot.joints[1].min_rad);
  const auto number = [](const std::optional<double>& v) { return v ? fmt::format("{:.17g}", *v) : std::string("-"); };
  for (const auto& r : table.rows) {
    text += fmt::format("{},{:.17g},{:.17g},{},{:.17g},{},{}\n", r.point, r.x_m, r.y_m, measurement::to_string(r.direction),
                        r.force_N, number(r.dx_m), number(r.dy_m));
  }
  return core::sha256_hex(text);
}

nlohmann::json structural_fit_record(const StructuralModel& model) {
  nlohmann::json arms = nlohmann::json::array();
  for (const ArmCompliance& a : model.arms()) {
    nlohmann::json arm;
    for (int k = 0; k < ArmCompliance::count; ++k) arm[kArmKeys[k]] = a[k];
    arm["proximal_bar_offset_m"] = {a.proximal_bar_offset_m.x(), a.proximal_bar_offset_m.y()};
    arm["distal_bar_offset_m"] = {a.distal_bar_offset_m.x(), a.distal_bar_offset_m.y()};
    arms.push_back(arm);
  }
  const BaseCompliance& b = model.base();
  return {{"arms", arms},
          {"base", {{"x_m_per_N", b.x_m_per_N}, {"y_m_per_N", b.y_m_per_N}, {"rotation_rad_per_Nm", b.rotation_rad_per_Nm}}},
          {"measured_offset_m", {model.measured_offset().x(), model.measured_offset().y()}}};
}

std::shared_ptr<StructuralModel> structural_model_from_record(const kinematics::Robot& robot, const nlohmann::json& record,
                                                              const compliance::GridBounds& region) {
  try {
    std::array<ArmCompliance, 2> arms;
    for (std::size_t i = 0; i < 2; ++i) {
      const nlohmann::json& arm = record.at("arms").at(i);
      for (int k = 0; k < ArmCompliance::count; ++k) arms[i][k] = arm.at(kArmKeys[k]).get<double>();
      arms[i].proximal_bar_offset_m = vec2(arm.at("proximal_bar_offset_m"));
      arms[i].distal_bar_offset_m = vec2(arm.at("distal_bar_offset_m"));
    }
    const nlohmann::json& b = record.at("base");
    const BaseCompliance base{b.at("x_m_per_N").get<double>(), b.at("y_m_per_N").get<double>(),
                              b.at("rotation_rad_per_Nm").get<double>()};
    return std::make_shared<StructuralModel>(robot, arms, region, base, vec2(record.at("measured_offset_m")));
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("structural fit record: {}", e.what()));
  }
}

std::shared_ptr<StructuralModel> stored_or_fitted_structural_model(const kinematics::Robot& robot,
                                                                   const measurement::DisplacementTable& table) {
  if (const auto text = core::find_embedded(kStorePath)) {
    const nlohmann::json store = nlohmann::json::parse(*text);
    const std::string key = structural_fit_key(robot, table);
    for (const nlohmann::json& entry : store.at("fits")) {
      if (entry.at("key").get<std::string>() == key) {
        return structural_model_from_record(robot, entry.at("model"), compliance::table_region(table));
      }
    }
  }
  return fit_structural_model(robot, table);
}

}  // namespace stiffpath::simulation
