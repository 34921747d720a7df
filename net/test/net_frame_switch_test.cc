// The card's two-port switch (net/frame_switch.h, docs/network.md "The two-port switch"): what reaches
// the card and which port a frame leaves by, for each kind of destination, with learning, filtering,
// replacement in a full table and flushing on link-down.
#include "net/frame_switch.h"

#include <gtest/gtest.h>

#include <vector>

namespace net {
namespace {

constexpr base::MacAddress kCard = {0x02, 0x00, 0x00, 0x00, 0x00, 0x01};
constexpr base::MacAddress kPlc = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x10};    // on port L (0)
constexpr base::MacAddress kDrive2 = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x20};  // on port R (1)
constexpr base::MacAddress kIgmpGroup = {0x01, 0x00, 0x5E, 0x40, 0x01, 0x02};
constexpr base::MacAddress kLldp = {0x01, 0x80, 0xC2, 0x00, 0x00, 0x0E};

constexpr std::size_t kL = 0;
constexpr std::size_t kR = 1;

std::vector<std::uint8_t> Frame(const base::MacAddress& destination, const base::MacAddress& source) {
  std::vector<std::uint8_t> frame(60, 0);
  std::copy(destination.begin(), destination.end(), frame.begin());
  std::copy(source.begin(), source.end(), frame.begin() + 6);
  frame[12] = 0x08;  // IPv4
  return frame;
}

SwitchDelivery Delivery(bool card, bool left, bool right) { return {card, {left, right}}; }

TEST(FrameSwitchTest, ForTheCardOnlyTheCard) {
  FrameSwitch sw(kCard, 2);
  EXPECT_EQ(sw.Ingress(Frame(kCard, kPlc), kL), Delivery(true, false, false));
  EXPECT_EQ(sw.Ingress(Frame(kCard, kDrive2), kR), Delivery(true, false, false));
}

TEST(FrameSwitchTest, BroadcastAndMulticastReachTheCardAndTheOtherPort) {
  FrameSwitch sw(kCard, 2);
  EXPECT_EQ(sw.Ingress(Frame(base::kBroadcastMac, kPlc), kL), Delivery(true, false, true));
  EXPECT_EQ(sw.Ingress(Frame(kIgmpGroup, kDrive2), kR), Delivery(true, true, false));
}

TEST(FrameSwitchTest, BridgeReservedGroupsAreNotForwarded) {
  FrameSwitch sw(kCard, 2);
  EXPECT_EQ(sw.Ingress(Frame(kLldp, kPlc), kL), Delivery(true, false, false));
}

TEST(FrameSwitchTest, UnknownUnicastPassesToTheOtherPortNotTheCard) {
  FrameSwitch sw(kCard, 2);
  EXPECT_EQ(sw.Ingress(Frame(kDrive2, kPlc), kL), Delivery(false, false, true));
  EXPECT_EQ(sw.PortOf(kPlc), kL);
}

TEST(FrameSwitchTest, AStationLearnedOnTheIngressSideIsFiltered) {
  FrameSwitch sw(kCard, 2);
  constexpr base::MacAddress kPlc2 = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x11};
  sw.Ingress(Frame(base::kBroadcastMac, kPlc2), kL);
  EXPECT_EQ(sw.Ingress(Frame(kPlc2, kPlc), kL), Delivery(false, false, false));
  // Learned on the other side: forwarded there.
  sw.Ingress(Frame(base::kBroadcastMac, kDrive2), kR);
  EXPECT_EQ(sw.Ingress(Frame(kDrive2, kPlc), kL), Delivery(false, false, true));
}

TEST(FrameSwitchTest, EgressGoesWhereTheDestinationWasLearnedElseEverywhere) {
  FrameSwitch sw(kCard, 2);
  using Ports = std::array<bool, kSwitchPorts>;
  EXPECT_EQ(sw.Egress(Frame(kPlc, kCard)), (Ports{true, true}));
  sw.Ingress(Frame(kCard, kPlc), kL);
  sw.Ingress(Frame(kCard, kDrive2), kR);
  EXPECT_EQ(sw.Egress(Frame(kPlc, kCard)), (Ports{true, false}));
  EXPECT_EQ(sw.Egress(Frame(kDrive2, kCard)), (Ports{false, true}));
  EXPECT_EQ(sw.Egress(Frame(base::kBroadcastMac, kCard)), (Ports{true, true}));
  // The PLC moves to port R: its next frame re-learns it.
  sw.Ingress(Frame(kCard, kPlc), kR);
  EXPECT_EQ(sw.Egress(Frame(kPlc, kCard)), (Ports{false, true}));
}

