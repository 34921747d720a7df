#include "host_options.h"

#include <gtest/gtest.h>

#include <vector>

namespace {

using host::HostOptions;
using host::ParseOutcome;

ParseOutcome Parse(std::vector<const char*> args, HostOptions& options, std::string& error) {
  args.insert(args.begin(), "ipe002z-host");
  return host::ParseHostOptions(static_cast<int>(args.size()), args.data(), options, error);
}

TEST(HostOptions, NoArguments_LoopbackWithSlirpDefaults) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({}, o, error), ParseOutcome::kRun);
  EXPECT_EQ(o.net, host::NetKind::kLoopback);
  EXPECT_EQ(o.ip, 0x0A00020Fu);
  EXPECT_EQ(o.netmask, 0xFFFFFF00u);
  EXPECT_EQ(o.gateway, 0x0A000202u);
  EXPECT_EQ(o.host_address, "127.0.0.2");
  EXPECT_EQ(o.model, "vf-mb1");
}

TEST(HostOptions, TwoTapPortsAndAddress_Parsed) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--net", "tap:tapL,tap:tapR", "--ip", "192.168.1.12/24", "--gateway", "192.168.1.1",
                   "--param", "c500=1", "--param", "f856=0x2", "--model", "vf-s15"},
                  o, error),
            ParseOutcome::kRun)
      << error;
  EXPECT_EQ(o.net, host::NetKind::kTap);
  EXPECT_EQ(o.tap_interfaces, (std::vector<std::string>{"tapL", "tapR"}));
  EXPECT_EQ(o.ip, 0xC0A8010Cu);
  EXPECT_EQ(o.netmask, 0xFFFFFF00u);
  EXPECT_EQ(o.gateway, 0xC0A80101u);
  ASSERT_EQ(o.params.size(), 2u);
  EXPECT_EQ(o.params[0], (std::pair<std::string, std::string>{"c500", "1"}));
  EXPECT_EQ(o.params[1], (std::pair<std::string, std::string>{"f856", "0x2"}));
  EXPECT_EQ(o.model, "vf-s15");
}

TEST(HostOptions, BadValues_ErrorNamesTheFlag) {
  const std::vector<std::pair<std::vector<const char*>, std::string>> cases = {
      {{"--net", "eth0"}, "invalid value for --net: 'eth0'"},
      {{"--net", "tap:a,tap:b,tap:c"}, "invalid value for --net: 'tap:a,tap:b,tap:c'"},
      {{"--net", "tap:x"}, "--ip is required with --net tap"},
      {{"--ip", "10.0.0.1"}, "invalid value for --ip: '10.0.0.1'"},
      {{"--ip", "10.0.0.256/24"}, "invalid value for --ip: '10.0.0.256/24'"},
      {{"--ip", "10.0.0.1/31"}, "invalid value for --ip: '10.0.0.1/31'"},
      {{"--host-addr", "10.0.0.1"}, "invalid value for --host-addr: '10.0.0.1'"},
      {{"--model", "vf-a7"}, "invalid value for --model: 'vf-a7'"},
      {{"--param", "c500"}, "invalid value for --param: 'c500'"},
      {{"--param", "c5-0=1"}, "invalid value for --param: 'c5-0=1'"},
      {{"--param", "c500=1x"}, "invalid value for --param: 'c500=1x'"},
      {{"--frobnicate", "1"}, "unknown option --frobnicate"},
      {{"--pcap"}, "missing value for --pcap"},
      {{"stray"}, "unexpected argument stray"},
  };
  for (const auto& [args, expected] : cases) {
    HostOptions o;
    std::string error;
    EXPECT_EQ(Parse(args, o, error), ParseOutcome::kError) << expected;
    EXPECT_EQ(error, expected);
  }
}

TEST(HostOptions, Help_Recognised) {
  HostOptions o;
  std::string error;
  EXPECT_EQ(Parse({"--ip", "1.2.3.4/8", "--help"}, o, error), ParseOutcome::kHelp);
}

TEST(HostOptions, Ipv4_RoundTrip) {
  std::uint32_t v = 0;
  ASSERT_TRUE(host::ParseIpv4("255.0.10.1", v));
  EXPECT_EQ(v, 0xFF000A01u);
  EXPECT_EQ(host::FormatIpv4(v), "255.0.10.1");
  EXPECT_FALSE(host::ParseIpv4("1.2.3", v));
  EXPECT_FALSE(host::ParseIpv4("1.2.3.4.5", v));
  EXPECT_FALSE(host::ParseIpv4(" 1.2.3.4", v));
}

}  // namespace
