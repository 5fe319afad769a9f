// The MEX gateway's arguments and results: strings, matrices, option structs checked field by field, and structs of
// named columns built from the library's values (C MEX API only, so MATLAB's `mex` builds it too).
#pragma once
#include <mex.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::mex {

using kinematics::Vec2;

//! Bad arguments from the caller (a wrong type or count: `stiffpath:usage`); a bad value is a stiffpath::Error.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

//! The signature of one command: nlhs, plhs, nrhs, prhs as mexFunction gets them (prhs[0] is the command's name).
using Command = void (*)(int, mxArray*[], int, const mxArray*[]);

//! Throws UsageError("usage: …") unless lo <= nrhs <= hi.
void need(int nrhs, int lo, int hi, const char* usage);
//! A character row vector as text; `what` names it in the error.
std::string text_arg(const mxArray* a, const std::string& what);
//! A robot: a preset name or a robot file.
kinematics::Robot robot_arg(const mxArray* a);

//! An N×k real double matrix, read column-major.
struct Matrix {
  const double* data = nullptr;
  std::size_t rows = 0, cols = 0;
  double operator()(std::size_t r, std::size_t c) const { return data[c * rows + r]; }
};
//! A real double matrix of min_cols … max_cols columns whose every entry is finite.
Matrix matrix_arg(const mxArray* a, const std::string& what, std::size_t min_cols, std::size_t max_cols);

//! An options struct (1×1) read field by field: each getter marks its field as known, finish() refuses the others
//! (a misspelt option is an error, not a silent default). Numbers are checked against their range where they enter.
class Options {
 public:
  //! `a` may be null (no options); else it must be a 1×1 struct.
  explicit Options(const mxArray* a, std::string what = "options");
  [[nodiscard]] bool has(const char* name);
  //! A real finite scalar in [lo, hi] (`unit` for the message), or nullopt when absent.
  std::optional<double> number(const char* name, double lo, double hi, const char* unit = "");
  //! A true/false (logical or 0/1), or nullopt when absent.
  std::optional<bool> flag(const char* name);
  //! Text, or nullopt when absent.
  std::optional<std::string> text(const char* name);
  //! A 1×2 point (m) within ±10 m, or nullopt when absent.
  std::optional<Vec2> point(const char* name);
  //! The field itself (marked known), or null when absent.
  const mxArray* raw(const char* name);
  //! Throws UsageError naming every field no getter asked for.
  void finish() const;
  [[nodiscard]] std::string name(const char* field) const { return what_ + "." + field; }

 private:
  const mxArray* a_;
  std::string what_;
  std::set<std::string> known_;
};

//! A struct (1×1) with fields in the order added.
class StructBuilder {
 public:
  StructBuilder& add(const std::string& name, mxArray* value);
  StructBuilder& add(const std::string& name, double value);
  StructBuilder& add(const std::string& name, const std::string& value);
  StructBuilder& add_bool(const std::string& name, bool value);
  [[nodiscard]] mxArray* build() const;

 private:
  std::vector<std::pair<std::string, mxArray*>> fields_;
};

mxArray* column(const std::vector<double>& values);
mxArray* logical_column(const std::vector<bool>& values);
//! N×2 (x, y) in the points' unit.
mxArray* pairs(const std::vector<Vec2>& points);
//! A JSON document as MATLAB values: objects → structs (keys made valid field names: '-' and others become '_'),
//! arrays of objects with the same keys → struct arrays (else cells), arrays of numbers → rows, arrays of equal
//! rows → matrices, null → [], true/false → logical.
mxArray* from_json(const nlohmann::json& j);

}  // namespace stiffpath::mex
