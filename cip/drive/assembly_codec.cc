// Bit maps of the §5 assemblies (assembly_codec.h, docs/drive-profile.md).
#include "cip/drive/assembly_codec.h"

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {

namespace {

constexpr std::size_t kNativeMinSize = 4;   // 2 words: FA06, FA07 / FD01, FD00
constexpr std::size_t kNativeMaxSize = 16;  // 8 words: + 6 scanner words

// 20/21/101 byte 0
constexpr std::uint8_t kRunForward = 1u << 0;
constexpr std::uint8_t kRunReverse = 1u << 1;  // 21, 101
constexpr std::uint8_t kFaultReset = 1u << 2;
constexpr std::uint8_t kNetCtrl = 1u << 5;  // 21, 101
constexpr std::uint8_t kNetRef = 1u << 6;   // 21, 101

// 70/71/151 byte 0
constexpr std::uint8_t kFaulted = 1u << 0;
constexpr std::uint8_t kWarning = 1u << 1;  // 71, 151
constexpr std::uint8_t kRunning1 = 1u << 2;
constexpr std::uint8_t kRunning2 = 1u << 3;     // 71, 151
constexpr std::uint8_t kReady = 1u << 4;        // 71, 151
constexpr std::uint8_t kCtrlFromNet = 1u << 5;  // 71, 151
constexpr std::uint8_t kRefFromNet = 1u << 6;   // 71, 151
constexpr std::uint8_t kAtReference = 1u << 7;  // 71, 151

// 150 word 0: FD01 without the bits §5.1.6 leaves "-" (3 undervoltage, 15 reserved).
constexpr std::uint16_t kNativeStatusMask = static_cast<std::uint16_t>(~(kFd01Undervoltage | kFd01Reserved));

void DecodeSpeedControl(base::ByteReader& in, bool extended, DriveCommand& command) {
  const std::uint8_t bits = in.U8();
  in.Skip(1);
  command.profile = CommandProfile::kCipSpeed;
  command.run_forward = (bits & kRunForward) != 0;
  command.fault_reset = (bits & kFaultReset) != 0;
  if (extended) {
    command.run_reverse = (bits & kRunReverse) != 0;
    command.has_net_bits = true;
    command.net_ctrl = (bits & kNetCtrl) != 0;
    command.net_ref = (bits & kNetRef) != 0;
  }
  command.speed_reference_rpm = static_cast<std::int16_t>(in.U16Le());
}

void DecodeScannerWords(base::ByteReader& in, DriveCommand& command) {
  const std::size_t count = in.remaining() / 2;
  command.scanner_count = static_cast<std::uint8_t>(count);
  for (std::size_t i = 0; i < count; ++i) command.scanner_words[i] = in.U16Le();
}

void EncodeSpeedStatus(const DriveFeedback& feedback, bool extended, base::ByteWriter& out) {
  std::uint8_t bits = 0;
  if (feedback.faulted) bits |= kFaulted;
  if (feedback.running_forward) bits |= kRunning1;
  if (extended) {
    if (feedback.warning) bits |= kWarning;
    if (feedback.running_reverse) bits |= kRunning2;
    if (feedback.ready) bits |= kReady;
    if (feedback.ctrl_from_net) bits |= kCtrlFromNet;
    if (feedback.ref_from_net) bits |= kRefFromNet;
    if (feedback.at_reference) bits |= kAtReference;
  }
  out.U8(bits);
  out.U8(extended ? static_cast<std::uint8_t>(feedback.state) : 0);
  out.U16Le(feedback.speed_actual_rpm);
}

void EncodeMonitorWords(const DriveFeedback& feedback, base::ByteWriter& out) {
  for (std::size_t i = 0; out.room() >= 2 && i < feedback.monitor_words.size(); ++i) out.U16Le(feedback.monitor_words[i]);
}

// 151 bytes 4-7.
void EncodeParameter151(const ParameterResponse& response, base::ByteWriter& out) {
  if (!response.present) {
    out.U16Le(0);
    out.U16Le(0);
    return;
  }
  std::uint16_t index = static_cast<std::uint16_t>(response.number & kParameterIndexMask);
  if (response.write) index |= kParameterWriteFlag;
  if (response.error) index |= kParameterErrorFlag;
  out.U16Le(index);
  out.U16Le(response.error ? Error151(response.cause) : response.value);
}

// 155 bytes 0-5.
void EncodeParameter155(const ParameterResponse& response, base::ByteWriter& out) {
  out.U8(0);
  out.U8(response.present && response.error ? kFunctionResultError : 0);
  out.U16Le(response.present ? response.number : 0);
  out.U16Le(!response.present ? 0 : response.error ? kErrorToshibaSpecific : response.value);
}

}  // namespace

bool IsOutputInstance(std::uint32_t instance) {
  for (std::uint16_t candidate : kOutputInstances) {
    if (candidate == instance) return true;
  }
  return false;
}

bool IsInputInstance(std::uint32_t instance) {
  for (std::uint16_t candidate : kInputInstances) {
    if (candidate == instance) return true;
  }
  return false;
}

bool IsValidSize(std::uint32_t instance, std::size_t bytes) {
  switch (instance) {
    case kNativeOutput:
    case kNativeInput:
      return bytes >= kNativeMinSize && bytes <= kNativeMaxSize && bytes % 2 == 0;
    default:
      return bytes != 0 && bytes == AssemblySize(instance);
  }
}

std::size_t AssemblySize(std::uint32_t instance) {
  switch (instance) {
    case kBasicSpeedOutput:
    case kExtendedSpeedOutput:
    case kBasicSpeedInput:
    case kExtendedSpeedInput:
      return 4;
    case kNativeOutput:
    case kNativeInput:
      return kNativeMaxSize;
    case kNativeParameterOutput:
    case kNativeParameterInput:
      return 8;
    case kScannerOutput:
    case kScannerInput:
      return 12;
    case kToshibaOutput:
    case kToshibaInput:
      return 18;
    default:
      return 0;
  }
}

std::uint16_t PairedInput(std::uint32_t output_instance) {
  for (std::size_t i = 0; i < kOutputInstances.size(); ++i) {
    if (kOutputInstances[i] == output_instance) return kInputInstances[i];
  }
  return 0;
}

bool DecodeOutput(std::uint32_t instance, std::span<const std::uint8_t> data, DriveCommand& command) {
  if (!IsOutputInstance(instance) || !IsValidSize(instance, data.size())) return false;
  DriveCommand decoded;
  decoded.instance = static_cast<std::uint16_t>(instance);
  base::ByteReader in(data);
  switch (instance) {
    case kBasicSpeedOutput:
      DecodeSpeedControl(in, false, decoded);
      break;
    case kExtendedSpeedOutput:
      DecodeSpeedControl(in, true, decoded);
      break;
    case kNativeOutput: {
      decoded.profile = CommandProfile::kNative;
      decoded.native_command = in.U16Le();
      decoded.native_frequency = in.U16Le();
      decoded.has_net_bits = true;
      decoded.net_ctrl = (decoded.native_command & drive_link::reg::command_bit::kCommandPriority) != 0;
      decoded.net_ref = (decoded.native_command & drive_link::reg::command_bit::kFrequencyPriority) != 0;
      decoded.fault_reset = (decoded.native_command & drive_link::reg::command_bit::kFaultReset) != 0;
      DecodeScannerWords(in, decoded);
      break;
    }
    case kNativeParameterOutput: {
      DecodeSpeedControl(in, true, decoded);
      const std::uint16_t index = in.U16Le();
      decoded.parameter.present = true;
      decoded.parameter.write = (index & kParameterWriteFlag) != 0;
      decoded.parameter.number = static_cast<std::uint16_t>(index & kParameterIndexMask);
      decoded.parameter.data = in.U16Le();
      decoded.parameter.function = decoded.parameter.write ? kFunctionWrite : kFunctionRead;
      break;
    }
    case kScannerOutput:
      decoded.profile = CommandProfile::kScanner;
      DecodeScannerWords(in, decoded);
      break;
    case kToshibaOutput: {
      decoded.profile = CommandProfile::kScanner;
      in.Skip(1);  // byte 0: blank in §5.1.11
      const std::uint8_t function = in.U8();
      decoded.parameter.present = true;
      decoded.parameter.function = function;
      decoded.parameter.valid = function == kFunctionRead || function == kFunctionWrite;
      decoded.parameter.write = function == kFunctionWrite;
      decoded.parameter.number = in.U16Le();
      decoded.parameter.data = in.U16Le();
      DecodeScannerWords(in, decoded);
      break;
    }
    default:
      return false;
  }
  if (!in.ok()) return false;  // cannot happen after IsValidSize; kept as the reader's contract
  command = decoded;
  return true;
}

bool EncodeInput(std::uint32_t instance, const DriveFeedback& feedback, std::span<std::uint8_t> out) {
  if (!IsInputInstance(instance) || !IsValidSize(instance, out.size())) return false;
  base::ByteWriter writer(out);
  switch (instance) {
    case kBasicSpeedInput:
      EncodeSpeedStatus(feedback, false, writer);
      break;
    case kExtendedSpeedInput:
      EncodeSpeedStatus(feedback, true, writer);
      break;
    case kNativeInput:
      writer.U16Le(static_cast<std::uint16_t>(feedback.status_word & kNativeStatusMask));
      writer.U16Le(feedback.output_frequency);
      EncodeMonitorWords(feedback, writer);
      break;
    case kNativeParameterInput:
      EncodeSpeedStatus(feedback, true, writer);
      EncodeParameter151(feedback.parameter, writer);
      break;
    case kScannerInput:
      EncodeMonitorWords(feedback, writer);
      break;
    case kToshibaInput:
      EncodeParameter155(feedback.parameter, writer);
      EncodeMonitorWords(feedback, writer);
      break;
    default:
      return false;
  }
  return writer.ok() && writer.size() == out.size();
}

}  // namespace cip::drive
