// Zero-offset auto-calibration on the moving robot (paper section 2.4, steps
// 1-7), driven only through the hardware interface (SafetySupervisor).
//
// The robot stands at R, near the reference point O whose active angles are
// known (IK of the controller model at O). Step 2: offsets = IK(O) - readings(R).
// Step 3: track a circle about O with those offsets, recording the readings at
// the interpolation points. Step 4: E of eq. 19 (calib/projected_error.hpp).
// Steps 5-7 (method grid): the same at the 8 neighbours of the current estimate
// at distance d; recentre on the smallest E; halve d down to d_min.
// Method direct: fit the offsets minimising E from one circle's readings (E is
// quadratic in the offsets, eq. 18-19), move to O with them, repeat until the
// offsets stop changing.
//
// The redundant joint (sensor_joint) is read only (torque off); the other two
// are position controlled. With all three commanded, wrong offsets make the
// servos fight (3 drives, 2 DOF); with one sensor joint the mechanism goes where
// the two commanded joints put it, and the readings are those of a real
// (feasible) configuration whatever the offsets: dtheta_m is feasible (eq. 14)
// and only the offset error survives the projection (eq. 18).
//
// Search coordinates: candidate points are commanded in the frame of the
// initial estimate (pose O + s with the step-2 offsets of the start), so
// "(x_r + d, y_r)" is the robot's point reached by commanding O + (d, 0).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hw/hw_errors.hpp"
#include "hw/safety_supervisor.hpp"

namespace gpm::hw {

enum class ZeroMethod { kGrid, kDirect };

// Text name ("grid", "direct").
const char* zero_method_name(ZeroMethod m);

// Settings of the procedure (constant).
struct ZeroSearchOptions {
  ZeroMethod method = ZeroMethod::kGrid;
  Eigen::Vector2d reference{216.5, 250.0};  // O (mm): its active angles are IK of the controller
  double circle_radius_mm = 30.0;           // step 3 circle about O
  int circle_points = 24;                   // interpolation points recorded per circle
  double circle_speed_mm_s = 80.0;          // peak tangential speed
  double circle_dwell_s = 0.0;              // > 0: stop at each interpolation point and average this long
  double move_speed_mm_s = 40.0;            // point-to-point moves
  double d_initial_mm = 4.0;                // step 5 pattern scope
  double d_min_mm = 0.125;                  // step 7 lower limit
  int sensor_joint = 0;                     // 0-based joint read only: chains 2 and 3 cross best near home
  double min_pair_sine = 0.5;               // driven chains' passive links cross at >= 30 deg
  double max_sensor_gap_rad = 0.1;          // read-only joint vs where the driven joints put it
  double settle_velocity_rad_s = 0.002;     // standing still: every joint slower than this ...
  double settle_hold_s = 0.02;              // ... for this long
  double settle_timeout_s = 2.0;
  double average_s = 0.04;                  // readings at R averaged over this
  double profile_headroom = 0.5;            // fraction of the velocity/acceleration limits used
  int max_rounds = 60;                      // grid: pattern evaluations before giving up
  int direct_iterations = 4;                // direct: circles at most
  double direct_tolerance_rad = 2e-5;       // direct: stop when the offsets move less
  // Step 1 in simulation: before the procedure, jog to this commanded point
  // (controller model as configured) and take it as the initial estimate.
  bool jog_to_start = false;
  Eigen::Vector2d start{216.5, 250.0};
};

// One evaluated estimate of O (steps 2-4).
struct ZeroCandidate {
  int index = 0;                            // evaluation number (0 = initial estimate)
  int round = 0;                            // pattern round (grid) or iteration (direct)
  double d_mm = 0.0;                        // pattern scope when evaluated (0: direct)
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();  // search coordinates (mm, from the start)
  Eigen::Vector3d readings = Eigen::Vector3d::Zero();  // theta_m at R (rad)
  Eigen::Vector3d offsets = Eigen::Vector3d::Zero();   // offsets tracked with (rad)
  double E = 0.0;                           // eq. 19 (rad^2)
  std::vector<Eigen::Vector2d> desired;     // interpolation points (controller frame, mm)
  std::vector<Eigen::Vector3d> circle;      // readings at them (rad)
};

// What the procedure did.
struct ZeroSearchResult {
  ZeroMethod method = ZeroMethod::kGrid;
  bool ok = false;                          // finished (false only in ZeroSearchStopped::partial)
  std::string error;                        // why it stopped (empty when ok)
  Eigen::Vector3d initial_offsets = Eigen::Vector3d::Zero();  // step 2 at the start
  Eigen::Vector3d offsets = Eigen::Vector3d::Zero();          // the result
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();  // final estimate of O, search coordinates
  double E = 0.0;                           // E of the result's circle
  double d_final_mm = 0.0;
  int motions = 0;                          // point-to-point moves and circles commanded
  int circles = 0;
  double robot_time_s = 0.0;                // hardware time (simulated or wall)
  double wall_time_s = 0.0;
  std::vector<ZeroCandidate> trace;         // every evaluation, in order
};

// Throws InputError (one line) for invalid options; nothing moves.
void validate_zero_search_options(const ZeroSearchOptions& options);

// Called after each evaluation (e.g. to append it to a file at once).
using ZeroTraceSink = std::function<void(const ZeroCandidate&)>;

// The search stopped before it finished (drives disabled): what() names the
// estimate, its round and d, the point and the reason; partial() is what was
// done up to then (trace, motions, times); interrupted() when a stop was
// requested (signal) rather than the robot or a point failing.
class ZeroSearchStopped : public HardwareError {
 public:
  ZeroSearchStopped(const std::string& what, ZeroSearchResult partial, bool interrupted);
  const ZeroSearchResult& partial() const { return partial_; }
  bool interrupted() const { return interrupted_; }

 private:
  ZeroSearchResult partial_;
  bool interrupted_;
};

// Runs section 2.4 on hw (configured or not; left finalized). Procedure
// convention (hw/README.md): returns the result (ok = true) when it finished;
// throws InputError for invalid options before anything moves, and
// ZeroSearchStopped (drives disabled) for a failure of the robot, a refused
// point or a stop request through stop (optional; StopOnSignal::flag). Each
// evaluation was handed to sink as it was made.
ZeroSearchResult run_zero_offset_search(SafetySupervisor& hw, const ZeroSearchOptions& options,
                                        const ZeroTraceSink& sink = {},
                                        const std::atomic<bool>* stop = nullptr);

}  // namespace gpm::hw
