#!/usr/bin/env bash
# The card's page in a real browser (docs/web.md "The page"): tests/browser/web_ui.js drives Debian's
# chromium through playwright-core against the host firmware on the loopback port (as the current user):
# login, the drive monitor following the drive (run through Modbus TCP), acc changed with the write
# password and checked in the simulated inverter (control socket), a wrong write password, every menu
# with a screenshot, the passwords changed.
#
#   tests/integration/web_browser.sh           the host firmware (FIRMWARE=..., default build/host)
#
# Screenshots go to WEB_SCREENSHOTS (default build/web-screenshots). c523 = 0: the one-shot Modbus
# writes that start the drive must not count as a lost master 2 s later (docs/modbus.md "Loss
# supervision").
source "$(dirname "$0")/lib.sh"

SHOTS=${WEB_SCREENSHOTS:-$ROOT/build/web-screenshots}
command -v node >/dev/null || fail "node is not installed (tools/setup)"
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || fail "no ${CHROMIUM:-/usr/bin/chromium} (tools/setup installs Debian's chromium)"
[ -d "$ROOT/node_modules/playwright-core" ] || fail "no node_modules/playwright-core (npm ci, or tools/setup)"
rm -f "$SHOTS"/*.png
mkdir -p "$SHOTS"


start_loopback_card 127.0.0.31 --param c523=0
http=$(ready_field http)
modbus=$(ready_field modbus)
[ -n "$http" ] && [ -n "$modbus" ] || fail "no http= or modbus= in the ready line: $CARD_READY"

# The side channels first (Modbus to run the drive, the control socket to read registers back), then the
# web server must answer the API before the browser is worth starting.
node "$ROOT/tests/browser/web_ui.js" --url="http://$http" --drive="modbus:$modbus" --verify="control:$CARD_CONTROL" \
  --channels-only || fail "the side channels (Modbus $modbus, control socket) do not work"
pass "side channels: Modbus TCP at $modbus, control socket"

answer=$(curl -s -m 5 -w ' %{http_code}' "http://$http/api/session" || true)
[[ "$answer" == *'"level"'*' 200' ]] \
  || fail "the firmware does not serve GET /api/session at http://$http (answer: '${answer:-none}')"
pass "the card answers GET /api/session at http://$http"

node "$ROOT/tests/browser/web_ui.js" --url="http://$http" --screenshots="$SHOTS" \
  --drive="modbus:$modbus" --verify="control:$CARD_CONTROL" \
  || fail "web_ui.js against the card at http://$http (screenshots in $SHOTS)"
pass "the page against the host firmware (screenshots in $SHOTS)"
