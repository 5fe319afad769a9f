// GcodeReader: reads a program line by line (never the whole file), runs each block through the
// interpreter, and gathers every refusal of the file before throwing them together.
#include "stiffpath/motion/gcode_reader.hpp"

#include <cmath>
#include <fmt/format.h>

#include "gcode_block.hpp"
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
  for (const double m : o.ignored_m_codes) {
    check_range(m, 0.0, max_code_number, "ignored_m_codes");
    const int code = detail::code_tenths(m);
    // The codes the reader runs itself cannot be ignored.
    for (const int own : {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 300, 620, 630, 1060, 1070}) {
      if (code == own) throw Error(fmt::format("G-code option ignored_m_codes: M{:g} is run by the reader, not ignored", m));
    }
  }
  for (const OutputAssignment& output : o.outputs) check_range(output.number, 0.0, max_code_number, "outputs");
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

// The next line into text_, reading at most max_line_bytes + 2 bytes of it; false at the end of the
// input. A longer line is refused (reading stops there: a file without line ends may never end).
bool GcodeReader::next_line() {
  constexpr std::size_t capacity = max_line_bytes + 2;  // the longest line, a CR, and one byte to tell
  buffer_.resize(capacity + 1);
  in_->getline(buffer_.data(), static_cast<std::streamsize>(capacity + 1));
  const auto got = static_cast<std::size_t>(in_->gcount());
  const bool full = in_->fail() && !in_->eof() && got == capacity;  // stopped by the capacity, not a line end
  if (got == 0 && in_->fail()) return false;                         // nothing left (or a read error)
  std::size_t length = in_->eof() || full ? got : got - 1;           // without the '\n'
  if (length > 0 && buffer_[length - 1] == '\r') --length;
  ++line_;
  where_.line = line_;
  if (full || length > max_line_bytes) {
    refuse(Error(SourceLocation{label_, line_, static_cast<int>(max_line_bytes) + 1},
                 fmt::format("the line is longer than {} bytes, the longest accepted; reading stops here", max_line_bytes)));
    end_of_file_ = true;
    text_.clear();
    return true;
  }
  text_.assign(buffer_.data(), length);
  return true;
}

// Reads, lexes, sorts and executes the next line; false at the end of the program.
bool GcodeReader::read_line() {
  if (interpreter_->ended() || end_of_file_ || !next_line()) return false;
  if (end_of_file_) return true;  // an over-long line, refused
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
    line_refusals_.clear();
    std::size_t line_omitted = 0;
    const detail::GcodeBlock block =
        detail::parse_block(words_, where_, options_.strict, options_.ignored_m_codes, line_refusals_, line_omitted);
    for (const Error& refusal : line_refusals_) refuse(refusal);
    omitted_errors_ += line_omitted;
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
    if (errors_.empty()) interpreter_->finish(pending_);  // what waited for a position (dwells before any move)
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
