// Program: a G-code file, G-code text or planned samples, opened as a fresh sample stream each time.
#include "stiffpath/job/program.hpp"

#include <sstream>

#include "stiffpath/core/error.hpp"

namespace stiffpath::job {

namespace {

// G-code text planned as a stream: owns the text's input stream, which the planner reads line by line.
class TextStream final : public motion::SampleSource {
 public:
  TextStream(const std::string& text, const std::string& label, const motion::PlanOptions& options)
      : in_(text), stream_(in_, label, options) {}
  std::optional<motion::TrajectorySample> next() override { return stream_.next(); }
  const motion::SegmentHistory* keep_segments(double seconds) override { return stream_.keep_segments(seconds); }
  const motion::SlowdownReport* slowdowns() const override { return stream_.slowdowns(); }

 private:
  std::istringstream in_;
  motion::TrajectoryStream stream_;
};

// Planned samples handed out in order.
class VectorStream final : public motion::SampleSource {
 public:
  explicit VectorStream(std::shared_ptr<const std::vector<motion::TrajectorySample>> samples)
      : samples_(std::move(samples)) {}
  std::optional<motion::TrajectorySample> next() override {
    if (i_ == samples_->size()) return std::nullopt;
    return (*samples_)[i_++];
  }

 private:
  std::shared_ptr<const std::vector<motion::TrajectorySample>> samples_;
  std::size_t i_ = 0;
};

}  // namespace

Program Program::file(std::string path) {
  Program p;
  p.kind_ = Kind::file;
  p.label_ = std::move(path);
  return p;
}

Program Program::text(std::string gcode, std::string label) {
  Program p;
  p.kind_ = Kind::text;
  p.label_ = std::move(label);
  p.text_ = std::make_shared<const std::string>(std::move(gcode));
  return p;
}

Program Program::samples(std::vector<motion::TrajectorySample> samples, std::string label) {
  Program p;
  p.kind_ = Kind::samples;
  p.label_ = std::move(label);
  p.samples_ = std::make_shared<const std::vector<motion::TrajectorySample>>(std::move(samples));
  return p;
}

std::unique_ptr<motion::SampleSource> Program::open(const motion::PlanOptions& options) const {
  switch (kind_) {
    case Kind::file: return std::make_unique<motion::TrajectoryStream>(label_, options);
    case Kind::text: return std::make_unique<TextStream>(*text_, label_, options);
    case Kind::samples: return std::make_unique<VectorStream>(samples_);
  }
  return nullptr;
}

motion::PlanSize Program::measure(const motion::PlanOptions& options, std::uint64_t rest_samples) const {
  switch (kind_) {
    case Kind::file: return motion::measure_plan(label_, options, rest_samples);
    case Kind::text: {
      std::istringstream in(*text_);
      return motion::measure_plan(in, label_, options, rest_samples);
    }
    case Kind::samples: {
      motion::PlanSize size;
      size.samples = samples_->size();
      size.duration_s = samples_->empty() ? 0.0 : samples_->back().t_s;
      return size;
    }
  }
  return {};
}

compliance::GridBounds Program::region(const motion::PlanOptions& options) const {
  auto quiet = options;
  quiet.gcode.on_warnings = nullptr;  // the job's own pass reports the program's warnings, once
  const auto source = open(quiet);
  auto box = compliance::GridBounds::none();
  while (const auto s = source->next()) box.include(s->position_m);
  if (box.x_min > box.x_max) throw Error(SourceLocation{label_}, "the program has no motion");
  return box;
}

}  // namespace stiffpath::job
