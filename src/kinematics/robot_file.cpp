// Robot files: field-by-field validation with located errors, unknown keys refused, and JSON output.
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <numbers>
#include <nlohmann/json.hpp>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::kinematics {

namespace {
// Physical ranges of a robot's numbers (docs/kinematics.md): a planar robot within 10 m, a platform of
// 1 g to 1 t, drives up to 10^4 rad/s and 10^8 rad/s^2.
constexpr double max_length_mm = 1e4;
constexpr double min_link_mm = 1.0;
constexpr double min_mass_kg = 1e-3, max_mass_kg = 1e3;
constexpr double max_cg_height_mm = 1e3;
constexpr double max_joint_velocity_rad_s = 1e4, max_joint_acceleration_rad_s2 = 1e8;

Vec2 point_mm(const core::JsonObject& obj, std::string_view key) {
  const auto [x, y] = obj.pair(key);
  if (!(std::abs(x) <= max_length_mm && std::abs(y) <= max_length_mm)) {
    obj.fail(key, fmt::format("RANGE: [{:g}, {:g}] mm lies beyond ±{:g} mm", x, y, max_length_mm));
  }
  return {units::mm_to_m(x), units::mm_to_m(y)};
}

double link_m(const core::JsonObject& obj, std::string_view key) {
  (void)obj.positive(key);  // "must be positive" before the range
  return units::mm_to_m(obj.within(key, min_link_mm, max_length_mm, "mm"));
}

JointLimit parse_joint(const core::JsonObject& j) {
  j.allow_only({"name", "min_deg", "max_deg", "max_velocity_rad_s", "max_acceleration_rad_s2"});
  JointLimit limit;
  limit.name = j.string("name");
  limit.min_rad = units::deg_to_rad(j.number("min_deg"));
  limit.max_rad = units::deg_to_rad(j.number("max_deg"));
  if (!(limit.max_rad > limit.min_rad)) j.fail("max_deg", "must exceed min_deg");
  if (limit.max_rad - limit.min_rad > 2.0 * std::numbers::pi) j.fail("max_deg", "must lie within 360 deg of min_deg");
  limit.max_velocity_rad_s = j.positive("max_velocity_rad_s");
  limit.max_acceleration_rad_s2 = j.positive("max_acceleration_rad_s2");
  (void)j.within("max_velocity_rad_s", 0.0, max_joint_velocity_rad_s, "rad/s");
  (void)j.within("max_acceleration_rad_s2", 0.0, max_joint_acceleration_rad_s2, "rad/s^2");
  return limit;
}

FiveBarGeometry parse_geometry(const core::JsonObject& root) {
  FiveBarGeometry g;
  g.actuator_m = {point_mm(root, "left_actuator_mm"), point_mm(root, "right_actuator_mm")};
  g.proximal_m = {link_m(root, "left_proximal_mm"), link_m(root, "right_proximal_mm")};
  g.distal_m = {link_m(root, "left_distal_mm"), link_m(root, "right_distal_mm")};
  const auto& elbows = root.array("elbows");
  if (elbows.size() != 2) root.fail("elbows", "must be [s_left, s_right] with each +1 or -1, got " + core::shown(elbows));
  for (std::size_t i = 0; i < 2; ++i) {
    if (!elbows[i].is_number() || (elbows[i].get<double>() != 1.0 && elbows[i].get<double>() != -1.0)) {
      root.fail("elbows", "must be [s_left, s_right] with each +1 or -1, got " + core::shown(elbows));
    }
    g.elbows[i] = elbows[i].get<double>() > 0 ? 1 : -1;
  }
  g.assembly = root.has("assembly") ? root.sign("assembly") : 1;
  if (root.has("joint_zero_offsets_deg")) {
    const auto [d1, d2] = root.pair("joint_zero_offsets_deg");
    for (const double d : {d1, d2}) {
      if (!(std::abs(d) <= kMaxJointZeroOffset_deg)) {
        root.fail("joint_zero_offsets_deg",
                  fmt::format("each offset must lie within +-{:g} deg, got {}", kMaxJointZeroOffset_deg, d));
      }
    }
    g.joint_zero_rad = {units::deg_to_rad(d1), units::deg_to_rad(d2)};
  }
  return g;
}

// Hints for keys that older mechanism files used.
const std::map<std::string, std::string, std::less<>> kHints = {
    {"link_length_mm", "give left_proximal_mm, right_proximal_mm, left_distal_mm and right_distal_mm"},
    {"build", "name the table's rows with compliance.rows"},
    {"dataset", "use table"},
};
}  // namespace

