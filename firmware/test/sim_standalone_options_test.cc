// Command line of ipe002z-inverter (sim/host/standalone_options.h): its own flags, the inverter flags it
// shares with ipe002z-host (same parser, same messages), and every refusal (exit 2 in main).
#include "standalone_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host_options.h"

namespace {

using sim::StandaloneOptions;
using sim::StandaloneParse;

StandaloneParse Parse(std::vector<const char*> args, StandaloneOptions& options, std::string& error) {
  args.insert(args.begin(), "ipe002z-inverter");
  return sim::ParseStandaloneOptions(static_cast<int>(args.size()), args.data(), options, error);
}

TEST(StandaloneOptions, SerialOnly_Defaults) {
  StandaloneOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--serial", "unix:/tmp/inverter.sock"}, o, error), StandaloneParse::kRun) << error;
  EXPECT_EQ(o.serial, "unix:/tmp/inverter.sock");
  EXPECT_EQ(o.state_dir, "");
  EXPECT_EQ(o.sim_control_path, "");
  EXPECT_FALSE(o.ip_given);
  EXPECT_EQ(o.model, sim::Model::kVfMb1);
  EXPECT_TRUE(o.params.empty());
  EXPECT_FALSE(o.rs485_profile);
  EXPECT_EQ(o.sim_processing_ms, -1);
}

TEST(StandaloneOptions, EveryFlag) {
  StandaloneOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--serial", "tcp:127.0.0.1:5555", "--state-dir", "/tmp/s", "--sim-control", "/tmp/c.sock",
                   "--ip", "192.168.1.20/24,192.168.1.1", "--param", "acc=50", "--param", "0010=0x28",
                   "--rs485-profile", "--sim-processing-ms", "7", "--model", "vf-s15"},
                  o, error),
            StandaloneParse::kRun)
      << error;
  EXPECT_EQ(o.serial, "tcp:127.0.0.1:5555");
  EXPECT_EQ(o.state_dir, "/tmp/s");
  EXPECT_EQ(o.sim_control_path, "/tmp/c.sock");
  EXPECT_TRUE(o.ip_given);
  EXPECT_EQ(o.address.ip, 0xC0A80114u);
  EXPECT_EQ(o.address.netmask, 0xFFFFFF00u);
  EXPECT_EQ(o.address.gateway, 0xC0A80101u);
  ASSERT_EQ(o.params.size(), 2u);
  EXPECT_EQ(o.params[0].text, "acc=50");
  EXPECT_EQ(o.params[0].number, 0x0009);
  EXPECT_EQ(o.params[0].value, 50);
  EXPECT_EQ(o.params[1].number, 0x0010);
  EXPECT_EQ(o.params[1].value, 40);
  EXPECT_TRUE(o.rs485_profile);
  EXPECT_EQ(o.sim_processing_ms, 7);
  EXPECT_EQ(o.model, sim::Model::kVfS15);
  EXPECT_EQ(sim::ServerConfigFromOptions(o).processing_delay, 7 * hal::kMicrosPerMilli);
}

TEST(StandaloneOptions, Help) {
  StandaloneOptions o;
  std::string error;
  EXPECT_EQ(Parse({"--help"}, o, error), StandaloneParse::kHelp);
  EXPECT_EQ(Parse({"--serial", "unix:/x", "-h"}, o, error), StandaloneParse::kHelp);
  const std::string usage = sim::StandaloneUsage();
  EXPECT_EQ(usage.rfind("usage: ipe002z-inverter --serial unix:PATH|tcp:HOST:PORT [options]\n", 0), 0u);
  for (const char* flag : {"\n  --serial unix:PATH|tcp:HOST:PORT ", "\n  --state-dir DIR ", "\n  --sim-control PATH ",
                           "\n  --ip A.B.C.D/N[,GW] ", "\n  --model vf-mb1|vf-s15 ", "\n  --param NAME|COMMNO=VALUE ",
                           "\n  --rs485-profile ", "\n  --sim-processing-ms N ", "\n  --help "}) {
    EXPECT_NE(usage.find(flag), std::string::npos) << flag;
  }
  // The inverter's flags read exactly as in ipe002z-host's help: one text for both.
  EXPECT_NE(std::string(host::HostUsage()).find(sim::kInverterOptionsUsage), std::string::npos);
  EXPECT_NE(usage.find(sim::kInverterOptionsUsage), std::string::npos);
}

TEST(StandaloneOptions, Refusals) {
  const std::vector<std::pair<std::vector<const char*>, std::string>> cases = {
      {{}, "missing --serial (unix:PATH or tcp:HOST:PORT)"},
      {{"--state-dir", "/tmp/s"}, "missing --serial (unix:PATH or tcp:HOST:PORT)"},
      {{"--serial"}, "missing value for --serial"},
      {{"--serial", "/tmp/x.sock"},
       "invalid value for --serial: '/tmp/x.sock' (expected unix:PATH or tcp:HOST:PORT, HOST a numeric address or "
       "localhost)"},
      {{"--serial", "tcp:127.0.0.1:99999"},
       "invalid value for --serial: 'tcp:127.0.0.1:99999' (expected unix:PATH or tcp:HOST:PORT, HOST a numeric "
       "address or localhost)"},
      {{"--serial", "unix:/x", "--net", "loopback"}, "unknown option --net"},
      {{"--serial", "unix:/x", "stray", "1"}, "unknown option stray"},
      {{"--serial", "unix:/x", "stray"}, "unexpected argument stray"},
      {{"--serial", "unix:/x", "--ip", "10.0.2.15"}, "invalid value for --ip: '10.0.2.15'"},
      {{"--serial", "unix:/x", "--ip", "10.0.2.15/24,gw"}, "invalid value for --ip: '10.0.2.15/24,gw'"},
      {{"--serial", "unix:/x", "--state-dir", ""}, "invalid value for --state-dir: ''"},
      {{"--serial", "unix:/x", "--model", "vf-a7"}, "invalid value for --model: 'vf-a7'"},
      {{"--serial", "unix:/x", "--param", "c500"}, "invalid value for --param: 'c500'"},
      {{"--serial", "unix:/x", "--param", "acc=0"}, "invalid value for --param: 'acc=0' (out of range 1..60000)"},
      {{"--serial", "unix:/x", "--param", "fa06=1"},
       "invalid value for --param: 'fa06=1' (fa06 is not a parameter hosts keep in the EEPROM (ram))"},
      {{"--serial", "unix:/x", "--param", "fmod=12"}, "invalid value for --param: 'fmod=12' (out of range 0..11)"},
      {{"--serial", "unix:/x", "--sim-processing-ms", "2001"}, "invalid value for --sim-processing-ms: '2001'"},
  };
  for (const auto& [args, expected] : cases) {
    StandaloneOptions o;
    std::string error;
    EXPECT_EQ(Parse(args, o, error), StandaloneParse::kError) << expected;
    EXPECT_EQ(error, expected);
  }
  // fmod 12 exists on VF-S15 only; --model may come after --param, as for ipe002z-host.
  StandaloneOptions s15;
  std::string error;
  EXPECT_EQ(Parse({"--serial", "unix:/x", "--param", "fmod=12", "--model", "vf-s15"}, s15, error),
            StandaloneParse::kRun)
      << error;
}

}  // namespace
