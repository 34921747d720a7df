#include "web_card_status.h"

#include <array>

#include "cip/message_router_object.h"
#include "hal/text_line.h"
#include "lwip/stats.h"
#include "lwip_internals.h"

namespace firmware {
namespace {

void Proto(web::JsonWriter& json, const char* name, const stats_proto& p) {
  json.Key(name).BeginObject();
  json.Key("xmit").Number(p.xmit).Key("recv").Number(p.recv).Key("drop").Number(p.drop);
  json.Key("chkerr").Number(p.chkerr).Key("lenerr").Number(p.lenerr).Key("memerr").Number(p.memerr);
  json.Key("proterr").Number(p.proterr).Key("err").Number(p.err);
  json.EndObject();
}

void Mem(web::JsonWriter& json, const char* name, const stats_mem& m) {
  json.Key(name).BeginObject();
  json.Key("avail").Number(m.avail).Key("used").Number(m.used).Key("max").Number(m.max).Key("err").Number(m.err);
  json.EndObject();
}

const char* ConnectionKind(const cip::ConnectionInfo& info) {
  if (info.transport_class == 3) return "class 3";
  switch (info.kind) {
    case cip::IoConnectionKind::kExclusiveOwner: return "exclusive owner";
    case cip::IoConnectionKind::kInputOnly: return "input only";
    case cip::IoConnectionKind::kListenOnly: return "listen only";
  }
  return "unknown";
}

// "lldp": {"neighbours": [{"port", "chassis", "port_id", "name", "port_description", "mgmt", "ttl"}],
// and the counters}. IDs and texts as `stats` shows them (card_lldp.h).
void Lldp(web::JsonWriter& json, const net::LldpAgent& agent) {
  json.Key("lldp").BeginObject().Key("neighbours").BeginArray();
  for (const net::LldpNeighbour& n : agent.neighbours()) {
    const char letter[1] = {hal::PortLetter(static_cast<hal::PortId>(n.port))};
    hal::TextLine text;
    json.BeginObject().Key("port").String(std::string_view(letter, 1));
    DescribeLldpId(n.info.chassis, true, text);
    json.Key("chassis").String(text.view());
    text.Clear();
    DescribeLldpId(n.info.port, false, text);
    json.Key("port_id").String(text.view());
    text.Clear();
    DescribeLldpText(n.info.system_name.view(), text);
    json.Key("name").String(text.view());
    text.Clear();
    DescribeLldpText(n.info.port_description.view(), text);
    json.Key("port_description").String(text.view());
    text.Clear();
    json.Key("mgmt");
    if (n.info.management.IsUnspecified()) {
      json.Null();
    } else {
      json.String(text.Ipv4(n.info.management).view());
    }
    json.Key("ttl").Number(n.info.ttl_seconds).EndObject();
  }
  const net::LldpCounters& c = agent.counters();
  json.EndArray().Key("frames_in").Number(c.frames_in).Key("frames_out").Number(c.frames_out);
  json.Key("malformed").Number(c.malformed).Key("table_full").Number(c.table_full);
  json.Key("aged_out").Number(c.aged_out).EndObject();
}

}  // namespace

const char* CardWebStatus::drive_link_state() const { return drive_link::LinkStateName(s_.proxy.link().state()); }

const char* CardWebStatus::drive_model() const {
  const std::string_view name = s_.publisher.board_data().drive_product_name.view();
  if (name == "VF-MB1") return "vf-mb1";
  if (name == "VF-S15") return "vf-s15";
  return "unknown";
}

void CardWebStatus::WriteLeds(web::JsonWriter& json) const {
  json.BeginObject();
  json.Key("ms").String(hal::LedColorName(s_.leds.Current(hal::Led::kModuleStatus)));
  json.Key("ns").String(hal::LedColorName(s_.leds.Current(hal::Led::kNetworkStatus)));
  json.Key("lnk_l").String(hal::LedColorName(s_.leds.Current(hal::Led::kLinkLeft)));
  json.Key("lnk_r").String(hal::LedColorName(s_.leds.Current(hal::Led::kLinkRight)));
  json.EndObject();
}

void CardWebStatus::WriteConnections(web::JsonWriter& json) const {
  std::array<cip::ConnectionInfo, cip::kMaxCipConnections> list{};
  const std::size_t count = s_.connections.ListConnections(list);
  json.BeginArray();
  for (std::size_t i = 0; i < count; ++i) {
    const cip::ConnectionInfo& c = list[i];
    std::array<char, 16> text{};
    std::size_t n = 0;
    for (std::size_t k = 0; k < base::Ipv4Address::kSize; ++k) {
      const unsigned octet = c.originator_address.octets()[k];
      if (octet >= 100) text[n++] = static_cast<char>('0' + octet / 100);
      if (octet >= 10) text[n++] = static_cast<char>('0' + octet / 10 % 10);
      text[n++] = static_cast<char>('0' + octet % 10);
      if (k + 1 < base::Ipv4Address::kSize) text[n++] = '.';
    }
    json.BeginObject().Key("originator").String(std::string_view(text.data(), n));
    json.Key("class").Number(c.transport_class).Key("kind").String(ConnectionKind(c));
    if (c.transport_class == 1) {
      json.Key("o_to_t").Number(c.points.consumed).Key("t_to_o").Number(c.points.produced);
      json.Key("configuration");
      if (c.points.configuration) {
        json.Number(*c.points.configuration);
      } else {
        json.Null();
      }
    }
    json.Key("o_to_t_api_us").Number(c.o_to_t_api).Key("t_to_o_api_us").Number(c.t_to_o_api);
    json.Key("timeout_ms").Number(c.timeout / hal::kMicrosPerMilli).Key("run").Bool(c.run);
    json.Key("multicast").Bool(c.multicast).Key("serial").Number(c.triad.connection_serial);
    json.EndObject();
  }
  json.EndArray();
}

void CardWebStatus::WriteStatistics(web::JsonWriter& json) const {
  json.BeginObject().Key("ports").BeginArray();
  hal::FramePort& port = s_.netif.port();
  for (std::size_t i = 0; i < port.PortCount() && i < 2; ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const hal::LinkState link = port.Link(id);
    const hal::PortCounters counters = port.Counters(id);
    const PortTraffic& traffic = s_.netif.traffic(id);
    const char letter[1] = {hal::PortLetter(id)};
    json.BeginObject().Key("port").String(std::string_view(letter, 1)).Key("link").Bool(link.up);
    json.Key("speed").Number(static_cast<int>(link.speed));
    json.Key("full_duplex").Bool(link.full_duplex);
    json.Key("counters").BeginObject();
    json.Key("in_octets").Number(static_cast<std::int64_t>(counters.rx_octets));
    json.Key("in_frames").Number(static_cast<std::int64_t>(counters.rx_frames));
    json.Key("in_errors").Number(static_cast<std::int64_t>(counters.rx_errors));
    json.Key("in_ucast").Number(static_cast<std::int64_t>(traffic.in_ucast));
    json.Key("in_nucast").Number(static_cast<std::int64_t>(traffic.in_nucast));
    json.Key("in_discards").Number(static_cast<std::int64_t>(traffic.in_discards));
    json.Key("out_octets").Number(static_cast<std::int64_t>(counters.tx_octets));
    json.Key("out_frames").Number(static_cast<std::int64_t>(counters.tx_frames));
    json.Key("out_errors").Number(static_cast<std::int64_t>(counters.tx_errors));
    json.Key("out_ucast").Number(static_cast<std::int64_t>(traffic.out_ucast));
    json.Key("out_nucast").Number(static_cast<std::int64_t>(traffic.out_nucast));
    json.Key("out_discards").Number(static_cast<std::int64_t>(traffic.out_discards));
    json.EndObject().EndObject();
  }
  json.EndArray();
  WriteRing(json);
  if (lldp_ != nullptr) Lldp(json, *lldp_);
  json.Key("lwip").BeginObject();
  Proto(json, "link", lwip_stats.link);
  Proto(json, "etharp", lwip_stats.etharp);
  Proto(json, "ip", lwip_stats.ip);
  Proto(json, "icmp", lwip_stats.icmp);
  Proto(json, "udp", lwip_stats.udp);
  Proto(json, "tcp", lwip_stats.tcp);
  Mem(json, "heap", lwip_stats.mem);
  for (std::size_t i = 0; i < kLwipPoolCount; ++i) {
    if (lwip_stats.memp[i] != nullptr) Mem(json, LwipPoolName(i), *lwip_stats.memp[i]);
  }
  json.EndObject();
  if (http_ == nullptr || web_service_ == nullptr) {
    json.EndObject();
    return;
  }
  const web::HttpServerCounters& http = http_->counters();
  const WebServiceCounters& tcp = web_service_->counters();
  json.Key("http").BeginObject();
  json.Key("accepted").Number(tcp.accepted).Key("evicted").Number(tcp.evicted).Key("refused_busy").Number(tcp.refused_busy);
  json.Key("requests").Number(http.requests).Key("parse_errors").Number(http.parse_errors);
  json.Key("request_timeouts").Number(http.request_timeouts).Key("responses_2xx").Number(http.responses_by_class[2]);
  json.Key("responses_4xx").Number(http.responses_by_class[4]).Key("responses_5xx").Number(http.responses_by_class[5]);
  json.EndObject().EndObject();
}

// The ring node as the DLR object shows it (docs/network.md "Ring (DLR)").
void CardWebStatus::WriteRing(web::JsonWriter& json) const {
  static constexpr std::string_view kTopology[] = {"linear", "ring"};
  static constexpr std::string_view kNetworkStatus[] = {"normal", "ring fault", "unexpected loop detected",
                                                        "partial network fault", "rapid fault/restore cycle"};
  static constexpr std::string_view kNodeState[] = {"idle", "fault", "normal"};
  const net::DlrRingStatus& s = s_.ring.status();
  json.Key("ring").BeginObject();
  json.Key("topology").String(kTopology[static_cast<std::size_t>(s.topology) & 1]);
  json.Key("network_status").String(kNetworkStatus[static_cast<std::size_t>(s.network_status) % 5]);
  json.Key("node_state").String(kNodeState[static_cast<std::size_t>(s.node_state) % 3]);
  hal::TextLine text;
  if (s.supervisor_known) text.Mac(s.supervisor.mac).Text(" ").Ipv4(s.supervisor.ip);
  json.Key("supervisor").String(s.supervisor_known ? text.view() : "none");
  json.Key("supervisor_precedence").Number(s.supervisor.precedence);
  json.Key("beacon_interval_us").Number(static_cast<std::int64_t>(s.supervisor.beacon_interval_us));
  json.Key("beacon_timeout_us").Number(static_cast<std::int64_t>(s.supervisor.beacon_timeout_us));
  json.Key("ring_faults").Number(static_cast<std::int64_t>(s.counters.ring_faults));
  json.Key("learning_flushes").Number(static_cast<std::int64_t>(s.counters.flushes));
  json.Key("neighbor_checks_answered").Number(static_cast<std::int64_t>(s.counters.neighbor_checks_answered));
  json.Key("link_status_sent").Number(static_cast<std::int64_t>(s.counters.link_status_sent));
  json.EndObject();
}

}  // namespace firmware
