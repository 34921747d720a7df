// The simulated VF-MB1 / VF-S15 inverter's behaviour: register reads and writes, the drive state machine,
// the motor, trips, resets, power cycles and the EEPROM image. No I/O and no protocol: the protocol server
// (the Toshiba/Modbus codec on the simulated serial link) calls Read/Write and asks in_reset()/tripped();
// the control socket drives the terminals, the panel, the load and trips.
//
// Deterministic: the state depends only on the sequence of calls. Time moves only in Advance(now) (the
// hal::Clock's microseconds, monotonic); the first Advance sets the time base. Every register lives in
// registers.csv / register_table.h; values are integers in the register's unit step, exactly what the
// wire carries (a written value reads back unchanged). docs/simulator.md "Behaviour model" lists every
// behaviour with its source and every assumed value.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "drive_link/drive_registers.h"
#include "hal/clock.h"
#include "sim/drive_command.h"
#include "sim/motor_model.h"
#include "sim/register_table.h"

namespace sim {

// Toshiba protocol W writes RAM and EEPROM, P writes RAM only (E6581913 caution page; seed 003 §13.8).
enum class WriteTarget : std::uint8_t { kRamAndEeprom, kRamOnly };

enum class WriteOutcome : std::uint8_t {
  kOk,
  kNoSuchRegister,           // the number does not exist (on this model): "communication number error"
  kOutOfRange,               // outside the static or run-time limits: "data error"
  kNotWritableWhileRunning,  // write_during_run = no and the drive runs: "impossible to execute"
  kReadOnly,                 // a monitor: nobody writes it
};

struct WriteResult {
  WriteOutcome outcome = WriteOutcome::kOk;
  // The write raised the fault-reset bit (FA06/FA00 bit 13, 0 -> 1): "no data is returned from the
  // drive" (seed 000 §3.2.4.2), so the protocol server sends no reply to this request.
  bool no_reply = false;

  bool ok() const { return outcome == WriteOutcome::kOk; }
};

const char* WriteOutcomeName(WriteOutcome outcome);

// Trip codes (FC90, FE10-FE13). err8 and e-23 are the card's too (drive_link/drive_registers.h).
namespace trip_code {
inline constexpr std::uint8_t kNone = 0;
inline constexpr std::uint8_t kEmergencyStop = 0x11;      // "E", 17 (seed 003 §10, VF-S11 table)
inline constexpr std::uint8_t kRs485Timeout = 0x18;       // "err5", 24 (seed 003 §10; S15 unverified)
// "err8", 27 (seed 000 §3.2.3, §12.2) and "e-23", 55 (seed 000 §12.1).
inline constexpr std::uint8_t kOptionCommunication = static_cast<std::uint8_t>(drive_link::reg::kErr8TripCode);
inline constexpr std::uint8_t kOptionFault = static_cast<std::uint8_t>(drive_link::reg::kE23TripCode);
}  // namespace trip_code

enum class AnalogInput : std::uint8_t { kVia, kVib, kVic };

// Bits of FD01 (seed 000 §3.2.4.7). The bits the card acts on are the card's definition
// (drive_link/drive_registers.h); the others only the simulator computes.
namespace status_bit {
using drive_link::reg::status_bit::kAlarm;
using drive_link::reg::status_bit::kEmergencyStopped;
using drive_link::reg::status_bit::kFailureFl;
using drive_link::reg::status_bit::kReady;
using drive_link::reg::status_bit::kReadyStRun;
using drive_link::reg::status_bit::kRunning;
using drive_link::reg::status_bit::kStOff;
using drive_link::reg::status_bit::kTripped;
inline constexpr std::uint16_t kUndervoltage = 1u << 3;
inline constexpr std::uint16_t kThr2 = 1u << 4;
inline constexpr std::uint16_t kPidOff = 1u << 5;
inline constexpr std::uint16_t kAd2 = 1u << 6;
inline constexpr std::uint16_t kDcBraking = 1u << 7;
inline constexpr std::uint16_t kJog = 1u << 8;
inline constexpr std::uint16_t kReverse = 1u << 9;
}  // namespace status_bit

// FC91 bits the model itself raises (seed 000 §3.2.4.13).
inline constexpr int kAlarmBitOptionCommunication = 11;

struct ModelTiming {
  // No communication after power-on, about 1 s (E6581913 p.6; seed 003 §13.14).
  hal::Micros power_on = hal::kMicrosPerSecond;
  // No communication after a fault reset or f899 = 1 while the drive initialises (assumed: as power-on).
  hal::Micros reset = hal::kMicrosPerSecond;
};

class InverterModel {
 public:
  // EEPROM life warning threshold per parameter (seed 003 §13.8; vf-s15-registers.md §13).
  static constexpr std::uint32_t kEepromWriteWarning = 10000;

