// GcodeReader: reads a program line by line (never the whole file) and runs each block through the interpreter.
#include "stiffpath/motion/gcode_reader.hpp"

#include "gcode_interpreter.hpp"

namespace stiffpath::motion {

GcodeReader::GcodeReader(const std::filesystem::path& path, GcodeOptions options)
    : owned_(std::make_unique<std::ifstream>(path, std::ios::binary)),
      in_(owned_.get()),
      label_(path.string()),
      interpreter_(std::make_unique<GcodeInterpreter>(options)),
      where_{label_, 0, 0} {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(SourceLocation{label_}, "is a directory, not a G-code file");
  if (!*owned_) throw Error(SourceLocation{label_}, "cannot open G-code file");
}

GcodeReader::GcodeReader(std::istream& in, std::string label, GcodeOptions options)
    : in_(&in),
      label_(std::move(label)),
      interpreter_(std::make_unique<GcodeInterpreter>(options)),
      where_{label_, 0, 0} {}

GcodeReader::~GcodeReader() = default;

std::optional<PathSegment> GcodeReader::next() {
  while (!interpreter_->ended() && std::getline(*in_, text_)) {
    ++line_;
    if (!text_.empty() && text_.back() == '\r') text_.pop_back();
    where_.line = line_;
    if (!lex_gcode_line(text_, where_, words_) || words_.empty()) continue;
    const detail::GcodeBlock block = detail::parse_block(words_, where_);
    if (auto segment = interpreter_->execute(block)) return segment;
  }
  if (in_->bad()) throw Error(SourceLocation{label_, line_, 0}, "read error");
  return std::nullopt;
}

}  // namespace stiffpath::motion
