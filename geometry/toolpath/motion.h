// Print time estimate: a trapezoidal speed profile per move (constant acceleration up to the
// programmed speed and down again) with junction speeds limited by a classic jerk rule: the
// speed kept through a corner of angle θ between moves at speed v is min(v, jerk / (2·sin(θ/2))).
// There is no look-ahead beyond the next move, so very short moves are estimated slightly fast.
#pragma once

#include "geometry/core/geom.h"

namespace tranche::toolpath {

struct MotionLimits {
  double print_accel = 1000;   // mm/s², extruding moves
  double travel_accel = 1500;  // mm/s², travel moves
  double jerk = 8;             // mm/s, speed change allowed at a sharp corner
  double z_speed = 12;         // mm/s, layer changes and lifts
};

// Accumulates the time of a stream of moves; feed moves in order, then finish().
class MotionClock {
 public:
  explicit MotionClock(const MotionLimits& limits = {}) : lim_(limits) {}
  // Starts from `p` at rest (after a layer change or a retraction).
  void start_at(const geo::Point& p);
  // A straight move to `p` at `speed` mm/s.
  void move(const geo::Point& p, double speed, bool extruding);
  // A pause in place (retraction, z move), seconds.
  void pause(double seconds);
  // Ends the current move at rest; returns the total time in seconds.
  double finish();
  double seconds() const { return total_; }
  // The part of seconds() spent in extruding moves (a move's time is known once the next one
  // fixes its exit speed, so read this after finish()).
  double extruding_seconds() const { return extruding_; }

 private:
  struct Pending {
    double len = 0, speed = 0, ux = 0, uy = 0, accel = 0, entry = 0;
    bool active = false, extruding = false;
  };
  void close_pending(double exit_speed);

  MotionLimits lim_;
  geo::Point pos_;
  Pending pending_;
  double total_ = 0, extruding_ = 0;
};

// Time of one trapezoidal move: length mm, cruise/entry/exit speeds mm/s, acceleration mm/s².
double trapezoid_time(double len, double cruise, double entry, double exit, double accel);

}  // namespace tranche::toolpath
