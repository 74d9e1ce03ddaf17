// What is drawn on top of the MuJoCo mechanism: chain colours, a floor, base
// markers, the desired path, the end-effector's travelled trace, an
// end-effector marker, and the text (time, tracking error, encoder readings).
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
  static constexpr double kMarkerTopZ_m = 0.092;  // height of the disc's top face (above the hub, whose top is at 0.07)
  static constexpr double kPathZ_m = 0.085;       // desired path (trace 1 mm above), over the links
  static constexpr double kFloorTopZ_m = -0.02;
};

// Overlay of one run. Holds the decimated desired path and trace.
class OverlayPainter {
 public:
  // spacing_mm: the smallest distance between kept path / trace points;
  // marker_radius_mm and line_px size the marker and the lines.
  OverlayPainter(const Robot& actual, const sim::TrajectoryLog& log, double spacing_mm,
                 double marker_radius_mm, double line_px);

  // Recolours the chains of a model built by mjcf_from_robot (geom_a*, geom_b*, geom_ee).
  static void paint_model(mjModel* m);

  // Most geoms add_geoms can append.
  int max_geoms() const;

  // Appends the overlay at time t (row: the log row shown) to scn, within its maxgeom.
  void add_geoms(mjvScene* scn, double t, const sim::LogRow& row) const;

  // Left and right columns of the text block for row (mjr_overlay).
  static std::array<std::string, 2> text(const sim::LogRow& row);

  const std::vector<Eigen::Vector2d>& desired_points() const { return desired_; }
  size_t trace_points() const { return trace_.size(); }

 private:
  Robot actual_;
  std::vector<Eigen::Vector2d> desired_;
  std::vector<std::pair<double, Eigen::Vector2d>> trace_;  // (t, actual position)
  double marker_radius_m_;
  double line_px_;
};

}  // namespace gpm::render
