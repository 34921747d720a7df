// The simulated inverter's motor: a linear frequency ramp and a steady-state V/f induction-motor model.
// Pure functions of their arguments, no state: the behaviour model (inverter_model.h) keeps the output
// frequency and calls these. Every constant that is not a drive parameter is assumed and listed in
// docs/simulator.md ("Behaviour model").
#pragma once

namespace sim {

// Ramp rates in 0.01 Hz per second. Toshiba's acceleration time is the time from 0 Hz to the maximum
// frequency fh, so rate = fh / time (same for deceleration).
struct RampRates {
  double acceleration = 1.0;
  double deceleration = 1.0;
};

struct RampStep {
  double output = 0.0;          // signed output frequency (0.01 Hz, negative = reverse) after the step
  double seconds_moving = 0.0;  // how long the output was not zero during the step
};

// Moves the signed output frequency `output` towards `target` for `seconds`: accelerates away from 0,
// decelerates towards 0, and passes through 0 (decelerating, then accelerating) to change direction.
RampStep Ramp(double output, double target, const RampRates& rates, double seconds);

// Whether the output is accelerating (+1), steady (0) or decelerating (-1) on its way to `target`.
int RampDirection(double output, double target);

// Drive and motor data, SI units.
struct MotorParameters {
  double base_frequency_hz = 60.0;  // vl (f170 with THR2)
  double base_voltage_v = 200.0;    // vlv (f171 with THR2)
  double torque_boost = 0.06;       // vb as a fraction (f172 with THR2)
  double rated_power_kw = 0.75;     // f405
  double rated_current_a = 3.4;     // f415
  double rated_speed_rpm = 1710.0;  // f417
  int pole_pairs = 2;               // f856
  double drive_rated_current_a = 4.8;  // FE70
  double drive_rated_voltage_v = 200.0;  // FE71
};

struct Electrical {
  double voltage_v = 0.0;               // output voltage (line-line rms)
  double current_a = 0.0;               // output current (rms)
  double torque_percent = 0.0;          // % of motor rated torque; negative when regenerating
  double torque_current_a = 0.0;        // active (torque-producing) current; negative when regenerating
  double excitation_current_a = 0.0;
  double output_power_kw = 0.0;         // sqrt(3) V I cos(phi); negative when regenerating
  double input_power_kw = 0.0;          // from the mains; never negative (no regeneration to the mains)
  double slip_hz = 0.0;
  double speed_hz = 0.0;                // estimated rotor speed as an electrical frequency, >= 0
};

// The motor at `output_hz` (>= 0), changing at `acceleration_hz_per_s` (negative when decelerating),
// driving a constant load torque `load_percent` (% of rated, >= 0). With `dc_braking` the drive injects
// DC into a stopped motor.
Electrical ComputeElectrical(const MotorParameters& p, double output_hz, double acceleration_hz_per_s,
                             double load_percent, bool dc_braking);

// Assumed constants (docs/simulator.md).
namespace motor_constant {
inline constexpr double kMagnetisingFraction = 0.40;     // no-load current / motor rated current
inline constexpr double kLossFraction = 0.05;            // active no-load loss current / rated current
inline constexpr double kSecondsToBaseAtRatedTorque = 0.5;  // inertia: 0 -> vl in 0.5 s at 100 % torque
inline constexpr double kTorqueLimitPercent = 150.0;     // stall prevention at 150 % (f601 default)
inline constexpr double kDcBrakingCurrentFraction = 0.5;  // DC braking current / drive rated current
inline constexpr double kDriveEfficiency = 0.95;         // input power = output power / efficiency
}  // namespace motor_constant

}  // namespace sim
