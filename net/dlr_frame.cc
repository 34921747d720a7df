// Stub: the codec is implemented in the next commit.
#include "net/dlr_frame.h"

namespace net {

std::uint8_t DlrLinkStatus::Encode() const { return 0; }
DlrLinkStatus DlrLinkStatus::Decode(std::uint8_t) { return {}; }
base::Result<DlrFrame> ParseDlrFrame(std::span<const std::uint8_t>) { return base::Unavailable(); }
DlrNode SignOnNode(std::span<const std::uint8_t>, const DlrFrame&, std::size_t) { return {}; }
base::Result<std::size_t> BuildNeighborCheckRequest(const DlrOrigin&, std::span<std::uint8_t>) {
  return base::Unavailable();
}
base::Result<std::size_t> BuildNeighborCheckResponse(const DlrOrigin&, std::uint8_t, std::span<std::uint8_t>) {
  return base::Unavailable();
}
base::Result<std::size_t> BuildLinkStatus(const DlrOrigin&, DlrLinkStatus, std::span<std::uint8_t>) {
  return base::Unavailable();
}
base::Result<std::size_t> BuildLearningUpdate(const DlrOrigin&, std::span<std::uint8_t>) {
  return base::Unavailable();
}
base::Result<std::size_t> BuildSignOn(std::span<const std::uint8_t>, const DlrFrame&, const base::MacAddress&,
                                      const DlrNode&, bool, std::span<std::uint8_t>) {
  return base::Unavailable();
}

}  // namespace net
