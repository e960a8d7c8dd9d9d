#include "geometry/toolpath/motion.h"

#include <algorithm>
#include <cmath>

namespace tranche::toolpath {

double trapezoid_time(double len, double v, double ve, double vx, double a) {
  if (len <= 0 || v <= 0) return 0;
  ve = std::min(ve, v);
  vx = std::min(vx, v);
  if (a <= 0) return len / v;
  double d_acc = (v * v - ve * ve) / (2 * a), d_dec = (v * v - vx * vx) / (2 * a);
  if (d_acc + d_dec <= len) return (v - ve) / a + (v - vx) / a + (len - d_acc - d_dec) / v;
  // Never reaches the cruise speed: accelerate to the peak, then brake.
  double peak2 = (2 * a * len + ve * ve + vx * vx) / 2;
  double vp = std::sqrt(std::max(peak2, 0.0));
  if (vp < std::max(ve, vx)) return len / std::max(0.5 * (ve + vx), 1e-3);  // junction too fast for this move
  return (vp - ve) / a + (vp - vx) / a;
}

void MotionClock::start_at(const geo::Point& p) {
  close_pending(0);
  pos_ = p;
}

void MotionClock::close_pending(double exit_speed) {
  if (!pending_.active) return;
  const double t = trapezoid_time(pending_.len, pending_.speed, pending_.entry, exit_speed, pending_.accel);
  total_ += t;
  if (pending_.extruding) extruding_ += t;
  pending_.active = false;
}

void MotionClock::move(const geo::Point& p, double speed, bool extruding) {
  double dx = geo::to_mm(p.X - pos_.X), dy = geo::to_mm(p.Y - pos_.Y);
  double len = std::hypot(dx, dy);
  pos_ = p;
  if (len <= 0 || speed <= 0) return;
  double ux = dx / len, uy = dy / len;
  double entry = 0;
  if (pending_.active) {
    double cosang = std::clamp(pending_.ux * ux + pending_.uy * uy, -1.0, 1.0);
    double half_sin = std::sqrt(std::max(0.0, 0.5 * (1 - cosang)));  // sin(θ/2)
    double vj = std::min(pending_.speed, speed);
    if (half_sin > 1e-9) vj = std::min(vj, lim_.jerk / (2 * half_sin));
    close_pending(vj);
    entry = vj;
  }
  pending_ = {len, speed, ux, uy, extruding ? lim_.print_accel : lim_.travel_accel, entry, true, extruding};
}

void MotionClock::pause(double seconds) {
  close_pending(0);
  total_ += std::max(0.0, seconds);
}

double MotionClock::finish() {
  close_pending(0);
  return total_;
}

}  // namespace tranche::toolpath
