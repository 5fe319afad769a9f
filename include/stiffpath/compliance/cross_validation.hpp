// Leave-one-out cross-validation of every compliance model over the measurement grid.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::compliance {

//! The held-out point's error for one method. The reference is the measurement at the highest load
//! step of each load direction (250 N nominal in the thesis); the error per point is the mean of
//! |Δx_pred − Δx_meas| and |Δy_pred − Δy_meas| over both load directions (µm), which is the
//! measure behind the "about 90 µm" for the thesis's bilinear interpolation on OC.
//! One reference load of a held-out point: what was measured and what the method predicted.
struct CvLoad {
  Vec2 force_N;
  std::optional<double> dx_m, dy_m;  //!< measured (missing cells stay empty)
  Vec2 predicted_m;
  Vec2 band_m = Vec2::Zero();  //!< half-width of the 95 % band of a measurement, per axis (0: not computed)
};

struct CvPoint {
  std::string id;
  Vec2 position;
  bool predicted = false;          //!< false where the method cannot predict the point (grid corners)
  bool interior = false;           //!< strictly inside the points' bounding rectangle (x2y2, x2y3, x2y4 on the thesis grid)
  double mean_abs_error_um = 0.0;  //!< mean absolute component error
  double mean_vector_error_um = 0.0;  //!< mean |Δ_pred − Δ_meas| over the load directions
  std::vector<CvLoad> loads;
};

struct CvMethod {
  FitMethod method = FitMethod::bilinear;
  std::string description;
  std::vector<CvPoint> points;
  int predicted = 0;
  double mean_um = 0.0;            //!< over the points the method can predict
  double max_um = 0.0;
  double interior_mean_um = 0.0;   //!< over the interior points
  //! With uncertainty: the held-out cells (dx, dy at the reference loads) with a 95 % band, and how many of the
  //! measured values fall inside it (the band learnt from the other points only).
  int band_cells = 0;
  int inside_band = 0;
  double mean_band_um = 0.0;  //!< the bands' mean half-width: how sharp they are
};

//! A method that could not run on these points, and why.
struct CvSkipped {
  FitMethod method = FitMethod::bilinear;
  std::string reason;
};

struct CvReport {
  std::string source;
  std::string rows;    //!< the table's rows (its `mechanism` value), empty for all
  std::string robot;   //!< the robot whose geometry the physical models used
  ForceConvention convention = ForceConvention::measured;
  ZeroForce zero_force = ZeroForce::relative;
  std::vector<CvMethod> methods;
  std::vector<CvSkipped> skipped;  //!< methods that need a full rectangular grid when there is none
};

//! Runs leave-one-out for every method that can run on the samples. Grid methods (bilinear,
//! symmetric) need the points to form a full rectangular grid; they predict a held-out node by linear
//! interpolation from its neighbours along x (else along y) — the bilinear scheme on the grid without
//! that node. The physical models (with `geometry`) are refitted without the point and run on any
//! layout. Methods that cannot run are listed in `skipped` with the reason. With `with_uncertainty`, each held-out
//! prediction also gets the 95 % band of a measurement (compliance::PredictionUncertainty learnt from the other
//! points, by their own leave-one-out: nested, so the held-out point is never seen), and each method counts the
//! held-out cells inside their band.
CvReport cross_validate(const std::vector<PointSamples>& points, const kinematics::FiveBarGeometry& geometry,
                        const std::string& source, ZeroForce zero_force = ZeroForce::relative,
                        bool with_uncertainty = false);

//! One point's compliance as a method predicts it from the other points.
struct LooCompliance {
  std::optional<Mat2> predicted;  //!< nullopt where the method cannot predict the point (grid corners)
  std::vector<std::size_t> used;  //!< grid methods: the points the prediction used; empty: all the others
};

//! Leave-one-out predictions of every point's C by `method` ("bilinear", "symmetric", "physical", "physical-0",
//! "physical-2", "physical-spline"): physical models refitted without the point, grid methods by neighbour
//! interpolation as cross_validate() does (the points must form a full grid). Throws stiffpath::Error when the
//! method cannot run on these points or is unknown.
std::vector<LooCompliance> leave_one_out_compliance(FitMethod method, const std::vector<PointSamples>& points,
                                                    const kinematics::FiveBarGeometry& geometry, const std::string& source);

//! The method with the smallest mean error over the points every method in the report predicted
//! (ties: the first listed), and that mean for each method (µm) in `scores`.
FitMethod favoured_method(const CvReport& report, std::vector<std::pair<FitMethod, double>>* scores = nullptr);

}  // namespace stiffpath::compliance
