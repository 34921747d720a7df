#include "sim/motor_model.h"

#include <algorithm>
#include <cmath>

namespace sim {
namespace {

double Sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

}  // namespace

int RampDirection(double output, double target) {
  if (output == target) return 0;
  const bool same_side = (output >= 0.0 && target >= 0.0) || (output <= 0.0 && target <= 0.0);
  if (same_side && std::fabs(target) > std::fabs(output)) return 1;
  return -1;
}

RampStep Ramp(double output, double target, const RampRates& rates, double seconds) {
  RampStep step{output, 0.0};
  double left = seconds;
  // At most three segments: decelerate to 0, accelerate to the target, hold.
  for (int segment = 0; segment < 3 && left > 0.0 && step.output != target; ++segment) {
    const int direction = RampDirection(step.output, target);
    // Decelerating towards the other side of zero stops at zero first.
    const bool through_zero = direction < 0 && step.output != 0.0 && Sign(step.output) != Sign(target) &&
                              target != 0.0;
    const double goal = through_zero ? 0.0 : target;
    const double rate = direction > 0 ? rates.acceleration : rates.deceleration;
    const double needed = std::fabs(goal - step.output) / rate;
    if (needed <= left) {
      step.output = goal;
      step.seconds_moving += needed;
      left -= needed;
    } else {
      step.output += Sign(goal - step.output) * rate * left;
      step.seconds_moving += left;
      left = 0.0;
    }
  }
  if (step.output != 0.0) step.seconds_moving += left;  // holding a non-zero target
  return step;
}

Electrical ComputeElectrical(const MotorParameters& p, double output_hz, double acceleration_hz_per_s,
                             double load_percent, bool dc_braking) {
  using namespace motor_constant;
  Electrical e;
  if (dc_braking) {
    e.current_a = kDcBrakingCurrentFraction * p.drive_rated_current_a;
    e.voltage_v = p.torque_boost * p.base_voltage_v;
    e.output_power_kw = e.voltage_v * e.current_a / 1000.0;
    e.input_power_kw = e.output_power_kw / kDriveEfficiency;
    return e;
  }
  if (output_hz <= 0.0) return e;

  // V/f: boost at 0 Hz rising linearly to vlv at vl, constant above.
  const double ratio = std::min(1.0, output_hz / p.base_frequency_hz);
  e.voltage_v = p.base_voltage_v * (p.torque_boost + (1.0 - p.torque_boost) * ratio);

  // Torque: the load plus what the ramp needs, limited by stall prevention.
  const double acceleration_torque =
      100.0 * acceleration_hz_per_s * kSecondsToBaseAtRatedTorque / p.base_frequency_hz;
  e.torque_percent = std::clamp(load_percent + acceleration_torque, -kTorqueLimitPercent, kTorqueLimitPercent);

  // Currents: constant flux up to vl, field weakening above (less flux, more current per torque).
  const double weakening = std::max(1.0, output_hz / p.base_frequency_hz);
  const double torque_current_at_rated =
      std::sqrt(1.0 - kMagnetisingFraction * kMagnetisingFraction) * p.rated_current_a;
  e.excitation_current_a = kMagnetisingFraction * p.rated_current_a / weakening;
  e.torque_current_a = e.torque_percent / 100.0 * torque_current_at_rated * weakening;
  e.current_a = std::hypot(e.excitation_current_a, e.torque_current_a);

  // Power: sqrt(3) V I cos(phi), the active current being the torque current plus the no-load losses.
  const double active_current_a = e.torque_current_a + kLossFraction * p.rated_current_a;
  e.output_power_kw = std::sqrt(3.0) * e.voltage_v * active_current_a / 1000.0;
  e.input_power_kw = std::max(0.0, e.output_power_kw) / kDriveEfficiency;

  // Slip proportional to torque; rated slip from the rated speed and the pole pairs.
  const double synchronous_rated_rpm = 60.0 * p.base_frequency_hz / p.pole_pairs;
  const double rated_slip_hz =
      std::clamp((synchronous_rated_rpm - p.rated_speed_rpm) * p.pole_pairs / 60.0, 0.0, 0.2 * p.base_frequency_hz);
  e.slip_hz = rated_slip_hz * e.torque_percent / 100.0;
  e.speed_hz = std::max(0.0, output_hz - e.slip_hz);
  return e;
}

}  // namespace sim
