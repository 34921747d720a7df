// Unit 255: the IO scanning server (seed 000 §9, MB-4).
//
// 32 periodic words each way. Output words (written by the IO scanner): 1-6 are the command words of
// c001-c006; input words (read by the IO scanner): 1-6 are the monitor words of c021-c026. Words 0 and
// 7-31 are reserved: they read 0 and writes to them are accepted and ignored (the seed's own PL7
// example, §10.4, writes all 32 words). The mapping of a word to a drive register is the cyclic
// exchange's (drive_link::ScannerImage); this server only moves words in and out of it.
//
// Functions (decided, docs/modbus.md): 23 writes output words and then reads input words in one
// request (the Modbus order); 03 reads input words; 06 and 16 write output words. The server answers
// only while c604 = 1 and, when c600-c603 is not 0.0.0.0, only to that master; otherwise every
// request to unit 255 gets exception 01 (Modbus: "the server is in the wrong state ... unconfigured").
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "config/card_config.h"
#include "drive_link/register_access.h"
#include "base/addresses.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "modbus/pdu.h"

namespace modbus {

inline constexpr std::uint16_t kIoScanWordCount = 32;

// kNone when `peer` may use unit 255 under `config`, otherwise kIllegalFunction.
ExceptionCode IoScanningAccess(const config::CardConfig& config, const base::Ipv4Address& peer);

// Whether the control registers (reg::IsControlRegister: FA00-FAFF, cmod, fmod, f207, f899) are locked
// for `peer` through units 0-248: while c604 = 1 and a master c600-c603 is configured, for every client
// but that master (docs/modbus.md "Unit 255"). The master's own writes, and everyone's while no master is
// configured, are only subject to the §9.1 reservation of the scanner's targets.
bool ControlLockedFor(const config::CardConfig& config, const base::Ipv4Address& peer);

// Whether a decoded request to unit 255 writes output words (FC 06, 16, 23): what IO scanning
// supervision counts as communication (docs/modbus.md "Loss supervision").
bool IsIoScanningWrite(const Request& request);

// Serves a decoded request to unit 255 whose access was granted; writes the answer PDU (normal or
// exception). Words outside 0-31 are exception 02; function 43 is the caller's.
void ServeIoScanner(const Request& request, drive_link::ScannerImage& scanner, base::ByteWriter& writer);

}  // namespace modbus
