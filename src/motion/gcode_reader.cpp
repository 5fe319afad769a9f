// GcodeReader: reads a program line by line (never the whole file), runs each block through the
// interpreter, and gathers every refusal of the file before throwing them together.
#include "stiffpath/motion/gcode_reader.hpp"

#include <cmath>
#include <fmt/format.h>

#include "gcode_interpreter.hpp"

namespace stiffpath::motion {

namespace {

void check_point(const Vec2& p, const char* field) {
  if (!p.allFinite() || p.cwiseAbs().maxCoeff() > max_coordinate_m) {
    throw Error(fmt::format("G-code option {} must be finite and within ±{:g} m, got ({}, {})", field,
                            max_coordinate_m, p.x(), p.y()));
  }
}

void check_range(double value, double low, double high, const char* field) {
  if (!(value >= low && value <= high)) {
    throw Error(fmt::format("G-code option {} must be within [{:g}, {:g}], got {}", field, low, high, value));
  }
}

constexpr char byte_order_mark[] = "\xEF\xBB\xBF";
constexpr char dos_end_of_file = '\x1A';

}  // namespace

void validate(const GcodeOptions& o) {
  check_point(o.work_offset_m, "work_offset_m");
  if (o.start_position_m) check_point(*o.start_position_m, "start_position_m");
  if (o.home_position_m) check_point(*o.home_position_m, "home_position_m");
  check_range(o.default_blend_tolerance_m, 0.0, max_blend_tolerance_m, "default_blend_tolerance_m");
  check_range(o.arc_tolerance_m, 0.0, max_coordinate_m, "arc_tolerance_m");
  check_range(o.s_max, 1e-6, 1e9, "s_max");
  if (o.program_stop_dwell_s) check_range(*o.program_stop_dwell_s, 0.0, max_block_duration_s, "program_stop_dwell_s");
}

GcodeReader::GcodeReader(const std::filesystem::path& path, GcodeOptions options)
    : owned_(std::make_unique<std::ifstream>(path, std::ios::binary)),
      in_(owned_.get()),
      label_(path.string()),
      options_(std::move(options)),
      where_{label_, 0, 0} {
  validate(options_);
  interpreter_ = std::make_unique<GcodeInterpreter>(options_, warnings_);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(SourceLocation{label_}, "is a directory, not a G-code file");
  if (!*owned_) throw Error(SourceLocation{label_}, "cannot open G-code file");
}

GcodeReader::GcodeReader(std::istream& in, std::string label, GcodeOptions options)
    : in_(&in), label_(std::move(label)), options_(std::move(options)), where_{label_, 0, 0} {
  validate(options_);
  interpreter_ = std::make_unique<GcodeInterpreter>(options_, warnings_);
}

GcodeReader::~GcodeReader() = default;

void GcodeReader::refuse(const Error& error) {
  if (errors_.size() < max_reported_errors) {
    errors_.push_back(error);
  } else {
    ++omitted_errors_;
  }
}

// Reads, lexes, sorts and executes the next line; false at the end of the program.
bool GcodeReader::read_line() {
  if (interpreter_->ended() || end_of_file_ || !std::getline(*in_, text_)) return false;
  ++line_;
  where_.line = line_;
  if (!text_.empty() && text_.back() == '\r') text_.pop_back();
  if (!options_.strict) {
    if (line_ == 1 && text_.starts_with(byte_order_mark)) text_.erase(0, sizeof byte_order_mark - 1);
    if (const auto eof = text_.find(dos_end_of_file); eof != std::string::npos) {
      text_.resize(eof);  // the DOS end-of-file character: nothing after it is part of the program
      end_of_file_ = true;
    }
    if (const auto first = text_.find_first_not_of(" \t"); first != std::string::npos && text_[first] == '/') {
      warnings_.add(GcodeWarningKind::block_delete, line_,
                    options_.skip_block_delete ? "lines starting with '/' (block delete) are skipped"
                                               : "lines starting with '/' (block delete) run, as with the switch off");
      if (options_.skip_block_delete) return true;
      text_[first] = ' ';
    }
  }
  try {
    if (!lex_gcode_line(text_, where_, words_, !options_.strict) || words_.empty()) return true;
    const std::size_t before = errors_.size() + omitted_errors_;
    std::vector<Error> refusals;
    const detail::GcodeBlock block = detail::parse_block(words_, where_, options_.strict, refusals);
    for (const Error& refusal : refusals) refuse(refusal);
    if (errors_.size() + omitted_errors_ == before) interpreter_->execute(block, pending_);
  } catch (const Error& e) {
    refuse(e);
  }
  if (!errors_.empty()) pending_.clear();  // after a refusal nothing more is handed out
  return true;
}

std::optional<PathSegment> GcodeReader::next() {
  while (pending_.empty() && !finished_) {
    if (read_line()) continue;
    if (in_->bad()) throw Error(SourceLocation{label_, line_, 0}, "read error");
    finished_ = true;
    if (!errors_.empty()) throw GcodeErrors(errors_, omitted_errors_);
    if (options_.on_warnings) options_.on_warnings(label_, warnings_.list());
  }
  if (pending_.empty()) return std::nullopt;
  PathSegment segment = pending_.front();
  pending_.pop_front();
  return segment;
}

}  // namespace stiffpath::motion
