// The MEX gateway's argument readers and result builders (see mex_args.hpp).
#include "mex_args.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

#include "stiffpath/core/error.hpp"

namespace stiffpath::mex {

void need(int nrhs, int lo, int hi, const char* usage) {
  if (nrhs < lo || nrhs > hi) throw UsageError(std::string("usage: ") + usage);
}

std::string text_arg(const mxArray* a, const std::string& what) {
  if (a == nullptr || !mxIsChar(a) || (mxGetM(a) > 1 && mxGetNumberOfElements(a) > 0)) {
    throw UsageError(what + " must be a character string (one row)");
  }
  char* chars = mxArrayToString(a);
  std::string s(chars != nullptr ? chars : "");
  mxFree(chars);
  return s;
}

kinematics::Robot robot_arg(const mxArray* a) { return kinematics::load_robot(text_arg(a, "robot")); }

Matrix matrix_arg(const mxArray* a, const std::string& what, std::size_t min_cols, std::size_t max_cols) {
  if (a == nullptr || !mxIsDouble(a) || mxIsComplex(a) || mxIsSparse(a) || mxGetNumberOfDimensions(a) > 2) {
    throw UsageError(what + " must be a real double matrix");
  }
  const Matrix m{mxGetPr(a), mxGetM(a), mxGetN(a)};
  if (m.cols < min_cols || m.cols > max_cols) {
    throw UsageError(fmt::format("{} must have {}{} columns, not {}", what, min_cols,
                                 max_cols > min_cols ? fmt::format(" to {}", max_cols) : "", m.cols));
  }
  for (std::size_t k = 0; k < m.rows * m.cols; ++k) {
    if (!std::isfinite(m.data[k])) {
      throw Error(fmt::format("{} row {}, column {}: expected a finite number, got {}", what, k % m.rows + 1,
                              k / m.rows + 1, m.data[k]));
    }
  }
  return m;
}

Options::Options(const mxArray* a, std::string what) : a_(a), what_(std::move(what)) {
  if (a_ != nullptr && (!mxIsStruct(a_) || mxGetNumberOfElements(a_) != 1)) {
    throw UsageError(what_ + " must be a 1×1 struct, e.g. struct('gain', 0.8)");
  }
}

const mxArray* Options::raw(const char* name) {
  known_.insert(name);
  return a_ != nullptr ? mxGetField(a_, 0, name) : nullptr;
}

bool Options::has(const char* name) { return raw(name) != nullptr; }

std::optional<double> Options::number(const char* name, double lo, double hi, const char* unit) {
  const mxArray* f = raw(name);
  if (f == nullptr) return std::nullopt;
  if (!(mxIsDouble(f) || mxIsLogical(f)) || mxIsComplex(f) || mxGetNumberOfElements(f) != 1) {
    throw UsageError(this->name(name) + " must be a real number");
  }
  const double v = mxGetScalar(f);
  if (!std::isfinite(v) || v < lo || v > hi) {
    throw Error(fmt::format("{}: expected {:g} … {:g}{}{}, got {}", this->name(name), lo, hi, *unit ? " " : "", unit, v));
  }
  return v;
}

std::optional<bool> Options::flag(const char* name) {
  const mxArray* f = raw(name);
  if (f == nullptr) return std::nullopt;
  if (mxGetNumberOfElements(f) != 1 || !(mxIsLogical(f) || mxIsDouble(f))) {
    throw UsageError(this->name(name) + " must be true or false");
  }
  const double v = mxGetScalar(f);
  if (v != 0.0 && v != 1.0) throw Error(fmt::format("{}: expected true or false, got {}", this->name(name), v));
  return v != 0.0;
}

std::optional<std::string> Options::text(const char* name) {
  const mxArray* f = raw(name);
  if (f == nullptr) return std::nullopt;
  return text_arg(f, this->name(name));
}

std::optional<Vec2> Options::point(const char* name) {
  const mxArray* f = raw(name);
  if (f == nullptr) return std::nullopt;
  if (!mxIsDouble(f) || mxIsComplex(f) || mxGetNumberOfElements(f) != 2) {
    throw UsageError(this->name(name) + " must be [x y] in m");
  }
  const double* p = mxGetPr(f);
  for (int k = 0; k < 2; ++k) {
    if (!std::isfinite(p[k]) || std::abs(p[k]) > 10.0) {
      throw Error(fmt::format("{}: expected coordinates within ±10 m, got [{} {}]", this->name(name), p[0], p[1]));
    }
  }
  return Vec2(p[0], p[1]);
}

void Options::finish() const {
  if (a_ == nullptr) return;
  std::string unknown;
  for (int k = 0; k < mxGetNumberOfFields(a_); ++k) {
    const std::string field = mxGetFieldNameByNumber(a_, k);
    if (!known_.contains(field)) unknown += (unknown.empty() ? "" : ", ") + field;
  }
  if (unknown.empty()) return;
  std::string names;
  for (const auto& k : known_) names += (names.empty() ? "" : ", ") + k;
  throw UsageError(fmt::format("{}: unknown field(s) {}; this command knows {}", what_, unknown, names));
}

StructBuilder& StructBuilder::add(const std::string& name, mxArray* value) {
  fields_.emplace_back(name, value);
  return *this;
}
StructBuilder& StructBuilder::add(const std::string& name, double value) { return add(name, mxCreateDoubleScalar(value)); }
StructBuilder& StructBuilder::add(const std::string& name, const std::string& value) {
  return add(name, mxCreateString(value.c_str()));
}
StructBuilder& StructBuilder::add_bool(const std::string& name, bool value) {
  return add(name, mxCreateLogicalScalar(value));
}

mxArray* StructBuilder::build() const {
  std::vector<const char*> names;
  for (const auto& [name, value] : fields_) names.push_back(name.c_str());
  mxArray* s = mxCreateStructMatrix(1, 1, static_cast<int>(names.size()), names.data());
  for (std::size_t k = 0; k < fields_.size(); ++k) mxSetFieldByNumber(s, 0, static_cast<int>(k), fields_[k].second);
  return s;
}

mxArray* column(const std::vector<double>& values) {
  mxArray* a = mxCreateDoubleMatrix(values.size(), 1, mxREAL);
  std::copy(values.begin(), values.end(), mxGetPr(a));
  return a;
}

mxArray* logical_column(const std::vector<bool>& values) {
  mxArray* a = mxCreateLogicalMatrix(values.size(), 1);
  mxLogical* p = mxGetLogicals(a);
  for (std::size_t i = 0; i < values.size(); ++i) p[i] = values[i];
  return a;
}

mxArray* pairs(const std::vector<Vec2>& points) {
  const std::size_t n = points.size();
  mxArray* a = mxCreateDoubleMatrix(n, 2, mxREAL);
  double* p = mxGetPr(a);
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = points[i].x();
    p[n + i] = points[i].y();
  }
  return a;
}

