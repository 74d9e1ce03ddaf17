// What is drawn on top of the MuJoCo mechanism: chain colours, a floor, base
// markers, the desired path, the end-effector's travelled trace, an
// end-effector marker, the error vector magnified, and the text (time,
// tracking error, magnification, encoder readings).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <mujoco/mujoco.h>

#include "models/robot.hpp"
#include "sim/sampling.hpp"

namespace gpm::render {

// Colours and heights of the overlay (a contract for tests and users).
struct OverlayStyle {
  // Chains 1..3: active links in these colours, passive links lighter.
  static constexpr std::array<std::array<float, 3>, 3> kChainRgb = {{
      {0.90f, 0.35f, 0.15f},  // chain 1: red-orange
      {0.20f, 0.75f, 0.30f},  // chain 2: green
      {0.25f, 0.50f, 0.95f},  // chain 3: blue
  }};
  static constexpr std::array<float, 4> kDesiredRgba = {0.95f, 0.95f, 0.95f, 1.0f};  // white
  static constexpr std::array<float, 4> kTraceRgba = {1.0f, 0.85f, 0.05f, 1.0f};     // yellow
  // The end-effector marker: a flat magenta disc, above everything else.
  static constexpr std::array<float, 4> kMarkerRgba = {1.0f, 0.0f, 1.0f, 1.0f};
  // The error vector (actual - desired) times the run's magnification, from the desired point: cyan.
  static constexpr std::array<float, 4> kErrorRgba = {0.0f, 1.0f, 1.0f, 1.0f};
  static constexpr double kErrorZ_m = 0.095;      // above the marker
  static constexpr double kMarkerTopZ_m = 0.092;  // height of the disc's top face (above the hub, whose top is at 0.07)
  static constexpr double kPathZ_m = 0.085;       // desired path (trace 1 mm above), over the links
  static constexpr double kFloorTopZ_m = -0.02;
};

// The error vector as drawn: gain times actual - desired (0: not drawn), with
// an arrow head of head_mm.
struct ErrorArrow {
  double gain = 0.0;
  double head_mm = 0.0;
};

// A distance as the overlay writes it: 3 significant digits, in um below
// 1 mm, else in mm ("9.26 um", "252 um", "9.70 mm"; the overlay font has
// no micro sign); "< 0.001 um" for a nonzero distance under 1 nm; "-" when
// not finite.
std::string distance_text(double mm);

// Overlay of one run. Holds the decimated desired path and trace.
class OverlayPainter {
 public:
  // spacing_mm: the smallest distance between kept path / trace points;
  // marker_radius_mm and line_px size the marker and the lines; arrow: the
  // magnified error vector.
  OverlayPainter(const Robot& actual, const sim::TrajectoryLog& log, double spacing_mm,
                 double marker_radius_mm, double line_px, ErrorArrow arrow = {});

  // Recolours the chains of a model built by mjcf_from_robot (geom_a*, geom_b*, geom_ee).
  static void paint_model(mjModel* m);

  // Most geoms add_geoms can append.
  int max_geoms() const;

  // Appends the overlay at time t (row: the log row shown) to scn, within its maxgeom.
  void add_geoms(mjvScene* scn, double t, const sim::LogRow& row) const;

  // Left and right columns of the text block for row (mjr_overlay): the
  // time since t0 (the start of the part shown), the error, the error
  // vector's magnification (gain; none if 0) and the readings.
  static std::array<std::string, 2> text(const sim::LogRow& row, double t0 = 0.0, double gain = 0.0);

  const std::vector<Eigen::Vector2d>& desired_points() const { return desired_; }
  size_t trace_points() const { return trace_.size(); }

 private:
  void add_error_arrow(mjvScene* scn, const sim::LogRow& row) const;

  Robot actual_;
  std::vector<Eigen::Vector2d> desired_;
  std::vector<std::pair<double, Eigen::Vector2d>> trace_;  // (t, actual position)
  double marker_radius_m_;
  double line_px_;
  ErrorArrow arrow_;
};

}  // namespace gpm::render
