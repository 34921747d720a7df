// A hal::Flash in RAM that enforces the rules of hal/flash.h and can lose power in the middle of any
// Program or Erase, leaving the mixes the contract allows. Copyable: a test saves the whole part before
// an operation and puts it back to try the next cut.
//
// Steps: every byte programmed and every Erase is one step, counted from construction (steps()). A cut
// armed at step S falls while step S is under way: the units of that Program before the one holding
// byte S are complete, that unit is torn (CutMix), the units after it untouched; an Erase at step S
// leaves its sector torn. From then on the part has no power: every call answers kUnavailable and
// changes nothing, until PowerOn().
//
// Torn units (and every unit of a sector whose erase was cut) count as programmed until a complete
// erase, whatever they read, so programming one again is refused (kFailedPrecondition), as on a part with
// ECC. With set_torn_units_unreadable(true) a read touching one answers kDataLoss (an ECC error).
//
// Every call the contract forbids (misaligned, past the end, a unit programmed twice) is refused with the
// contract's code and counted in violations(): a store under test must keep it at 0.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "base/status.h"
#include "hal/flash.h"

namespace hal::test {

// What a cut leaves in the unit being programmed (or the sector being erased). Old bits are those
// before the operation (0xFF for a fresh unit); new bits those it was writing (0xFF for an erase).
enum class CutMix {
  kOld,        // nothing of the unit (sector) changed
  kPartlyNew,  // written front to back: the bytes before the cut new, the cut byte with the new bits
               // of its low nibble only, the rest old (an erase: a seeded point in the sector)
  kRandom,     // every bit independently old or new (seeded)
  kNew,        // all new: the cut came as the unit (sector) was done, and it still counts as torn
};

class FakeFlash final : public Flash {
 public:
  FakeFlash(std::size_t sector_size, std::size_t sector_count, std::size_t program_unit)
      : sector_size_(sector_size),
        sector_count_(sector_count),
        unit_(program_unit),
        bytes_(sector_size * sector_count, 0xFF),
        programmed_(bytes_.size() / program_unit, false),
        torn_(bytes_.size() / program_unit, false),
        erases_(sector_count, 0) {}

  std::size_t SectorSize() const override { return sector_size_; }
  std::size_t SectorCount() const override { return sector_count_; }
  std::size_t ProgramUnit() const override { return unit_; }

  base::Status Read(std::size_t offset, std::span<std::uint8_t> out) override {
    if (!powered_) return base::Unavailable();
    if (offset > bytes_.size() || out.size() > bytes_.size() - offset) return Violation(base::OutOfRange());
    if (torn_unreadable_ && !out.empty()) {
      for (std::size_t unit = offset / unit_; unit <= (offset + out.size() - 1) / unit_; ++unit) {
        if (torn_[unit]) return base::DataLoss();
      }
    }
    std::copy_n(bytes_.begin() + static_cast<std::ptrdiff_t>(offset), out.size(), out.begin());
    return base::OkStatus();
  }

  base::Status Erase(std::size_t sector) override {
    if (!powered_) return base::Unavailable();
    if (sector >= sector_count_) return Violation(base::OutOfRange());
    const std::size_t first = sector * sector_size_;
    const std::size_t units = sector_size_ / unit_;
    if (CutNow()) {
      TearErase(first);
      std::fill_n(programmed_.begin() + static_cast<std::ptrdiff_t>(first / unit_), units, true);
      std::fill_n(torn_.begin() + static_cast<std::ptrdiff_t>(first / unit_), units, true);
      return PowerFails();
    }
    ++steps_;
    ++erases_[sector];
    std::fill_n(bytes_.begin() + static_cast<std::ptrdiff_t>(first), sector_size_, std::uint8_t{0xFF});
    std::fill_n(programmed_.begin() + static_cast<std::ptrdiff_t>(first / unit_), units, false);
    std::fill_n(torn_.begin() + static_cast<std::ptrdiff_t>(first / unit_), units, false);
    return base::OkStatus();
  }