TEST(FrameSwitchTest, OwnAndGroupSourcesAreNeverLearned) {
  FrameSwitch sw(kCard, 2);
  sw.Ingress(Frame(base::kBroadcastMac, kCard), kL);       // our broadcast reflected
  sw.Ingress(Frame(base::kBroadcastMac, kIgmpGroup), kL);  // an invalid group source
  EXPECT_EQ(sw.learned(), 0U);
  EXPECT_EQ(sw.PortOf(kCard), kSwitchPorts);
}

TEST(FrameSwitchTest, LinkDownForgetsThatPortsStations) {
  FrameSwitch sw(kCard, 2);
  sw.Ingress(Frame(kCard, kPlc), kL);
  sw.Ingress(Frame(kCard, kDrive2), kR);
  sw.PortDown(kL);
  EXPECT_EQ(sw.PortOf(kPlc), kSwitchPorts);
  EXPECT_EQ(sw.PortOf(kDrive2), kR);
  EXPECT_EQ(sw.learned(), 1U);
}

TEST(FrameSwitchTest, FlushForgetsEveryStationAndRelearnsFromTheNextFrame) {
  FrameSwitch sw(kCard, 2);
  sw.Ingress(Frame(kCard, kPlc), kL);
  sw.Ingress(Frame(kCard, kDrive2), kR);
  sw.Flush();
  EXPECT_EQ(sw.learned(), 0U);
  EXPECT_EQ(sw.PortOf(kPlc), kSwitchPorts);
  // After a ring fault the PLC is behind the other port: the card's frames to it go out of both ports
  // until its next frame tells where it is.
  EXPECT_EQ(sw.Egress(Frame(kPlc, kCard)), (std::array<bool, kSwitchPorts>{true, true}));
  sw.Ingress(Frame(kCard, kPlc), kR);
  EXPECT_EQ(sw.PortOf(kPlc), kR);
}

TEST(FrameSwitchTest, AFullTableReplacesItsOldestEntry) {
  FrameSwitch sw(kCard, 2);
  for (std::size_t i = 0; i < FrameSwitch::kCapacity + 1; ++i) {
    const base::MacAddress station = {0x00, 0x00, 0x5E, 0x01, static_cast<std::uint8_t>(i >> 8),
                                static_cast<std::uint8_t>(i)};
    sw.Ingress(Frame(kCard, station), i % 2);
  }
  EXPECT_EQ(sw.learned(), FrameSwitch::kCapacity);
  EXPECT_EQ(sw.PortOf({0x00, 0x00, 0x5E, 0x01, 0x00, 0x00}), kSwitchPorts);  // the first, replaced
  EXPECT_EQ(sw.PortOf({0x00, 0x00, 0x5E, 0x01, 0x00, 0x01}), kR);
  EXPECT_EQ(sw.PortOf({0x00, 0x00, 0x5E, 0x01, 0x00, 0x40}), kL);  // the newest (64)
}

TEST(FrameSwitchTest, OnePortCardNeverForwardsAndRuntsGoNowhere) {
  FrameSwitch sw(kCard, 1);
  EXPECT_EQ(sw.Ingress(Frame(base::kBroadcastMac, kPlc), kL), Delivery(true, false, false));
  EXPECT_EQ(sw.Ingress(Frame(kDrive2, kPlc), kL), Delivery(false, false, false));
  const std::vector<std::uint8_t> runt(13, 0xFF);
  EXPECT_EQ(sw.Ingress(runt, kL), Delivery(false, false, false));
  EXPECT_EQ(sw.Ingress(Frame(kCard, kPlc), 5), Delivery(false, false, false));
}

}  // namespace
}  // namespace net
