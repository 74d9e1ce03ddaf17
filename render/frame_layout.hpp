// Where things go in a frame: a column on the left of each panel for the
// text (caption, time, error, encoder readings), the legend and the scale
// bar, and the mechanism framed in the rest of the panel so that no overlay
// covers it. Pure geometry, no OpenGL.
#pragma once

#include <vector>

#include "render/camera_set.hpp"

namespace gpm::render {

// The region to give a free camera filling a panel of panel_w x panel_h
// pixels so that region f (mm) lands, as large as fits and centred, in the
// part of the panel right of a left column of column_px pixels, pad_px
// clear of every edge. (The camera fits the returned region exactly: it has
// the panel's aspect.)
Framing frame_beside_column(const Framing& f, int panel_w, int panel_h, int column_px, int pad_px);

// The longest "round" length (1, 2 or 5 x 10^k mm) whose bar at px_per_mm
// pixels per millimetre is at most max_px pixels long (0 if none >= 0.1 mm).
double scale_bar_mm(double px_per_mm, double max_px);

// Pixels per millimetre, at height z_m above the plane, of a free camera
// looking straight down from distance_m above the plane with vertical field
// fovy_deg, in a viewport panel_h pixels high (pinhole).
double top_px_per_mm(double distance_m, double z_m, double fovy_deg, int panel_h);

// The magnification of a run's error vector: the largest round number (1, 2
// or 5 x 10^k, from 1 to 1e5) at which the 95th percentile of errors_mm is drawn at most target_px
// long at px_per_mm (1 if there is no error), so that a 10 mm and a 10 um
// error both read as an arrow of tens of pixels.
double error_gain(std::vector<double> errors_mm, double px_per_mm, double target_px);

}  // namespace gpm::render
