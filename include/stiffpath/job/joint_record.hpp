// The joint record's fields, listed once: the CSV columns, the binary layouts and the bindings' names come from here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "stiffpath/compensation/samples.hpp"

namespace stiffpath::job {

//! Largest |t_s| of a record (s): 10^7 s, about 116 days.
inline constexpr double max_record_time_s = 1e7;

//! The member of compensation::JointCommand a field carries. Each name is also the field's name in
//! NumPy's stiffpath.joints_dtype and the member of the C interface's stiffpath_joint_command.
enum class JointMember : std::uint8_t { t_s, q_rad, qd_rad_s, qdd_rad_s2, laser, power, target_m, command_m, force_N, line };

//! How a field is stored in a binary record (little-endian).
enum class BinaryType : std::uint8_t { f64, i32, u8 };

//! How a field is written as CSV text: fixed-point decimals (job::write_fixed), a 0/1 flag or an integer.
enum class CsvText : std::uint8_t { fixed, flag, integer };

//! What a reader takes for a field that an older file lacks (CSV without the column, binary version 1).
enum class IfAbsent : std::uint8_t { refused, zero, laser_bit };

//! One field of a joint record: how it is named, written, stored and checked on every surface.
struct JointField {
  std::string_view csv_name;  //!< CSV column, its unit in the name ("x_mm")
  std::string_view si_name;   //!< the value's SI name, used for the binary record and its messages ("x_m")
  JointMember member;         //!< what it carries
  int component;              //!< 0 or 1 for a two-vector member (x/y, joint 1/2), 0 otherwise
  CsvText csv_text;
  int csv_decimals;           //!< decimals of a CsvText::fixed cell
  double csv_per_si;          //!< CSV value = SI value × this (1e3 for mm)
  BinaryType binary_type;
  int offset_v2;              //!< byte offset in a version-2 record
  int offset_v1;              //!< byte offset in a version-1 record, -1 where version 1 lacks the field
  double min_si, max_si;      //!< what a reader accepts (SI): generous physical bounds
  IfAbsent if_absent;
};

namespace detail {
constexpr JointField fixed(std::string_view csv, std::string_view si, JointMember m, int component, int decimals,
                           double csv_per_si, int offset_v2, int offset_v1, double max_abs, IfAbsent absent = IfAbsent::refused) {
  return {csv, si, m, component, CsvText::fixed, decimals, csv_per_si, BinaryType::f64, offset_v2, offset_v1,
          -max_abs, max_abs, absent};
}
}  // namespace detail

//! The joint record, in CSV column order. Decimals: t 6 (1 µs), θ and ω 9 (1 nrad), α 6, power 6, positions 6
//! (1 nm), forces 4 (0.1 mN); every CSV number is the value correctly rounded to them. The binary record
//! (version 2, 120 bytes) holds the doubles first, then the i32 line, the u8 laser and 3 bytes of zero padding;
//! version 1 (112 bytes) is the same without power.
inline constexpr std::array<JointField, 16> kJointFields{{
    detail::fixed("t_s", "t_s", JointMember::t_s, 0, 6, 1.0, 0, 0, max_record_time_s),
    detail::fixed("theta1_rad", "theta1_rad", JointMember::q_rad, 0, 9, 1.0, 8, 8, 1e3),
    detail::fixed("theta2_rad", "theta2_rad", JointMember::q_rad, 1, 9, 1.0, 16, 16, 1e3),
    detail::fixed("omega1_rad_s", "omega1_rad_s", JointMember::qd_rad_s, 0, 9, 1.0, 24, 24, 1e6),
    detail::fixed("omega2_rad_s", "omega2_rad_s", JointMember::qd_rad_s, 1, 9, 1.0, 32, 32, 1e6),
    detail::fixed("alpha1_rad_s2", "alpha1_rad_s2", JointMember::qdd_rad_s2, 0, 6, 1.0, 40, 40, 1e9, IfAbsent::zero),
    detail::fixed("alpha2_rad_s2", "alpha2_rad_s2", JointMember::qdd_rad_s2, 1, 6, 1.0, 48, 48, 1e9, IfAbsent::zero),
    {"laser", "laser", JointMember::laser, 0, CsvText::flag, 0, 1.0, BinaryType::u8, 116, 108, 0.0, 1.0, IfAbsent::refused},
    {"power", "power", JointMember::power, 0, CsvText::fixed, 6, 1.0, BinaryType::f64, 104, -1, 0.0, 1.0, IfAbsent::laser_bit},
    detail::fixed("x_mm", "x_m", JointMember::target_m, 0, 6, 1e3, 56, 56, 1e3),
    detail::fixed("y_mm", "y_m", JointMember::target_m, 1, 6, 1e3, 64, 64, 1e3),
    detail::fixed("xcmd_mm", "xcmd_m", JointMember::command_m, 0, 6, 1e3, 72, 72, 1e3),
    detail::fixed("ycmd_mm", "ycmd_m", JointMember::command_m, 1, 6, 1e3, 80, 80, 1e3),
    detail::fixed("fx_n", "fx_n", JointMember::force_N, 0, 4, 1.0, 88, 88, 1e9),
    detail::fixed("fy_n", "fy_n", JointMember::force_N, 1, 4, 1.0, 96, 96, 1e9),
    {"line", "line", JointMember::line, 0, CsvText::integer, 0, 1.0, BinaryType::i32, 112, 104, 0.0, 2e9, IfAbsent::refused},
}};

//! The name of a member (the NumPy field, the C struct's member).
constexpr std::string_view member_name(JointMember m) noexcept {
  switch (m) {
    case JointMember::t_s: return "t_s";
    case JointMember::q_rad: return "q_rad";
    case JointMember::qd_rad_s: return "qd_rad_s";
    case JointMember::qdd_rad_s2: return "qdd_rad_s2";
    case JointMember::laser: return "laser";
    case JointMember::power: return "power";
    case JointMember::target_m: return "target_m";
    case JointMember::command_m: return "command_m";
    case JointMember::force_N: return "force_N";
    case JointMember::line: return "line";
  }
  return "?";
}

//! The field's value in a command (SI; the laser 0 or 1, the line as a number).
inline double value_of(const compensation::JointCommand& c, const JointField& f) noexcept {
  const auto xy = [&](const compensation::Vec2& v) { return f.component == 0 ? v.x() : v.y(); };
  switch (f.member) {
    case JointMember::t_s: return c.t_s;
    case JointMember::q_rad: return xy(c.q_rad);
    case JointMember::qd_rad_s: return xy(c.qd_rad_s);
    case JointMember::qdd_rad_s2: return xy(c.qdd_rad_s2);
    case JointMember::laser: return c.laser_on ? 1.0 : 0.0;
    case JointMember::power: return c.power;
    case JointMember::target_m: return xy(c.target_m);
    case JointMember::command_m: return xy(c.command_m);
    case JointMember::force_N: return xy(c.force_N);
    case JointMember::line: return static_cast<double>(c.line);
  }
  return 0.0;
}

//! Sets the field in a command from its SI value (the laser on for any value but 0).
inline void set_value(compensation::JointCommand& c, const JointField& f, double v) noexcept {
  const auto xy = [&](compensation::Vec2& to) { to[f.component] = v; };
  switch (f.member) {
    case JointMember::t_s: c.t_s = v; return;
    case JointMember::q_rad: xy(c.q_rad); return;
    case JointMember::qd_rad_s: xy(c.qd_rad_s); return;
    case JointMember::qdd_rad_s2: xy(c.qdd_rad_s2); return;
    case JointMember::laser: c.laser_on = v != 0.0; return;
    case JointMember::power: c.power = v; return;
    case JointMember::target_m: xy(c.target_m); return;
    case JointMember::command_m: xy(c.command_m); return;
    case JointMember::force_N: xy(c.force_N); return;
    case JointMember::line: c.line = static_cast<int>(v); return;
  }
}

//! Bytes of a binary type.
constexpr int binary_bytes(BinaryType t) noexcept { return t == BinaryType::f64 ? 8 : t == BinaryType::i32 ? 4 : 1; }

//! Index of the field with CSV column `csv_name` in kJointFields; a compile-time error (in a constant
//! expression) when there is none.
consteval std::size_t joint_field(std::string_view csv_name) {
  for (std::size_t i = 0; i < kJointFields.size(); ++i) {
    if (kJointFields[i].csv_name == csv_name) return i;
  }
  throw "no joint field of this name";  // not a constant expression: the caller's name is wrong
}

namespace detail {
// Bytes a record's fields fill in `version` (1 or 2), if they tile [0, end) without gap or overlap; -1 otherwise.
constexpr int tiled_bytes(int version) {
  std::array<bool, 256> used{};
  int end = 0;
  for (const auto& f : kJointFields) {
    const int at = version == 1 ? f.offset_v1 : f.offset_v2;
    if (at < 0) continue;
    const int bytes = binary_bytes(f.binary_type);
    if (at % bytes != 0 || at + bytes > 256) return -1;  // misaligned or beyond any record
    for (int b = at; b < at + bytes; ++b) {
      if (used[static_cast<std::size_t>(b)]) return -1;
      used[static_cast<std::size_t>(b)] = true;
    }
    end = at + bytes > end ? at + bytes : end;
  }
  for (int b = 0; b < end; ++b) {
    if (!used[static_cast<std::size_t>(b)]) return -1;
  }
  return end;
}

constexpr bool names_unique() {
  for (std::size_t i = 0; i < kJointFields.size(); ++i) {
    for (std::size_t j = i + 1; j < kJointFields.size(); ++j) {
      if (kJointFields[i].csv_name == kJointFields[j].csv_name || kJointFields[i].si_name == kJointFields[j].si_name) {
        return false;
      }
    }
  }
  return true;
}

constexpr std::size_t csv_header_length() {
  std::size_t n = kJointFields.size() - 1;  // the commas
  for (const auto& f : kJointFields) n += f.csv_name.size();
  return n;
}

constexpr std::array<char, csv_header_length() + 1> csv_header() {
  std::array<char, csv_header_length() + 1> out{};
  std::size_t at = 0;
  for (const auto& f : kJointFields) {
    if (at > 0) out[at++] = ',';
    for (char ch : f.csv_name) out[at++] = ch;
  }
  return out;
}
inline constexpr auto kCsvHeaderText = csv_header();
}  // namespace detail

static_assert(detail::names_unique(), "joint fields need unique CSV and SI names");
static_assert(detail::tiled_bytes(2) > 0 && detail::tiled_bytes(1) > 0,
              "the binary fields must tile their record without gap or overlap, each aligned to its size");

//! Bytes of a binary record: its fields, then zero padding to a multiple of 8 (version 2: 117 + 3 = 120;
//! version 1: 109 + 3 = 112).
inline constexpr std::uint32_t kBinaryRecordBytes = (detail::tiled_bytes(2) + 7) / 8 * 8;
inline constexpr std::uint32_t kBinaryV1RecordBytes = (detail::tiled_bytes(1) + 7) / 8 * 8;
//! Bytes the fields fill; the rest of each record is zero padding.
inline constexpr std::uint32_t kBinaryRecordFieldBytes = detail::tiled_bytes(2);

//! CSV header of the joint trajectory (units in the names): the CSV names of kJointFields, comma-separated.
inline constexpr const char* kJointCsvHeader = detail::kCsvHeaderText.data();

}  // namespace stiffpath::job
