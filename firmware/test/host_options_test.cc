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
  EXPECT_EQ(o.model, sim::Model::kVfMb1);
  EXPECT_TRUE(o.params.empty());
  EXPECT_FALSE(o.rs485_profile);
  EXPECT_EQ(o.sim_processing_ms, -1);
  // lwipopts.h's keepalive: 60 s idle, 10 s apart, 6 probes.
  EXPECT_EQ(o.tcp_keepalive.idle_ms, 60000u);
  EXPECT_EQ(o.tcp_keepalive.interval_ms, 10000u);
  EXPECT_EQ(o.tcp_keepalive.count, 6u);
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
  EXPECT_EQ(o.params[0].text, "c500=1");
  EXPECT_EQ(o.params[0].number, 0xC500);
  EXPECT_EQ(o.params[0].value, 1);
  EXPECT_EQ(o.params[1].text, "f856=0x2");
  EXPECT_EQ(o.params[1].number, 0x0856);
  EXPECT_EQ(o.params[1].value, 2);
  EXPECT_EQ(o.model, sim::Model::kVfS15);
}

TEST(HostOptions, ParamByTitleOrCommunicationNumber_InOrder) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--param", "ACC=50", "--param", "0010=0x28", "--param", "acc=60", "--param", "vb=-0"}, o,
                  error),
            ParseOutcome::kRun)
      << error;
  ASSERT_EQ(o.params.size(), 4u);
  EXPECT_EQ(o.params[0].number, 0x0009);
  EXPECT_EQ(o.params[0].value, 50);
  EXPECT_EQ(o.params[1].number, 0x0010);  // dec
  EXPECT_EQ(o.params[1].value, 40);
  EXPECT_EQ(o.params[2].number, 0x0009);  // repeated: applied in order, the last one wins
  EXPECT_EQ(o.params[2].value, 60);
  EXPECT_EQ(o.params[3].number, 0x0016);
  EXPECT_EQ(o.params[3].value, 0);
}

TEST(HostOptions, ParamCheckedAgainstTheModelGivenLater) {
  // fmod 12-14 exist on VF-S15 only (registers.csv); --model may come after --param.
  HostOptions s15;
  std::string error;
  EXPECT_EQ(Parse({"--param", "fmod=12", "--model", "vf-s15"}, s15, error), ParseOutcome::kRun) << error;
  HostOptions mb1;
  EXPECT_EQ(Parse({"--param", "fmod=12"}, mb1, error), ParseOutcome::kError);
  EXPECT_EQ(error, "invalid value for --param: 'fmod=12' (out of range 0..11)");
}

TEST(HostOptions, SimulatorServerFlags) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--rs485-profile", "--sim-processing-ms", "7"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_TRUE(o.rs485_profile);
  EXPECT_EQ(o.sim_processing_ms, 7);
}

