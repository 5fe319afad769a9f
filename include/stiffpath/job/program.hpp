// A job's program: a G-code file, G-code text, or samples planned elsewhere; opened as often as the job needs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::job {

//! What a job plans and compensates. Cheap to copy (text and samples are shared).
class Program {
 public:
  //! A G-code file, read line by line each time it is opened.
  static Program file(std::string path);
  //! G-code text; `label` names it in messages ("x_motion", "<string>").
  static Program text(std::string gcode, std::string label);
  //! Samples planned elsewhere (a binding's trajectory array), in time order at the job's rate.
  static Program samples(std::vector<motion::TrajectorySample> samples, std::string label);

  //! How messages name the program (the file's path, or the label).
  [[nodiscard]] const std::string& label() const noexcept { return label_; }
  //! True for G-code (a file or text), false for planned samples.
  [[nodiscard]] bool is_gcode() const noexcept { return kind_ != Kind::samples; }

  //! A fresh stream of the program's samples planned with `options` (samples: as given).
  [[nodiscard]] std::unique_ptr<motion::SampleSource> open(const motion::PlanOptions& options) const;
  //! Its size without sampling it (motion::measure_plan, with reference filters that rest `rest_samples` at every
  //! stop; samples: their count and last time).
  [[nodiscard]] motion::PlanSize measure(const motion::PlanOptions& options, std::uint64_t rest_samples = 0) const;
  //! The rectangle its samples cover (one pass); throws stiffpath::Error for a program with no samples.
  [[nodiscard]] compliance::GridBounds region(const motion::PlanOptions& options) const;

 private:
  enum class Kind { file, text, samples };
  Kind kind_ = Kind::file;
  std::string label_;
  std::shared_ptr<const std::string> text_;
  std::shared_ptr<const std::vector<motion::TrajectorySample>> samples_;
};

}  // namespace stiffpath::job
