// tools/ipe: the command line (commands, options anywhere, their values, the errors word for word).
#include <gtest/gtest.h>

#include "cli.h"

namespace ipe {
namespace {

ParsedCommandLine Parse(std::vector<std::string> arguments) { return ParseCommandLine(arguments); }

TEST(IpeCli, OptionsBeforeAndAfterTheCommand) {
  const ParsedCommandLine p = Parse({"--timeout", "500ms", "get", "127.0.0.2", "acc", "--modbus", "--port=5020", "dec"});
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.options.command, "get");
  EXPECT_EQ(p.options.args, (std::vector<std::string>{"127.0.0.2", "acc", "dec"}));
  EXPECT_TRUE(p.options.modbus);
  EXPECT_EQ(p.options.port, 5020);
  EXPECT_EQ(p.options.timeout_ms, 500u);
  EXPECT_EQ(p.options.unit, 1);
  EXPECT_EQ(DefaultPort(p.options), 5020);
}

TEST(IpeCli, DefaultPortsAndIoOptions) {
  ParsedCommandLine p = Parse({"get", "h", "acc"});
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(DefaultPort(p.options), 44818);
  p = Parse({"get", "h", "acc", "--modbus"});
  EXPECT_EQ(DefaultPort(p.options), 502);
  p = Parse({"io", "h", "--connection", "21/71", "--rpi", "20ms", "--run", "--speed", "30Hz", "--duration", "5"});
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.options.rpi_ms, 20u);
  EXPECT_TRUE(p.options.run);
  EXPECT_EQ(p.options.speed, "30Hz");
  EXPECT_EQ(p.options.duration_ms, 5000u);
  p = Parse({"watch", "h", "fd00", "--count", "3", "--interval", "100"});
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.options.count, 3u);
  EXPECT_EQ(p.options.interval_ms, 100u);
}

TEST(IpeCli, ErrorsWordForWord) {
  EXPECT_EQ(Parse({}).error, "no command given (try: ipe --help)");
  EXPECT_EQ(Parse({"frobnicate"}).error, "unknown command 'frobnicate' (try: ipe --help)");
  EXPECT_EQ(Parse({"get", "h", "acc", "--port"}).error, "option --port needs a value");
  EXPECT_EQ(Parse({"get", "h", "acc", "--port", "70000"}).error, "--port wants 1-65535, not '70000'");
  EXPECT_EQ(Parse({"identity", "h", "--modbus"}).error, "option --modbus does not apply to 'identity'");
  EXPECT_EQ(Parse({"get", "h", "acc", "--unit", "251"}).error, "--unit wants 0-248 (the drive's unit ids), not '251'");
  EXPECT_EQ(Parse({"io", "h", "--connection", "100/150"}).error, "--connection: only 21/71 is supported by ipe io");
  EXPECT_EQ(Parse({"io", "h", "--connection", "21"}).error,
            "--connection wants OUTPUT/INPUT assembly instances (21/71), not '21'");
  EXPECT_EQ(Parse({"discover", "--interface", "eth0", "--broadcast", "10.0.0.255"}).error,
            "discover takes --interface or --broadcast, not both");
  EXPECT_EQ(Parse({"get", "h"}).error.substr(0, 35), "wrong number of arguments for 'get'");
  EXPECT_EQ(Parse({"identity"}).error.substr(0, 40), "wrong number of arguments for 'identity'");
}

TEST(IpeCli, HelpForTheToolAndEachCommand) {
  ParsedCommandLine p = Parse({"--help"});
  ASSERT_TRUE(p.ok);
  EXPECT_TRUE(p.options.help);
  EXPECT_TRUE(p.options.command.empty());
  p = Parse({"restore", "--help"});
  ASSERT_TRUE(p.ok);  // the arguments a command needs are not needed for its help
  EXPECT_EQ(p.options.command, "restore");
  EXPECT_EQ(CommandHelp("restore").substr(0, 20), "usage: ipe restore H");
  EXPECT_EQ(CommandHelp("nosuch"), "");
  for (const char* command : {"discover", "identity", "get", "set", "backup", "restore", "watch", "io", "eds"}) {
    EXPECT_NE(UsageText().find(std::string("  ipe ") + command + " "), std::string::npos) << command;
    EXPECT_EQ(CommandHelp(command).rfind(std::string("usage: ipe ") + command, 0), 0u) << command;
  }
  EXPECT_NE(UsageText().find("exit codes: 0 ok, 1 refused by the card, 2 bad arguments"), std::string::npos);
}

}  // namespace
}  // namespace ipe
