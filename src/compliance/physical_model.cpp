// PhysicalModel: C(p) = U⁻ᵀ D(p) U⁻¹ from the five-bar's statics, D fitted by linear least squares.
#include "stiffpath/compliance/physical_model.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::compliance {

PhysicalModel::PhysicalModel(const kinematics::FiveBarGeometry& geometry, GridBounds bounds, int order,
                             std::vector<std::array<double, 3>> coefficients, nlohmann::json stats)
    : geometry_(geometry), bounds_(bounds), order_(order), coefficients_(std::move(coefficients)),
      stats_(std::move(stats)) {
  std::array<double, kMaxTerms> b{};
  if (order_ < 0 || order_ > 2) throw Error(fmt::format("physical model: order must be 0, 1 or 2, got {}", order_));
  const int terms = basis(bounds_, order_, Vec2::Zero(), b);
  if (static_cast<int>(coefficients_.size()) != terms) {
    throw Error(fmt::format("physical model: order {} needs {} coefficient triples, got {}", order_, terms,
                            coefficients_.size()));
  }
  (void)kinematics::FiveBar(geometry_, {0.0, 2.0, 0.0});  // throws for a geometry that is no five-bar
  thesis_ = geometry_.is_thesis_case();
  if (!(bounds_.x_max > bounds_.x_min) || !(bounds_.y_max > bounds_.y_min)) {
    throw Error("physical model: the grid bounds must be non-empty");
  }
}

int PhysicalModel::basis(const GridBounds& g, int order, const Vec2& p, std::array<double, kMaxTerms>& out) noexcept {
  const double X = (2.0 * p.x() - g.x_min - g.x_max) / (g.x_max - g.x_min);
  const double Y = (2.0 * p.y() - g.y_min - g.y_max) / (g.y_max - g.y_min);
  out = {1.0, X, Y, X * X, X * Y, Y * Y};
  return order == 0 ? 1 : order == 1 ? 3 : 6;
}

namespace {
// Eq. 2.2 without trigonometry: cos/sin of θ1,2 = φ ± η from cos φ = x/r, sin φ = y/r,
// cos η = r/2l, sin η = √(1 − cos²η). r is kept just inside (0, 2l) so that the map stays finite.
Mat2 thesis_link_force_map(double l, const Vec2& p) noexcept {
  const double r_raw = p.norm();
  const double r = std::clamp(r_raw, 1e-9, 2.0 * l * (1.0 - 1e-12));
  const double c_phi = r_raw > 0.0 ? p.x() / r_raw : 1.0, s_phi = r_raw > 0.0 ? p.y() / r_raw : 0.0;
  const double c_eta = r / (2.0 * l), s_eta = std::sqrt(1.0 - c_eta * c_eta);
  const double c1 = c_phi * c_eta - s_phi * s_eta, s1 = s_phi * c_eta + c_phi * s_eta;
  const double c2 = c_phi * c_eta + s_phi * s_eta, s2 = s_phi * c_eta - c_phi * s_eta;
  // U = [w2 w1] = [c2 c1; s2 s1], det U = c2·s1 − c1·s2 = sin(θ1 − θ2) = sin 2η > 0.
  const double det = c2 * s1 - c1 * s2;
  Mat2 inv;
  inv << s1 / det, -c1 / det, -s2 / det, c2 / det;
  return inv;
}
}  // namespace

Mat2 PhysicalModel::link_force_map(const kinematics::FiveBarGeometry& g, const Vec2& p) noexcept {
  if (g.is_thesis_case()) return thesis_link_force_map(g.proximal_m[0], p);
  // The working mode's elbows without trigonometry: e_i is the direction of A_iC turned by s_i·α_i,
  // cos α_i = (r² + l_p² − l_d²)/(2 r l_p); u_i = (C − A_i − l_p e_i)/l_d.
  Vec2 u[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const double lp = g.proximal_m[i], ld = g.distal_m[i], s = g.elbows[i];
    const Vec2 d = p - g.actuator_m[i];
    const double r_raw = d.norm();
    const double r = std::clamp(r_raw, std::abs(lp - ld) * (1.0 + 1e-12) + 1e-9, (lp + ld) * (1.0 - 1e-12));
    const Vec2 dir = r_raw > 0.0 ? Vec2(d / r_raw) : Vec2(1.0, 0.0);
    const double c_alpha = std::clamp((r * r + lp * lp - ld * ld) / (2.0 * r * lp), -1.0, 1.0);
    const double s_alpha = std::sqrt(1.0 - c_alpha * c_alpha);
    const Vec2 e{dir.x() * c_alpha - s * dir.y() * s_alpha, dir.y() * c_alpha + s * dir.x() * s_alpha};
    u[i] = (r * dir - lp * e) / ld;
  }
  // U = [u1 u2]; U⁻¹ = [u2.y −u2.x; −u1.y u1.x] / det U.
  const double det = u[0].x() * u[1].y() - u[1].x() * u[0].y();
  Mat2 inv;
  inv << u[1].y() / det, -u[1].x() / det, -u[0].y() / det, u[0].x() / det;
  return inv;
}