  explicit InverterModel(Model model, const ModelTiming& timing = {});

  Model model() const { return model_; }

  // Registers. Read: NotFound when the number does not exist on this model.
  base::Result<std::uint16_t> Read(std::uint16_t number) const;
  WriteResult Write(std::uint16_t number, std::uint16_t word, WriteTarget target);

  // Moves time to `now` (ignored if earlier than the last call): ramps, hours, energy, loss delays.
  void Advance(hal::Micros now);
  hal::Micros now() const { return now_; }

  // The drive is initialising (after power-on, a fault reset, f899 = 1) and does not communicate.
  bool in_reset(hal::Micros now) const { return now < reset_until_; }
  hal::Micros ResetInProgressUntil() const { return reset_until_; }

  // State.
  bool tripped() const { return trip_ != trip_code::kNone; }
  std::uint8_t trip() const { return trip_; }
  bool running() const;  // FD01 bit 10: run state or output not yet at 0 Hz
  std::uint16_t StatusWord() const;  // FD01
  std::int32_t output_frequency() const;  // FD00, 0.01 Hz
  std::int32_t target_frequency() const;  // where the ramp is heading: signed 0.01 Hz, 0 when stopped
  double output_frequency_signed() const { return output_; }  // 0.01 Hz, negative in reverse
  std::int32_t motor_speed_rpm() const;  // estimated speed (FD16) in min-1 with f856 pole pairs
  DriveCommand command() const;          // what the source in command asks for now
  Electrical electrical() const;

  // Inputs for the control socket.
  void SetTerminal(Terminal terminal, bool on);
  bool SetTerminal(std::string_view name, bool on);  // F R RES S1 S2 S3 VIB VIA ST; false if unknown
  bool terminal(Terminal terminal) const;
  void SetPanelFrequency(std::int32_t centi_hz);  // fmod 0/3
  void SetPanelRun(bool run, bool reverse);      // cmod 1
  void SetAnalogInput(AnalogInput input, std::int32_t centi_percent);  // FE35-FE37
  void SetLoadTorque(std::int32_t centi_percent);  // constant load torque, % of motor rated, >= 0
  void SetAlarm(int bit, bool on);                // FC91 bits raised from outside

  // Trips now with `code` unless already tripped (the first trip holds).
  void Trip(std::uint8_t code);
  // The panel/RES reset of a trip; false when not tripped or the trip needs a power cycle (err8, e-23).
  bool FaultReset();

  // The option reports its network lost / back: FC91 bit 11 while lost; after c100 the c101 action if
  // c103 allows (seed 000 §3.2.3).
  void OptionCommunicationLost();
  void OptionCommunicationRestored();
  bool option_communication_lost() const { return loss_ != Loss::kNone; }

  // Power off and on: RAM reloaded from the EEPROM image, RAM-only registers to defaults, trips cleared,
  // motor stopped, no communication for ModelTiming::power_on.
  void PowerCycle();

  // EEPROM image.
  std::uint32_t EepromWriteCount(std::uint16_t number) const;
  std::int32_t EepromValue(std::uint16_t number) const;  // 0 for registers without EEPROM storage
  // The value in force: for effective-after-reset registers ((*3)) the one at the last power-on or
  // f899 reset, for the others the current value. 0 when the number does not exist.
  std::int32_t ActiveValue(std::uint16_t number) const;
  std::uint64_t operation_micros() const { return operation_us_; }
  std::uint64_t power_on_micros() const { return power_on_us_; }

