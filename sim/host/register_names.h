// Inverter registers as a person types them on the command line (--param) or the control socket
// (get/set): a panel title or a communication number, and a value in the register's unit step.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "sim/register_table.h"

namespace sim {

// "acc", "C500", "fa06" (a panel title, case ignored) or "0009", "FA06" (4 hex digits). A title wins
// over the same letters read as hex: "f800" is f800 = 0x0800 (the drive has no F800). nullptr with
// `error` set: "unknown register 'foo'", "no communication number 000A (numbers ending in A-F do not
// exist)", "no communication number 0001", "0123 does not exist on vf-s15".
const RegisterInfo* ResolveRegister(std::string_view name, Model model,
                                                    std::string& error);

// A decimal integer with an optional sign, or 0x-hex ("50", "-100", "0x1F40"). False for anything
// else, including values beyond what 32 bits hold.
bool ParseRegisterValue(std::string_view text, std::int32_t& value);

// "acc = 50 (0x0032)": the title, the value in its unit step (signed registers negative) and the word
// on the wire.
std::string FormatRegisterValue(const RegisterInfo& info, std::uint16_t word);

// "out of range 0..60000" for `info` on `model` when `value` is outside its static limits; empty when
// inside.
std::string StaticRangeError(const RegisterInfo& info, Model model,
                             std::int32_t value);

}  // namespace sim
