// Python: stiffpath.plan — G-code text or file → sampled jerk-limited trajectory (structured array).
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "arrays.hpp"
#include "parts.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::python {

namespace {

std::optional<Vec2> optional_point(const std::optional<std::pair<double, double>>& p) {
  if (!p) return std::nullopt;
  return Vec2(p->first, p->second);
}

py::array plan(const std::optional<std::string>& gcode, const std::optional<std::string>& file, double max_velocity_m_s,
               double max_acceleration_m_s2, std::optional<double> max_jerk_m_s3, double rate_hz,
               const std::optional<std::pair<double, double>>& start_m,
               const std::optional<std::pair<double, double>>& home_m, std::size_t max_samples) {
  if (gcode.has_value() == file.has_value()) throw py::value_error("plan: give exactly one of gcode= (text) or file=");
  motion::PlanOptions options;
  options.limits.max_velocity_m_s = max_velocity_m_s;
  options.limits.max_acceleration_m_s2 = max_acceleration_m_s2;
  options.limits.max_jerk_m_s3 = max_jerk_m_s3.value_or(motion::default_jerk_m_s3(max_acceleration_m_s2));
  options.rate_hz = rate_hz;
  options.gcode.start_position_m = optional_point(start_m);
  options.gcode.home_position_m = optional_point(home_m);
  std::vector<TrajectoryRow> rows;
  {
    py::gil_scoped_release unlocked;
    std::istringstream text(gcode.value_or(""));
    std::unique_ptr<motion::TrajectoryStream> stream =
        file ? std::make_unique<motion::TrajectoryStream>(*file, options)
             : std::make_unique<motion::TrajectoryStream>(text, "<gcode>", options);
    while (auto s = stream->next()) {
      if (rows.size() >= max_samples) {
        throw Error(SourceLocation{file.value_or("<gcode>")},
                    fmt::format("the program needs more than max_samples = {} samples at {} Hz", max_samples, rate_hz));
      }
      rows.push_back({s->t_s,
                      {s->position_m.x(), s->position_m.y()},
                      {s->velocity_m_s.x(), s->velocity_m_s.y()},
                      {s->acceleration_m_s2.x(), s->acceleration_m_s2.y()},
                      {s->jerk_m_s3.x(), s->jerk_m_s3.y()},
                      s->laser_on,
                      s->power,
                      static_cast<std::int32_t>(s->line)});
    }
  }
  ensure_record_dtypes();
  py::array_t<TrajectoryRow> out(static_cast<py::ssize_t>(rows.size()));
  std::copy(rows.begin(), rows.end(), out.mutable_data());
  return out;
}

}  // namespace

void add_motion(py::module_& m) {
  m.def("plan", &plan, py::kw_only(), py::arg("gcode") = py::none(), py::arg("file") = py::none(),
        py::arg("max_velocity_m_s") = motion::default_max_velocity_m_s,
        py::arg("max_acceleration_m_s2") = motion::default_acceleration_m_s2, py::arg("max_jerk_m_s3") = py::none(),
        py::arg("rate_hz") = motion::default_sample_rate_hz, py::arg("start_m") = py::none(),
        py::arg("home_m") = py::none(), py::arg("max_samples") = std::size_t{50'000'000},
        "Plans a G-code program (text via gcode=, or a path via file=) with look-ahead and jerk-limited profiles, as\n"
        "`stiffpath plan` does, and samples it at rate_hz (default 2000 Hz, the thesis's control rate).\n\n"
        "Limits: max_velocity_m_s (m/s, also the G0 speed, default 2), max_acceleration_m_s2 (m/s², default 5 g),\n"
        "max_jerk_m_s3 (m/s³, default acceleration / 5 ms). start_m, home_m: (x, y) in m, robot frame.\n"
        "Returns a structured array of dtype stiffpath.trajectory_dtype: t_s, p_m[2], v_m_s[2], a_m_s2[2], j_m_s3[2],\n"
        "laser (bool), power (0…1), line (G-code line). A bad program raises stiffpath.Error 'file:line:column: …'.");
}

}  // namespace stiffpath::python