namespace {

std::string field_name(const std::string& key) {
  std::string out;
  for (const char c : key) out += std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
  if (out.empty() || std::isalpha(static_cast<unsigned char>(out.front())) == 0) out = "x" + out;
  return out.substr(0, 63);
}

// Rows of equal length of numbers only: their count and length, else nullopt.
std::optional<std::pair<std::size_t, std::size_t>> numeric_shape(const nlohmann::json& j) {
  if (j.empty()) return std::pair<std::size_t, std::size_t>{1, 0};
  if (std::all_of(j.begin(), j.end(), [](const auto& v) { return v.is_number(); })) return std::pair{std::size_t{1}, j.size()};
  const std::size_t cols = j.front().is_array() ? j.front().size() : 0;
  for (const auto& row : j) {
    if (!row.is_array() || row.size() != cols || cols == 0) return std::nullopt;
    for (const auto& v : row) {
      if (!v.is_number()) return std::nullopt;
    }
  }
  return std::pair{j.size(), cols};
}

std::vector<std::string> keys(const nlohmann::json& o) {
  std::vector<std::string> k;
  for (const auto& item : o.items()) k.push_back(item.key());
  return k;
}

}  // namespace

mxArray* from_json(const nlohmann::json& j) {
  if (j.is_null()) return mxCreateDoubleMatrix(0, 0, mxREAL);
  if (j.is_boolean()) return mxCreateLogicalScalar(j.get<bool>());
  if (j.is_number()) return mxCreateDoubleScalar(j.get<double>());
  if (j.is_string()) return mxCreateString(j.get<std::string>().c_str());
  if (j.is_object()) {
    StructBuilder s;
    for (const auto& item : j.items()) s.add(field_name(item.key()), from_json(item.value()));
    return s.build();
  }
  if (const auto shape = numeric_shape(j)) {
    const auto [rows, cols] = *shape;
    mxArray* a = mxCreateDoubleMatrix(rows, cols, mxREAL);
    double* p = mxGetPr(a);
    if (rows == 1 && !j.empty() && j.front().is_number()) {
      for (std::size_t c = 0; c < cols; ++c) p[c] = j[c].get<double>();
    } else {
      for (std::size_t r = 0; r < rows && cols > 0; ++r) {
        for (std::size_t c = 0; c < cols; ++c) p[c * rows + r] = j[r][c].get<double>();
      }
    }
    return a;
  }
  const bool same_objects = j.front().is_object() && std::all_of(j.begin(), j.end(), [&](const auto& v) {
    return v.is_object() && keys(v) == keys(j.front());
  });
  if (same_objects) {
    std::vector<std::string> names;
    for (const auto& k : keys(j.front())) names.push_back(field_name(k));
    std::vector<const char*> pointers;
    for (const auto& n : names) pointers.push_back(n.c_str());
    mxArray* s = mxCreateStructMatrix(1, j.size(), static_cast<int>(pointers.size()), pointers.data());
    for (std::size_t i = 0; i < j.size(); ++i) {
      int k = 0;
      for (const auto& item : j[i].items()) mxSetFieldByNumber(s, i, k++, from_json(item.value()));
    }
    return s;
  }
  mxArray* c = mxCreateCellMatrix(1, j.size());
  for (std::size_t i = 0; i < j.size(); ++i) mxSetCell(c, i, from_json(j[i]));
  return c;
}

}  // namespace stiffpath::mex