Robot parse_robot(std::string_view text, const core::DataRef& file) {
  const core::JsonDocument doc = core::parse_json_document(text, file.label());
  const core::JsonObject root(doc);
  root.allow_only({"name", "description", "left_actuator_mm", "right_actuator_mm", "left_proximal_mm",
                   "right_proximal_mm", "left_distal_mm", "right_distal_mm", "elbows", "assembly",
                   "joint_zero_offsets_deg", "moving_mass_kg", "tip_damping_ratio", "tip_frequency_scale", "laser", "cg",
                   "measurement", "joints", "singularity_margin", "home_mm", "compliance"},
                  kHints);
  Robot robot;
  robot.file = file;
  robot.name = root.has("name") ? root.string("name") : std::filesystem::path(file.path).stem().string();
  if (robot.name.empty()) root.fail("name", "must not be empty");
  robot.description = root.has("description") ? root.string("description") : "";
  robot.geometry = parse_geometry(root);
  robot.moving_mass_kg = root.positive("moving_mass_kg");
  (void)root.within("moving_mass_kg", min_mass_kg, max_mass_kg, "kg");
  if (root.has("tip_damping_ratio")) {
    robot.tip_damping_ratio = root.non_negative("tip_damping_ratio");
    if (!(robot.tip_damping_ratio < 1.0)) root.fail("tip_damping_ratio", fmt::format("must be below 1 (an underdamped mode), got {}", robot.tip_damping_ratio));
  }
  if (root.has("tip_frequency_scale")) {
    robot.tip_frequency_scale = root.positive("tip_frequency_scale");
    if (!(robot.tip_frequency_scale >= 0.2 && robot.tip_frequency_scale <= 5.0)) {
      root.fail("tip_frequency_scale", fmt::format("RANGE: must lie in 0.2 … 5, got {}", robot.tip_frequency_scale));
    }
  }
  if (root.has("laser")) {
    const core::JsonObject laser = root.object("laser");
    laser.allow_only({"on_delay_ms", "off_delay_ms"});
    for (const auto& [key, field] : {std::pair{"on_delay_ms", &robot.laser_on_delay_s}, std::pair{"off_delay_ms", &robot.laser_off_delay_s}}) {
      if (!laser.has(key)) continue;
      const double ms = laser.number(key);
      if (!(ms >= -50.0 && ms <= 50.0)) laser.fail(key, fmt::format("RANGE: must lie within ±50 ms, got {}", ms));
      *field = ms * 1e-3;
    }
  }

  if (root.has("cg")) {
    const core::JsonObject cg = root.object("cg");
    cg.allow_only({"label", "height_above_G_mm"});
    robot.cg_label = cg.has("label") ? cg.string("label") : "G";
    robot.cg_height_m = units::mm_to_m(cg.non_negative("height_above_G_mm"));
    (void)cg.within("height_above_G_mm", 0.0, max_cg_height_mm, "mm");
  }
  if (root.has("measurement")) {
    const core::JsonObject meas = root.object("measurement");
    meas.allow_only({"UG_mm", "UL_mm"});
    ReplicaLevers levers{units::mm_to_m(meas.positive("UG_mm")), units::mm_to_m(meas.positive("UL_mm"))};
    (void)meas.within("UL_mm", 0.0, max_length_mm, "mm");
    if (!(levers.ug_m < levers.ul_m)) meas.fail("UG_mm", "must be shorter than UL_mm (G lies between U and L)");
    robot.replica = levers;
  }

  const auto& joints = root.array("joints");
  if (joints.size() != 2) root.fail("joints", "must list exactly 2 actuated joints, got " + std::to_string(joints.size()));
  for (std::size_t i = 0; i < 2; ++i) robot.joints[i] = parse_joint(root.element("joints", i));

  if (root.has("singularity_margin")) {
    const core::JsonObject margin = root.object("singularity_margin");
    margin.allow_only({"min_distance_mm", "max_condition_number", "min_distal_angle_deg"});
    if (margin.has("min_distance_mm")) robot.margin.min_distance_m = units::mm_to_m(margin.non_negative("min_distance_mm"));
    if (margin.has("max_condition_number")) {
      robot.margin.max_condition_number = margin.number("max_condition_number");
      if (!(robot.margin.max_condition_number > 1.0)) margin.fail("max_condition_number", "must exceed 1");
    }
    if (margin.has("min_distal_angle_deg")) {
      const double deg = margin.non_negative("min_distal_angle_deg");
      if (!(deg < 90.0)) margin.fail("min_distal_angle_deg", "must be below 90");
      robot.margin.min_distal_angle_rad = units::deg_to_rad(deg);
    }
    const double shortest = std::min({robot.geometry.proximal_m[0], robot.geometry.proximal_m[1],
                                      robot.geometry.distal_m[0], robot.geometry.distal_m[1]});
    if (!(robot.margin.min_distance_m < shortest)) margin.fail("min_distance_mm", "must be shorter than every link");
  }
  if (root.has("home_mm")) robot.home_m = point_mm(root, "home_mm");

  if (root.has("compliance")) {
    const core::JsonObject c = root.object("compliance");
    c.allow_only({"table", "rows", "model", "method"}, kHints);
    if (c.has("table")) robot.compliance.table = core::resolve_beside(file, c.string("table"));
    if (c.has("rows")) robot.compliance.rows = c.string("rows");
    if (c.has("model")) robot.compliance.model = core::resolve_beside(file, c.string("model"));
    for (const char* key : {"rows", "method"}) {
      if (c.has(key) && !c.has("table")) c.fail(key, "applies to a table, and this robot names none (compliance.table)");
    }
    if (c.has("method")) {
      const std::string method = c.string("method");
      if (method != "auto") {  // "auto": the method the table's cross-validation favours, as when none is named
        robot.compliance.method = core::find_enum<FitMethod>(method);
        if (!robot.compliance.method) {
          c.fail("method", fmt::format("must be auto, {}, got '{}'", core::enum_choices<FitMethod>(), method));
        }
      }
    }
    // One key per meaning: a table (fitted on load, by `method`, of its `rows`) or a fitted model.
    if (c.has("model") && c.has("table")) {
      c.fail("model", "give either a table (fitted when loaded) or a fitted model, not both: which one compensates "
                      "would be ambiguous");
    }
    for (const auto* ref : {&robot.compliance.table, &robot.compliance.model}) {
      if (!ref->empty() && !core::data_exists(*ref)) {
        c.fail(ref == &robot.compliance.table ? "table" : "model", "no such file: " + ref->label());
      }
    }
  }
  try {
    (void)robot.five_bar();  // the geometry and the margin must leave a workspace
    if (robot.home_m && !robot.refusal(*robot.home_m).empty()) {
      root.fail("home_mm", "is not reachable: " + robot.refusal(*robot.home_m));
    }
  } catch (const Error& e) {
    if (!e.where().file.empty()) throw;
    throw Error(SourceLocation{file.label()}, e.message());
  }
  return robot;
}