TEST(HostOptions, TcpKeepalive_Parsed) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--tcp-keepalive", "1000,500,3"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_EQ(o.tcp_keepalive.idle_ms, 1000u);
  EXPECT_EQ(o.tcp_keepalive.interval_ms, 500u);
  EXPECT_EQ(o.tcp_keepalive.count, 3u);
  // The bounds themselves are accepted.
  ASSERT_EQ(Parse({"--tcp-keepalive", "100,7200000,20"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_EQ(o.tcp_keepalive.idle_ms, 100u);
  EXPECT_EQ(o.tcp_keepalive.interval_ms, 7200000u);
  EXPECT_EQ(o.tcp_keepalive.count, 20u);
  ASSERT_EQ(Parse({"--tcp-keepalive", "7200000,100,1"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_EQ(o.tcp_keepalive.idle_ms, 7200000u);
  EXPECT_EQ(o.tcp_keepalive.interval_ms, 100u);
  EXPECT_EQ(o.tcp_keepalive.count, 1u);
}

TEST(HostOptions, Eds_PathTaken) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({}, o, error), ParseOutcome::kRun) << error;
  EXPECT_EQ(o.eds_path, "");
  ASSERT_EQ(Parse({"--eds", "/tmp/x.eds"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_EQ(o.eds_path, "/tmp/x.eds");
}

TEST(HostOptions, TapWithoutIp_TheInvertersAddressingDecides) {
  HostOptions o;
  std::string error;
  ASSERT_EQ(Parse({"--net", "tap:x", "--param", "c504=2"}, o, error), ParseOutcome::kRun) << error;
  EXPECT_FALSE(o.ip_given);
  EXPECT_EQ(o.ip, 0u);
}

TEST(HostOptions, BadValues_ErrorNamesTheFlag) {
  const std::vector<std::pair<std::vector<const char*>, std::string>> cases = {
      {{"--net", "eth0"}, "invalid value for --net: 'eth0'"},
      {{"--net", "tap:a,tap:b,tap:c"}, "invalid value for --net: 'tap:a,tap:b,tap:c'"},
      {{"--ip", "10.0.0.1"}, "invalid value for --ip: '10.0.0.1'"},
      {{"--ip", "10.0.0.256/24"}, "invalid value for --ip: '10.0.0.256/24'"},
      {{"--ip", "10.0.0.1/31"}, "invalid value for --ip: '10.0.0.1/31'"},
      {{"--host-addr", "10.0.0.1"}, "invalid value for --host-addr: '10.0.0.1'"},
      {{"--model", "vf-a7"}, "invalid value for --model: 'vf-a7'"},
      {{"--param", "c500"}, "invalid value for --param: 'c500'"},
      {{"--param", "c5-0=1"}, "invalid value for --param: 'c5-0=1'"},
      {{"--param", "c500=1x"}, "invalid value for --param: 'c500=1x'"},
      {{"--param", "c500=1.5"}, "invalid value for --param: 'c500=1.5'"},
      {{"--param", "c500=--1"}, "invalid value for --param: 'c500=--1'"},
      {{"--param", "c500="}, "invalid value for --param: 'c500='"},
      {{"--param", "nosuch=1"}, "invalid value for --param: 'nosuch=1' (unknown register 'nosuch')"},
      {{"--param", "000A=1"},
       "invalid value for --param: '000A=1' (no communication number 000A (numbers ending in A-F do not "
       "exist))"},
      {{"--param", "0001=1"}, "invalid value for --param: '0001=1' (no communication number 0001)"},
      {{"--param", "acc=0"}, "invalid value for --param: 'acc=0' (out of range 1..60000)"},
      {{"--param", "fa06=1"},
       "invalid value for --param: 'fa06=1' (fa06 is not a parameter hosts keep in the EEPROM (ram))"},
      {{"--param", "fd00=1"},
       "invalid value for --param: 'fd00=1' (fd00 is not a parameter hosts keep in the EEPROM (monitor, "
       "not host-writable))"},
      {{"--sim-processing-ms", "2001"}, "invalid value for --sim-processing-ms: '2001'"},
      {{"--sim-processing-ms", "-1"}, "invalid value for --sim-processing-ms: '-1'"},
      {{"--tcp-keepalive", "1000,500"}, "invalid value for --tcp-keepalive: '1000,500'"},
      {{"--tcp-keepalive", "1000,500,3,4"}, "invalid value for --tcp-keepalive: '1000,500,3,4'"},
      {{"--tcp-keepalive", "99,500,3"}, "invalid value for --tcp-keepalive: '99,500,3'"},
      {{"--tcp-keepalive", "1000,99,3"}, "invalid value for --tcp-keepalive: '1000,99,3'"},
      {{"--tcp-keepalive", "7200001,500,3"}, "invalid value for --tcp-keepalive: '7200001,500,3'"},
      {{"--tcp-keepalive", "1000,7200001,3"}, "invalid value for --tcp-keepalive: '1000,7200001,3'"},
      {{"--tcp-keepalive", "1000,500,0"}, "invalid value for --tcp-keepalive: '1000,500,0'"},
      {{"--tcp-keepalive", "1000,500,21"}, "invalid value for --tcp-keepalive: '1000,500,21'"},
      {{"--tcp-keepalive", "1000,,3"}, "invalid value for --tcp-keepalive: '1000,,3'"},
      {{"--tcp-keepalive", "1000,500,"}, "invalid value for --tcp-keepalive: '1000,500,'"},
      {{"--tcp-keepalive", "-1000,500,3"}, "invalid value for --tcp-keepalive: '-1000,500,3'"},
      {{"--tcp-keepalive", "1000, 500,3"}, "invalid value for --tcp-keepalive: '1000, 500,3'"},
      {{"--tcp-keepalive", "99999999999,500,3"}, "invalid value for --tcp-keepalive: '99999999999,500,3'"},
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

TEST(HostOptions, Help_SaysPresetsApplyToANewInverterOnly) {
  const std::string usage = host::HostUsage();
  EXPECT_NE(usage.find("--param NAME|COMMNO=VALUE"), std::string::npos);
  EXPECT_NE(usage.find("applied only while DIR has no usable file for the model"), std::string::npos);
  EXPECT_NE(usage.find("--rs485-profile"), std::string::npos);
  EXPECT_NE(usage.find("--sim-processing-ms N"), std::string::npos);
  EXPECT_NE(usage.find("--tcp-keepalive IDLE_MS,INTERVAL_MS,COUNT"), std::string::npos);
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