  // Text image of the EEPROM (values, write counters, cumulative hours, energy, trip history). Load
  // replaces the image and reloads RAM from it as at power-on; false (nothing changed) if malformed or
  // for the other model.
  std::string SerializeEeprom() const;
  bool LoadEeprom(std::string_view text);
  // Moves on whenever the image's register values, write counters or trip history change, so whoever
  // stores the image knows a setting changed; the cumulative time and energy counters do not move it.
  std::uint64_t eeprom_generation() const { return eeprom_generation_; }

 private:
  enum class Loss : std::uint8_t { kNone, kPending, kActive };

  std::size_t Index(const RegisterInfo& info) const;
  const RegisterInfo& Info(std::uint16_t number) const;  // for numbers the model always has
  std::int32_t Value(std::uint16_t number) const;        // RAM value of a stored register
  void SetRam(std::uint16_t number, std::int32_t value);
  WriteOutcome CheckRunTimeLimits(std::uint16_t number, std::int32_t value) const;
  void AfterCommandWrite(std::uint16_t old_word, std::uint16_t new_word, WriteResult& result);
  void ApplyImmediateEffects();
  void ResetRamOnlyHostRegisters();
  void Reinitialise(hal::Micros silence);  // power-on and f899: RAM from EEPROM, trips cleared
  void StartSilence(hal::Micros duration);
  void ExecuteTyp(std::int32_t choice);
  void ClearTrip();
  void ApplyLossAction();
  void AdvanceTo(hal::Micros now);

  CommandInputs Inputs() const;
  double TargetFrequency(const DriveCommand& cmd) const;  // signed 0.01 Hz
  bool RunEffective(const DriveCommand& cmd) const;
  RampRates Rates(const DriveCommand& cmd) const;
  MotorParameters Motor(const DriveCommand& cmd) const;
  std::int32_t MonitorValue(const RegisterInfo& info) const;
  std::int32_t LiveTripHoldValue(std::uint16_t number) const;
  std::uint16_t InputTerminalWord() const;
  std::uint16_t OutputTerminalWord() const;
  std::uint16_t AlarmWord() const;
  std::int32_t EnergyRaw(double kwh) const;

  Model model_;
  ModelTiming timing_;
  std::span<const RegisterInfo> table_;
  std::vector<std::int32_t> ram_;
  std::vector<std::int32_t> eeprom_;
  std::vector<std::uint32_t> eeprom_writes_;
  std::vector<std::int32_t> active_;  // values in force of effective-after-reset registers
  std::vector<std::int32_t> held_;    // trip-hold values captured at the trip
  std::uint64_t eeprom_generation_ = 0;

  // Time.
  bool time_known_ = false;
  hal::Micros now_ = 0;
  hal::Micros reset_until_ = 0;
  hal::Micros pending_silence_ = 0;  // silence to start at the first Advance

  // Drive.
  std::uint8_t trip_ = trip_code::kNone;
  std::array<std::uint8_t, 4> trip_history_{};  // FE10 (most recent) .. FE13
  double output_ = 0.0;                          // signed, 0.01 Hz
  double igbt_temperature_c_ = 25.0;
  std::uint64_t operation_us_ = 0;  // FE14
  std::uint64_t power_on_us_ = 0;   // FE80
  double input_kwh_ = 0.0;          // FE76
  double output_kwh_ = 0.0;         // FE77

  // Inputs.
  std::uint16_t terminals_ = 0;  // FD06 bit order, bit 8 = ST
  bool panel_run_ = false;
  bool panel_reverse_ = false;
  std::int32_t panel_frequency_ = 0;
  std::array<std::int32_t, 3> analog_{};
  std::int32_t load_percent_ = 0;  // 0.01 %
  std::uint16_t external_alarms_ = 0;

  // Communication loss (c100-c103).
  Loss loss_ = Loss::kNone;
  hal::Micros loss_deadline_ = 0;
  std::int32_t loss_action_ = 1;
};

}  // namespace sim