nlohmann::json geometry_to_json(const FiveBarGeometry& g) {
  const auto mm = [](const Vec2& p) { return nlohmann::json::array({units::m_to_mm(p.x()), units::m_to_mm(p.y())}); };
  nlohmann::json out = {{"left_actuator_mm", mm(g.actuator_m[0])},
          {"right_actuator_mm", mm(g.actuator_m[1])},
          {"left_proximal_mm", units::m_to_mm(g.proximal_m[0])},
          {"right_proximal_mm", units::m_to_mm(g.proximal_m[1])},
          {"left_distal_mm", units::m_to_mm(g.distal_m[0])},
          {"right_distal_mm", units::m_to_mm(g.distal_m[1])},
          {"elbows", {g.elbows[0], g.elbows[1]}},
          {"assembly", g.assembly}};
  if (g.joint_zero_rad[0] != 0.0 || g.joint_zero_rad[1] != 0.0) {
    out["joint_zero_offsets_deg"] = {units::rad_to_deg(g.joint_zero_rad[0]), units::rad_to_deg(g.joint_zero_rad[1])};
  }
  return out;
}

nlohmann::json to_json(const Robot& r) {
  nlohmann::json joints = nlohmann::json::array();
  for (const auto& j : r.joints) {
    joints.push_back({{"name", j.name},
                      {"min_deg", units::rad_to_deg(j.min_rad)},
                      {"max_deg", units::rad_to_deg(j.max_rad)},
                      {"max_velocity_rad_s", j.max_velocity_rad_s},
                      {"max_acceleration_rad_s2", j.max_acceleration_rad_s2}});
  }
  nlohmann::json doc = {{"name", r.name}, {"description", r.description}};
  doc.update(geometry_to_json(r.geometry));
  doc["moving_mass_kg"] = r.moving_mass_kg;
  doc["tip_damping_ratio"] = r.tip_damping_ratio;
  if (r.tip_frequency_scale != 1.0) doc["tip_frequency_scale"] = r.tip_frequency_scale;
  if (r.laser_on_delay_s != 0.0 || r.laser_off_delay_s != 0.0) {
    doc["laser"] = {{"on_delay_ms", r.laser_on_delay_s * 1e3}, {"off_delay_ms", r.laser_off_delay_s * 1e3}};
  }
  doc["cg"] = {{"label", r.cg_label}, {"height_above_G_mm", units::m_to_mm(r.cg_height_m)}};
  if (r.replica) doc["measurement"] = {{"UG_mm", units::m_to_mm(r.replica->ug_m)}, {"UL_mm", units::m_to_mm(r.replica->ul_m)}};
  doc["joints"] = joints;
  doc["singularity_margin"] = {{"min_distance_mm", units::m_to_mm(r.margin.min_distance_m)},
                               {"max_condition_number", r.margin.max_condition_number},
                               {"min_distal_angle_deg", units::rad_to_deg(r.margin.min_distal_angle_rad)}};
  if (r.home_m) doc["home_mm"] = {units::m_to_mm(r.home_m->x()), units::m_to_mm(r.home_m->y())};
  nlohmann::json compliance = nlohmann::json::object();
  if (!r.compliance.table.empty()) compliance["table"] = r.compliance.table.label();
  if (!r.compliance.rows.empty()) compliance["rows"] = r.compliance.rows;
  if (!r.compliance.model.empty()) compliance["model"] = r.compliance.model.label();
  if (r.compliance.method) compliance["method"] = core::enum_name(*r.compliance.method);
  doc["compliance"] = compliance;
  return doc;
}

}  // namespace stiffpath::kinematics