  base::Status Program(std::size_t offset, std::span<const std::uint8_t> data) override {
    if (!powered_) return base::Unavailable();
    if (offset > bytes_.size() || data.size() > bytes_.size() - offset) return Violation(base::OutOfRange());
    if (offset % unit_ != 0 || data.size() % unit_ != 0) return Violation(base::InvalidArgument());
    for (std::size_t unit = offset / unit_; unit < (offset + data.size()) / unit_; ++unit) {
      if (programmed_[unit]) return Violation(base::FailedPrecondition());
    }
    for (std::size_t done = 0; done < data.size(); done += unit_) {
      const std::size_t at = offset + done;
      const std::span<const std::uint8_t> unit_data = data.subspan(done, unit_);
      programmed_[at / unit_] = true;
      if (cut_step_ && *cut_step_ < steps_ + unit_) {
        const std::uint64_t cut = *cut_step_ > steps_ ? *cut_step_ - steps_ : 0;
        TearProgram(at, unit_data, static_cast<std::size_t>(cut));
        torn_[at / unit_] = true;
        return PowerFails();
      }
      for (std::size_t i = 0; i < unit_; ++i) bytes_[at + i] &= unit_data[i];
      steps_ += unit_;
    }
    return base::OkStatus();
  }

  // Power is lost while step `step` is under way, leaving `mix` (random draws from `seed`).
  void CutPowerAtStep(std::uint64_t step, CutMix mix, std::uint32_t seed = 1) {
    cut_step_ = step;
    mix_ = mix;
    random_.seed(seed);
  }
  void PowerOn() {
    powered_ = true;
    cut_step_.reset();
  }
  bool powered() const { return powered_; }
  void set_torn_units_unreadable(bool unreadable) { torn_unreadable_ = unreadable; }

  std::uint64_t steps() const { return steps_; }
  int violations() const { return violations_; }
  int erase_count(std::size_t sector) const { return erases_[sector]; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

  // Test set-up and damage, outside the rules: the whole contents (units not all 0xFF then count as
  // programmed), or bits flipped in place.
  void SetContents(std::span<const std::uint8_t> contents) {
    std::fill(bytes_.begin(), bytes_.end(), std::uint8_t{0xFF});
    std::copy_n(contents.begin(), std::min(contents.size(), bytes_.size()), bytes_.begin());
    for (std::size_t unit = 0; unit < programmed_.size(); ++unit) {
      const auto begin = bytes_.begin() + static_cast<std::ptrdiff_t>(unit * unit_);
      programmed_[unit] = std::any_of(begin, begin + static_cast<std::ptrdiff_t>(unit_),
                                      [](std::uint8_t b) { return b != 0xFF; });
      torn_[unit] = false;
    }
  }
  void FlipBits(std::size_t offset, std::uint8_t mask) { bytes_[offset] ^= mask; }

 private:
  bool CutNow() const { return cut_step_ && *cut_step_ <= steps_; }

  base::Status PowerFails() {
    powered_ = false;
    cut_step_.reset();
    return base::Unavailable();
  }

  base::Status Violation(base::Status status) {
    ++violations_;
    return status;
  }

  std::uint8_t RandomByte() { return static_cast<std::uint8_t>(random_() & 0xFFU); }

  // The unit at `at` was being programmed with `data` and power failed at its byte `cut`.
  void TearProgram(std::size_t at, std::span<const std::uint8_t> data, std::size_t cut) {
    for (std::size_t i = 0; i < unit_; ++i) {
      std::uint8_t& byte = bytes_[at + i];
      switch (mix_) {
        case CutMix::kOld: break;
        case CutMix::kPartlyNew:
          if (i < cut) byte &= data[i];
          if (i == cut) byte &= static_cast<std::uint8_t>(data[i] | 0xF0);
          break;
        case CutMix::kRandom: byte &= static_cast<std::uint8_t>(data[i] | RandomByte()); break;
        case CutMix::kNew: byte &= data[i]; break;
      }
    }
  }

  void TearErase(std::size_t first) {
    const std::size_t point = static_cast<std::size_t>(random_() % sector_size_);
    for (std::size_t i = 0; i < sector_size_; ++i) {
      std::uint8_t& byte = bytes_[first + i];
      switch (mix_) {
        case CutMix::kOld: break;
        case CutMix::kPartlyNew:
          if (i < point) byte = 0xFF;
          if (i == point) byte |= 0x0F;
          break;
        case CutMix::kRandom: byte |= RandomByte(); break;
        case CutMix::kNew: byte = 0xFF; break;
      }
    }
  }

  std::size_t sector_size_;
  std::size_t sector_count_;
  std::size_t unit_;
  std::vector<std::uint8_t> bytes_;
  std::vector<bool> programmed_;  // per unit: written (or torn) since its sector's last erase
  std::vector<bool> torn_;        // per unit: a cut hit it (or its sector's erase)
  std::vector<int> erases_;
  std::uint64_t steps_ = 0;
  std::optional<std::uint64_t> cut_step_;
  CutMix mix_ = CutMix::kRandom;
  std::mt19937 random_{1};
  bool powered_ = true;
  bool torn_unreadable_ = false;
  int violations_ = 0;
};

}  // namespace hal::test