Mat2 PhysicalModel::link_compliance(const Vec2& p) const noexcept {
  std::array<double, kMaxTerms> b{};
  const int terms = basis(bounds_, order_, policy_point(p), b);
  double d11 = 0.0, d12 = 0.0, d22 = 0.0;
  for (int k = 0; k < terms; ++k) {
    const auto& c = coefficients_[static_cast<std::size_t>(k)];
    d11 += c[0] * b[static_cast<std::size_t>(k)];
    d12 += c[1] * b[static_cast<std::size_t>(k)];
    d22 += c[2] * b[static_cast<std::size_t>(k)];
  }
  Mat2 d;
  d << d11, d12, d12, d22;
  return d;
}

Mat2 PhysicalModel::compliance(const Vec2& p) const noexcept {
  const Mat2 r = thesis_ ? thesis_link_force_map(geometry_.proximal_m[0], p) : link_force_map(geometry_, p);
  return r.transpose() * link_compliance(p) * r;
}

nlohmann::json PhysicalModel::parameters() const {
  nlohmann::json d = nlohmann::json::array();
  for (const auto& c : coefficients_) d.push_back({c[0] * 1e6, c[1] * 1e6, c[2] * 1e6});
  return {{"geometry", kinematics::geometry_to_json(geometry_)},
          {"order", order_},
          {"bounds_mm", {bounds_.x_min * 1e3, bounds_.x_max * 1e3, bounds_.y_min * 1e3, bounds_.y_max * 1e3}},
          {"D_um_per_N", d},
          {"stats", stats_}};
}

std::unique_ptr<PhysicalModel> fit_physical_model(const std::vector<PointSamples>& points,
                                                  const kinematics::FiveBarGeometry& geometry, int order,
                                                  const std::string& source, bool check_definite) {
  auto g = GridBounds::none();
  for (const auto& p : points) g.include(p.position);
  if (points.empty() || !(g.x_max > g.x_min) || !(g.y_max > g.y_min)) {
    throw Error(SourceLocation{source}, "the physical model needs points spread over x and y");
  }
  std::array<double, PhysicalModel::kMaxTerms> b{};
  const int terms = PhysicalModel::basis(g, order, Vec2::Zero(), b);
  const int unknowns = 3 * terms;
  std::vector<double> a_rows, rhs;
  const Mat2 e[3] = {(Mat2() << 1, 0, 0, 0).finished(), (Mat2() << 0, 1, 1, 0).finished(),
                     (Mat2() << 0, 0, 0, 1).finished()};
  for (const auto& point : points) {
    const Mat2 r = PhysicalModel::link_force_map(geometry, point.position);
    PhysicalModel::basis(g, order, point.position, b);
    for (const auto& s : point.samples) {
      const std::optional<double> measured[2] = {s.dx_m, s.dy_m};
      for (int comp = 0; comp < 2; ++comp) {
        if (!measured[comp]) continue;
        for (int k = 0; k < terms; ++k) {
          for (int m = 0; m < 3; ++m) {
            // Unknowns in µm/N so that the columns are O(1).
            a_rows.push_back((r.transpose() * e[m] * r * s.force_N)(comp) * b[static_cast<std::size_t>(k)] * 1e-6);
          }
        }
        rhs.push_back(*measured[comp]);
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(rhs.size());
  if (n < unknowns) {
    throw Error(SourceLocation{source},
                fmt::format("the physical model of order {} has {} unknowns but only {} measurements", order, unknowns, n));
  }
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> A(a_rows.data(), n,
                                                                                                  unknowns);
  const Eigen::Map<const Eigen::VectorXd> y(rhs.data(), n);
  const Eigen::VectorXd sol = A.colPivHouseholderQr().solve(y);
  const double rms = std::sqrt((A * sol - y).squaredNorm() / static_cast<double>(n));

  std::vector<std::array<double, 3>> coefficients;
  for (int k = 0; k < terms; ++k) coefficients.push_back({sol(3 * k) * 1e-6, sol(3 * k + 1) * 1e-6, sol(3 * k + 2) * 1e-6});
  if (!check_definite) {
    return std::make_unique<PhysicalModel>(geometry, g, order, std::move(coefficients),
                                           nlohmann::json{{"rms_residual_um", rms * 1e6}, {"equations", n}, {"unknowns", unknowns}});
  }
  auto model = std::make_unique<PhysicalModel>(geometry, g, order, coefficients, nlohmann::json::object());
  // Positive definiteness of D over the grid rectangle (51 × 51 samples).
  double min_eig = 1e300;
  for (int i = 0; i <= 50; ++i) {
    for (int j = 0; j <= 50; ++j) {
      const Vec2 p{g.x_min + (g.x_max - g.x_min) * i / 50.0, g.y_min + (g.y_max - g.y_min) * j / 50.0};
      min_eig = std::min(min_eig, Eigen::SelfAdjointEigenSolver<Mat2>(model->link_compliance(p)).eigenvalues()(0));
    }
  }
  nlohmann::json stats = {{"rms_residual_um", rms * 1e6},
                          {"equations", n},
                          {"unknowns", unknowns},
                          {"min_D_eigenvalue_um_per_N", min_eig * 1e6},
                          {"positive_definite_on_grid", min_eig > 0.0}};
  return std::make_unique<PhysicalModel>(geometry, g, order, std::move(coefficients), std::move(stats));
}

}  // namespace stiffpath::compliance
