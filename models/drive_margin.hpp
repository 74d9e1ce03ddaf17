// How far a pose is from losing control, for the drives actually in position
// mode, in the controller's model widened by its uncertainty (closed form;
// millimetres, radians).
//
// With all three drives in position the mechanism is the 3-RRR; with one
// drive torque-off (the redundant joint, e.g. `servo.modes: [torque_off,
// position, position]`) the two driven chains form a five-bar that carries
// the hub, and the free chain follows it. What loses control:
//  - type 1 (serial) of a driven chain: its passive link aligned with its
//    active link, |sin(theta_a - theta_b)| -> 0 (eq. 11's denominator); the
//    drive no longer moves the hub across the link;
//  - type 1 of a free chain: its own elbow folds or stretches (the hub on the
//    chain's annulus edge); past it the chain changes elbow branch;
//  - type 2 (parallel) of the driven mechanism: the passive links of the
//    driven chains parallel, so the hub can move with every drive held
//    (three drives: gpm::Conditioning::direct; two drives i, j: the smallest
//    singular value of the 2x2 matrix of their passive-link directions,
//    sqrt(1 - |cos(theta_b_i - theta_b_j)|), 1 at 90 degrees). Passing
//    through it the five-bar changes assembly mode: the hub jumps to the
//    other intersection of the two passive circles;
//  - the workspace border: the distance from each chain's annulus edge;
//  - the deviation: where the perturbed mechanism puts the hub, away from p
//    (near type 2 a small model error moves the hub far), which the
//    tracking watch would see.
// The measures are taken where the mechanism really goes: the driven joints
// at the controller's command for p (inverse kinematics of its model, eq.
// 31, 35), the hub where they put a mechanism of the perturbed geometry
// (forward kinematics, eq. 32-34, or the driven pair's circles in the
// assembly mode of the unperturbed pose).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "models/robot.hpp"

namespace gpm {

// Which chains' drives hold position (the others are torque-off or hold a
// constant torque: free). At least two are true.
using DriveMask = std::array<bool, kNumChains>;

// How well the controller knows its geometry (the data-sheet tolerances of
// an uncalibrated machine): each parameter may be off by up to this much.
struct ModelTolerance {
  double base_mm = 1.0;     // every base coordinate xa*, ya*
  double link_mm = 1.0;     // every link length la*, lb*
  double offset_rad = 0.02; // every encoder zero offset dth*
  bool operator==(const ModelTolerance&) const = default;
};

// How far parameter k (Geometry index) may be off by t: offset_rad, link_mm or base_mm.
double tolerance_of(const ModelTolerance& t, int k);

// The margin a planned path keeps from losing control (defaults documented
// in scenarios/SCHEMA.md, `sampling.path_margin`).
struct PathMargin {
  double singularity = 0.15;  // every normalised measure (transmission, direct) at least this
  double reach_mm = 10.0;    // distance from every chain's annulus edge at least this
  double deviation_mm = 20.0;  // the hub's statistical (RSS) deviation from the plan at most this (the tracking watch's bound)
  ModelTolerance tolerance;  // the controller model's uncertainty the margin must cover
  bool operator==(const PathMargin&) const = default;
};

// The measures at one pose (see the header comment).
struct DriveMargins {
  bool ok = false;            // false when the mechanism cannot reach or assemble there
  double reach_mm = 0.0;      // smallest distance from an annulus edge, any chain
  int reach_chain = 0;        // 0-based chain of reach_mm
  double transmission = 0.0;  // smallest |sin(theta_a - theta_b)|, any chain
  int transmission_chain = 0; // 0-based chain of transmission
  double direct = 0.0;        // type 2 of the driven mechanism (normalised, 1 at the best spread)
  double deviation_mm = 0.0;  // hub's distance from p over the tolerance (RSS stack-up); 0 in the controller's model
};

// The measures of the controller's model at p (ok false when p is out of reach).
DriveMargins drive_margins(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives);

// The worst measures over the tolerance box to first order: each measure at
// the controller's geometry less sum_k |m(g + t_k e_k) - m(g - t_k e_k)| / 2
// over the 15 parameters, the perturbed mechanism driven by the controller's
// commands for p; deviation_mm the statistical stack-up of where it puts the
// hub, sqrt(sum_k |p(g + t_k e_k) - p(g - t_k e_k)|^2 / 4). A perturbed mechanism that cannot assemble there has lost
// that margin: 0 for direct (the driven passive circles do not meet: past a
// type-2 singularity) or for reach_mm and transmission (the hub outside a
// chain's annulus). ok false when p is out of the controller's reach.
DriveMargins drive_margins(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives,
                           const ModelTolerance& tolerance);

// Why p breaks the margin (one sentence naming the measure, its value, the
// margin and the chains), empty when it keeps it.
std::string margin_violation(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives,
                             const PathMargin& margin);

}  // namespace gpm
