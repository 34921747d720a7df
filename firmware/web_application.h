// The card's web application (docs/web.md): the embedded page's assets and the JSON API under /api/,
// as a web::HttpHandler for the web server. Access goes through web::AccessControl (sessions, CSRF,
// back-off); the drive through WebDriveMonitor and WebRegisterJobs (the register proxy's on-demand
// accesses); everything else the pages show through WebCardStatus, which the composition root implements
// on the card's objects.
//
// Device-path code: no allocation; answers are written into the server's response buffer.
#pragma once

#include <cstdint>
#include <string_view>

#include "cip/file_object.h"
#include "config/card_config.h"
#include "drive_link/register_access.h"
#include "event_loop.h"
#include "web/access_control.h"
#include "web/http_server.h"
#include "web/json.h"
#include "web_drive_access.h"

namespace firmware {

// What the pages show besides register values. Each Write* writes one JSON value (object or array).
class WebCardStatus {
 public:
  virtual ~WebCardStatus() = default;
  virtual const config::CardConfig& config() const = 0;       // the configuration in force
  virtual config::CardStatus card_status() const = 0;         // c502/c503, MAC, c524-c535, c536
  virtual const char* drive_link_state() const = 0;               // drive_link::LinkStateName
  virtual const char* drive_model() const = 0;                    // "vf-mb1", "vf-s15" or "unknown"
  virtual void WriteLeds(web::JsonWriter& json) const = 0;        // {"ms":..,"ns":..,"lnk_l":..,"lnk_r":..}
  virtual void WriteConnections(web::JsonWriter& json) const = 0; // the CIP connections array
  virtual void WriteStatistics(web::JsonWriter& json) const = 0;  // {"ports":[...],"lwip":{...},...}
};

struct WebApplicationDevices {
  web::AccessControl& access;
  drive_link::DriveRegisters& registers;
  const drive_link::ScannerImage& scanner;
  const drive_link::LossSupervision& loss;
  const WebCardStatus& status;
  cip::ServedFile eds = {};  // GET /api/eds (docs/file-object.md); no content: 404
};

class WebApplication final : public web::HttpHandler, public Service {
 public:
  explicit WebApplication(const WebApplicationDevices& devices)
      : devices_(devices), monitor_(devices.registers), jobs_(devices.registers), eds_body_(devices.eds.content) {}
  WebApplication(const WebApplication&) = delete;
  WebApplication& operator=(const WebApplication&) = delete;

  // web::HttpHandler
  web::HandlerResult Handle(web::HttpClientId client, const web::HttpRequest& request,
                            web::HttpResponseWriter& response, hal::Micros now) override;
  void OnClientClosed(web::HttpClientId client) override { jobs_.Finish(client); }
  hal::Micros NextDeadline() const override;

  // Service: the monitor's reads and the jobs' retries.
  void Poll(hal::Micros now) override;

 private:
  struct Call {
    web::HttpClientId client;
    const web::HttpRequest& request;
    web::HttpResponseWriter& response;
    hal::Micros now;
    std::string_view session;  // the cookie's value, empty when none
  };

  web::HandlerResult HandleAsset(const Call& call);
  web::HandlerResult HandleApi(const Call& call, std::string_view route);
  web::HandlerResult Login(const Call& call);
  web::HandlerResult Elevate(const Call& call);
  web::HandlerResult ChangePassword(const Call& call);
  web::HandlerResult ReadRegisters(const Call& call);
  web::HandlerResult WriteRegister(const Call& call);
  web::HandlerResult CommunicationReset(const Call& call);
  void Monitor(const Call& call);
  void Network(const Call& call);
  void ModbusScanner(const Call& call);
  void EipScanner(const Call& call);
  web::HandlerResult Eds(const Call& call);

  // The EDS as the web server streams it.
  class FileBody final : public web::HttpBodySource {
   public:
    explicit FileBody(const cip::FileContent* content) : content_(content) {}
    std::uint32_t Size() const override { return content_->Size(); }
    std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override {
      return content_->ReadAt(offset, out);
    }

   private:
    const cip::FileContent* content_;
  };

  const WebApplicationDevices devices_;
  WebDriveMonitor monitor_;
  WebRegisterJobs jobs_;
  FileBody eds_body_;
};

}  // namespace firmware
