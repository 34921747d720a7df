// TcpConnection's waits under signals: tools/ipe's Ctrl-C handler (card.cc) interrupts whatever system
// call is waiting, and a wait that ended there made `watch` exit 3 ("unreachable") instead of finishing
// the request and stopping with 0.
#include "socket_io.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "failure.h"

namespace ipe {
namespace {

std::atomic<int> alarms{0};
void OnAlarm(int) { alarms.fetch_add(1); }

// A listening socket on 127.0.0.1, a SIGALRM handler installed as tools/ipe installs its SIGINT one
// (no SA_RESTART), and a timer that fires every `period_ms`.
class InterruptedWait : public ::testing::Test {
 protected:
  void SetUp() override {
    listener_ = socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(listener_, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(listen(listener_, 1), 0);
    socklen_t length = sizeof address;
    ASSERT_EQ(getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length), 0);
    port_ = ntohs(address.sin_port);
    struct sigaction action {};
    action.sa_handler = OnAlarm;
    sigemptyset(&action.sa_mask);
    ASSERT_EQ(sigaction(SIGALRM, &action, &previous_), 0);
    alarms = 0;
  }
  void TearDown() override {
    StartTimer(0);
    sigaction(SIGALRM, &previous_, nullptr);
    if (peer_ >= 0) close(peer_);
    close(listener_);
  }
  static void StartTimer(int period_ms) {
    itimerval timer{};
    timer.it_value.tv_usec = period_ms * 1000;
    timer.it_interval.tv_usec = period_ms * 1000;
    setitimer(ITIMER_REAL, &timer, nullptr);
  }
  void Accept() { peer_ = accept(listener_, nullptr, nullptr); }

  int listener_ = -1;
  int peer_ = -1;
  std::uint16_t port_ = 0;
  struct sigaction previous_ {};
};

TEST_F(InterruptedWait, ASignalWhileAReplyIsAwaitedDoesNotEndTheWait) {
  TcpConnection connection("127.0.0.1", port_, 2000);
  Accept();
  ASSERT_GE(peer_, 0);
  // The reply comes 200 ms later, from a thread that does not take the signal; the timer interrupts the
  // main thread's wait every 20 ms meanwhile.
  sigset_t alarm_only;
  sigemptyset(&alarm_only);
  sigaddset(&alarm_only, SIGALRM);
  pthread_sigmask(SIG_BLOCK, &alarm_only, nullptr);
  std::thread replier([this] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const std::uint8_t reply[] = {0xDE, 0xAD, 0xBE, 0xEF};
    (void)send(peer_, reply, sizeof reply, 0);
  });
  pthread_sigmask(SIG_UNBLOCK, &alarm_only, nullptr);
  StartTimer(20);
  std::vector<std::uint8_t> got;
  try {
    got = connection.Receive(4);
  } catch (const Failure& failure) {
    ADD_FAILURE() << "exit " << failure.code << ": " << failure.message;
  }
  StartTimer(0);
  replier.join();
  EXPECT_EQ(got, (std::vector<std::uint8_t>{0xDE, 0xAD, 0xBE, 0xEF}));
  EXPECT_GE(alarms.load(), 2);  // the wait was interrupted, more than once
}

TEST_F(InterruptedWait, SignalsDoNotStretchTheTimeout) {
  TcpConnection connection("127.0.0.1", port_, 300);
  Accept();
  StartTimer(20);
  const auto begin = std::chrono::steady_clock::now();
  int code = -1;
  std::string message;
  try {
    connection.Receive(1);
  } catch (const Failure& failure) {
    code = failure.code;
    message = failure.message;
  }
  const auto waited = std::chrono::steady_clock::now() - begin;
  StartTimer(0);
  EXPECT_EQ(code, kExitUnreachable);
  EXPECT_EQ(message, "127.0.0.1:" + std::to_string(port_) + ": no reply within 300 ms");
  EXPECT_GE(waited, std::chrono::milliseconds(290));  // not ended early by the first signal
  EXPECT_GE(alarms.load(), 5);
}

}  // namespace
}  // namespace ipe
