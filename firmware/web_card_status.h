// WebCardStatus on the card's own objects (the composition root builds it): the configuration and the
// written-back values from the register proxy and the status publisher, the LEDs from their mirror, the
// CIP connections from the connection manager, and the statistics page from the ports, the netif, lwIP's
// counters and the web server's own.
#pragma once

#include "card_lldp.h"
#include "card_netif.h"
#include "card_ring.h"
#include "card_status_publisher.h"
#include "cip/io_connection.h"
#include "drive_link/register_proxy.h"
#include "led_mirror.h"
#include "web/http_server.h"
#include "web_application.h"
#include "web_service.h"

namespace firmware {

struct WebCardStatusSources {
  const drive_link::RegisterProxy& proxy;
  const CardStatusPublisher& publisher;
  CardNetif& netif;
  const LedMirror& leds;
  const cip::ConnectionTable& connections;
  const CardRing& ring;
};

class CardWebStatus final : public WebCardStatus {
 public:
  explicit CardWebStatus(const WebCardStatusSources& sources) : s_(sources) {}
  // The web server's own counters (built after the application that shows them).
  void SetWebCounters(const web::HttpServer& http, const WebService& service) {
    http_ = &http;
    web_service_ = &service;
  }
  // The LLDP neighbour table and counters ("lldp" of the statistics).
  void SetLldp(const net::LldpAgent& lldp) { lldp_ = &lldp; }

  const config::CardConfig& config() const override { return s_.proxy.config(); }
  config::CardStatus card_status() const override { return s_.publisher.board_data().status; }
  const char* drive_link_state() const override;
  const char* drive_model() const override;
  void WriteLeds(web::JsonWriter& json) const override;
  void WriteConnections(web::JsonWriter& json) const override;
  void WriteStatistics(web::JsonWriter& json) const override;
  void WriteRing(web::JsonWriter& json) const;

 private:
  WebCardStatusSources s_;
  const web::HttpServer* http_ = nullptr;
  const WebService* web_service_ = nullptr;
  const net::LldpAgent* lldp_ = nullptr;
};

}  // namespace firmware
