// Mechanism presets and user files: loading, field-by-field validation, JSON output, limit checks.
#include "stiffpath/kinematics/mechanism_spec.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::kinematics {

namespace {
constexpr std::array<const char*, 4> kPresets = {"oc-gu", "oc-gl", "sc-gu", "sc-gl"};

JointLimit parse_joint(const nlohmann::json& value, const std::string& context) {
  const core::JsonObject j(value, context);
  JointLimit limit;
  limit.name = j.string("name");
  limit.min_rad = units::deg_to_rad(j.number("min_deg"));
  limit.max_rad = units::deg_to_rad(j.number("max_deg"));
  if (!(limit.max_rad > limit.min_rad)) j.fail("max_deg", "must exceed min_deg");
  limit.max_velocity_rad_s = j.positive("max_velocity_rad_s");
  limit.max_acceleration_rad_s2 = j.positive("max_acceleration_rad_s2");
  return limit;
}
}  // namespace

std::vector<std::string> preset_names() { return {kPresets.begin(), kPresets.end()}; }

MechanismSpec parse_mechanism(const nlohmann::json& document, const std::string& label) {
  const core::JsonObject root(document, label);
  MechanismSpec spec;
  spec.name = root.string("name");
  spec.description = root.has("description") ? root.string("description") : "";
  spec.build = root.string("build");
  if (spec.build != "OC" && spec.build != "SC") root.fail("build", "must be \"OC\" or \"SC\", got \"" + spec.build + "\"");
  spec.link_length_m = units::mm_to_m(root.positive("link_length_mm"));
  spec.moving_mass_kg = root.positive("moving_mass_kg");

  const core::JsonObject cg = root.object("cg");
  spec.cg_label = cg.string("label");
  spec.cg_height_m = units::mm_to_m(cg.non_negative("height_above_G_mm"));

  const core::JsonObject meas = root.object("measurement");
  spec.ug_m = units::mm_to_m(meas.positive("UG_mm"));
  spec.ul_m = units::mm_to_m(meas.positive("UL_mm"));
  if (!(spec.ug_m < spec.ul_m)) meas.fail("UG_mm", "must be shorter than UL_mm (G lies between U and L)");

  const auto& joints = root.array("joints");
  if (joints.size() != 2) root.fail("joints", "must list exactly 2 actuated joints, got " + std::to_string(joints.size()));
  for (std::size_t i = 0; i < 2; ++i) spec.joints[i] = parse_joint(joints[i], label + ".joints[" + std::to_string(i) + "]");

  const core::JsonObject margin = root.object("singularity_margin");
  spec.margin.min_distance_m = units::mm_to_m(margin.non_negative("min_distance_mm"));
  spec.margin.max_condition_number = margin.number("max_condition_number");
  if (!(spec.margin.max_condition_number > 1.0)) margin.fail("max_condition_number", "must exceed 1");
  if (!(spec.margin.min_distance_m < spec.link_length_m)) margin.fail("min_distance_mm", "must be shorter than a link");

  spec.compliance_dataset = root.object("compliance").string("dataset");
  spec.source = label;
  return spec;
}

MechanismSpec load_mechanism(const std::string& preset_or_path) {
  for (const char* preset : kPresets) {
    if (preset_or_path == preset) {
      const std::string path = std::string("mechanisms/") + preset + ".json";
      const auto text = core::find_embedded(path);
      if (!text) throw Error("preset '" + preset_or_path + "' is not built into this binary");
      MechanismSpec spec = parse_mechanism(core::parse_json(*text, path), path);
      spec.source = "preset " + preset_or_path;
      return spec;
    }
  }
  if (!std::filesystem::exists(preset_or_path)) {
    std::string known;
    for (const char* preset : kPresets) known += (known.empty() ? "" : ", ") + std::string(preset);
    throw Error("'" + preset_or_path + "' is neither a preset (" + known + ") nor an existing file");
  }
  return parse_mechanism(core::read_json_file(preset_or_path), preset_or_path);
}

nlohmann::json to_json(const MechanismSpec& spec) {
  nlohmann::json joints = nlohmann::json::array();
  for (const auto& j : spec.joints) {
    joints.push_back({{"name", j.name},
                      {"min_deg", units::rad_to_deg(j.min_rad)},
                      {"max_deg", units::rad_to_deg(j.max_rad)},
                      {"max_velocity_rad_s", j.max_velocity_rad_s},
                      {"max_acceleration_rad_s2", j.max_acceleration_rad_s2}});
  }
  return {{"name", spec.name},
          {"description", spec.description},
          {"build", spec.build},
          {"link_length_mm", units::m_to_mm(spec.link_length_m)},
          {"moving_mass_kg", spec.moving_mass_kg},
          {"cg", {{"label", spec.cg_label}, {"height_above_G_mm", units::m_to_mm(spec.cg_height_m)}}},
          {"measurement", {{"UG_mm", units::m_to_mm(spec.ug_m)}, {"UL_mm", units::m_to_mm(spec.ul_m)}}},
          {"joints", joints},
          {"singularity_margin",
           {{"min_distance_mm", units::m_to_mm(spec.margin.min_distance_m)},
            {"max_condition_number", spec.margin.max_condition_number}}},
          {"compliance", {{"dataset", spec.compliance_dataset}}}};
}

}  // namespace stiffpath::kinematics
