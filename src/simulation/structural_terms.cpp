// Parsing a compliance field given in the robot's own terms into a structural model.
#include "stiffpath/simulation/structural_terms.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

namespace {
constexpr const char* kKnown =
    "actuator_rad_per_Nm, proximal_bending_per_Nm2, proximal_axial_m_per_N, distal_axial_m_per_N (per arm: one value "
    "or left/right), base_x_m_per_N, base_y_m_per_N, base_rotation_rad_per_Nm";
// The largest compliance a term may give (SI): a metre per newton is no robot.
constexpr double kMaxTerm = 1.0;

double value_of(const std::string& name, const std::string& text) {
  const auto v = core::parse_double(text);
  if (!v || !(*v >= 0.0 && *v <= kMaxTerm)) {
    throw Error(fmt::format("field term {}: '{}' is not a compliance in [0, {:g}] (SI)", name, text, kMaxTerm));
  }
  return *v;
}
}  // namespace

std::shared_ptr<StructuralModel> structural_model_from_terms(const kinematics::Robot& robot, const std::string& terms,
                                                             const compliance::GridBounds& region) {
  std::array<ArmCompliance, 2> arms{};
  BaseCompliance base;
  std::stringstream all(terms);
  std::string term;
  int count = 0;
  while (std::getline(all, term, ',')) {
    term.erase(0, term.find_first_not_of(' '));
    term.erase(term.find_last_not_of(' ') + 1);
    if (term.empty()) continue;
    const auto eq = term.find('=');
    if (eq == std::string::npos) throw Error(fmt::format("field term '{}': write name=value (known: {})", term, kKnown));
    const std::string name = term.substr(0, eq), value = term.substr(eq + 1);
    const auto slash = value.find('/');
    const std::string left = value.substr(0, slash), right = slash == std::string::npos ? left : value.substr(slash + 1);
    double ArmCompliance::*member = nullptr;
    if (name == "actuator_rad_per_Nm") member = &ArmCompliance::actuator_rad_per_Nm;
    if (name == "proximal_bending_per_Nm2") member = &ArmCompliance::proximal_bending_per_Nm2;
    if (name == "proximal_axial_m_per_N") member = &ArmCompliance::proximal_axial_per_N;
    if (name == "distal_axial_m_per_N") member = &ArmCompliance::distal_axial_per_N;
    if (member) {
      arms[0].*member = value_of(name, left);
      arms[1].*member = value_of(name, right);
    } else if (slash != std::string::npos) {
      throw Error(fmt::format("field term {}: the frame has one value, not left/right", name));
    } else if (name == "base_x_m_per_N") {
      base.x_m_per_N = value_of(name, value);
    } else if (name == "base_y_m_per_N") {
      base.y_m_per_N = value_of(name, value);
    } else if (name == "base_rotation_rad_per_Nm") {
      base.rotation_rad_per_Nm = value_of(name, value);
    } else {
      throw Error(fmt::format("field term '{}': unknown name (known: {})", name, kKnown));
    }
    ++count;
  }
  if (count == 0) throw Error(fmt::format("no field terms given (known: {})", kKnown));
  return std::make_shared<StructuralModel>(robot, arms, region, base);
}

}  // namespace stiffpath::simulation
