// The simulation control socket (--sim-control PATH): a UNIX stream socket with a line protocol.
//
// Protocol: the client sends one command per line. The answer is zero or more data lines followed by
// exactly one status line: "ok" or "error <reason>". Several commands may be pipelined; answers come
// in order. Lines longer than kMaxLineBytes get "error line too long" and the connection is closed.
// At most kMaxClients at once; a further client gets "error too many clients" and is closed.
//
// The server only frames lines; what a command does is decided by the handler the composition root
// installs (the host card's, the stand-alone simulated inverter's), so they add commands without
// touching this file. A command is words separated by spaces: SplitCommand cuts one.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "poll_waiter.h"

namespace hal::host {

// Words a command has at most: the longest is "inject delay until-cleared 150".
inline constexpr std::size_t kMaxCommandWords = 4;

// Splits `command` at spaces (any number of them) into `words`. Returns how many there are, or
// words.size() + 1 when there are more than fit.
std::size_t SplitCommand(std::string_view command, std::span<std::string_view> words);

class ControlServer final : public PollSource {
 public:
  static constexpr std::size_t kMaxClients = 4;
  static constexpr std::size_t kMaxLineBytes = 512;
  static constexpr std::size_t kMaxPendingReplyBytes = 256 * 1024;

  // Appends the answer lines (each ending in '\n', the last one "ok"/"error ...") to `reply`.
  using Handler = std::function<void(std::string_view command, std::string& reply)>;

  ControlServer(std::string path, Handler handler);
  ~ControlServer() override;
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  // Binds and listens (removes a stale socket file first). False with `error` set on failure.
  bool Start(std::string& error);

  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

 private:
  struct Client {
    int fd = -1;
    std::string in;
    std::string out;
    std::size_t slot = 0;
  };

  void Accept();
  void ServeInput(Client& client);
  void Flush(Client& client);
  void Close(Client& client);

  std::string path_;
  Handler handler_;
  int listen_fd_ = -1;
  std::size_t listen_slot_ = 0;
  std::vector<Client> clients_;
};

}  // namespace hal::host
