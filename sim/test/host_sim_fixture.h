// Shared fixture of the host card's simulated-inverter tests (host_sim_inverter_test.cc,
// host_sim_control_test.cc): a temporary state dir, a fake clock, a serial socket pair and a
// SimulatedInverter on its inverter end, with warnings captured in memory.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "fake_clock.h"
#include "sim_inverter.h"
#include "socket_serial_port.h"

namespace host::test {

// The host card runs the simulator of sim/host/ (namespace sim).
using sim::EepromFileContents;
using sim::EepromImageOf;
using sim::ParamPreset;
using sim::SimInverterConfig;
using sim::SimulatedInverter;

inline constexpr hal::Micros kSecond = hal::kMicrosPerSecond;

class SimInverterFixture : public ::testing::Test {
 protected:
  SimInverterFixture() {
    char pattern[] = "/tmp/ipe-sim-test.XXXXXX";
    dir_ = mkdtemp(pattern);
    auto pair = hal::host::SocketSerialPort::CreatePair();
    EXPECT_TRUE(pair.ok());
    card_ = std::move(pair.value().card);
    line_ = std::move(pair.value().inverter);
    log_ = open_memstream(&log_buffer_, &log_size_);
    config_.directory = dir_ + "/inverter";
    config_.program = "ipe002z-host";
  }
  ~SimInverterFixture() override {
    inverter_.reset();
    std::fclose(log_);
    free(log_buffer_);
    std::filesystem::remove_all(dir_);
  }

  // Creates the inverter from config_ and lets it pass its power-on second.
  bool Start() {
    std::string error;
    inverter_ = SimulatedInverter::Create(config_, *line_, clock_, log_, error);
    error_ = error;
    if (!inverter_) return false;
    inverter_->AdvanceToNow();
    clock_.Advance(2 * kSecond);
    inverter_->AdvanceToNow();
    return true;
  }

  std::string Log() {
    std::fflush(log_);
    return std::string(log_buffer_, log_size_);
  }
  std::string FilePath() const {
    return config_.directory + "/" + sim::ModelName(config_.model) + ".eeprom";
  }
  std::string ReadText(const std::string& path) const {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  void WriteText(const std::string& path, const std::string& text) const {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path) << text;
  }
  std::uint16_t Read(std::uint16_t number) { return *inverter_->model().Read(number); }

  std::string dir_;
  hal::test::FakeClock clock_{1000 * kSecond};
  std::unique_ptr<hal::host::SocketSerialPort> card_;
  std::unique_ptr<hal::host::SocketSerialPort> line_;
  std::FILE* log_ = nullptr;
  char* log_buffer_ = nullptr;
  std::size_t log_size_ = 0;
  SimInverterConfig config_;
  std::unique_ptr<SimulatedInverter> inverter_;
  std::string error_;
};

}  // namespace host::test
