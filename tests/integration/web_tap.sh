#!/usr/bin/env bash
# The web server over TAP in a namespace (tools/netns, --pcap), driven with curl and Python's standard
# library (docs/web.md "Tests"). Every answer is checked with its status code and JSON contents:
#   (a) the page: gzip, content type, ETag and 304, HEAD, 404/405/406;
#   (b) access: 401 without a session, wrong password 401, login sets the cookie, session level, CSRF
#       refusals (403), read level cannot write (403), elevate with the write password;
#   (c) data: monitor, registers read against the control socket, a write seen in the simulated
#       inverter, refusals mapped to 409/422/404, network, scanners, statistics;
#   (d) passwords: change the read password, the old one is refused, no plain text in the card's store;
#   (e) back-off: 3 free failures, then 1 s waits answered 429 with Retry-After;
#   (f) slots: a 4th connection takes an idle one's slot; with 3 busy connections it gets 503;
#   (g) c554 = 0 (written through the API, communication reset) closes port 80; c554 = 1 and f899 = 1
#       over Modbus open it again;
#   (h) tshark finds no malformed HTTP in the capture.
source "$(dirname "$0")/lib.sh"

BASE="http://$CARD_IP"
JAR=$(mktemp /tmp/ipe-web-jar.XXXXXX)
OUT=$(mktemp /tmp/ipe-web-out.XXXXXX)
trap 'rm -f "$JAR" "$OUT"' EXIT

# http METHOD PATH [BODY [EXTRA CURL ARGS...]]: prints the status code; the body is in $OUT.
http() {
  local method=$1 path=$2 body=${3:-}; shift 3 2>/dev/null || shift $#
  local args=(-s -o "$OUT" -w '%{http_code}' -X "$method" -b "$JAR" -c "$JAR" --max-time 10)
  [ -n "$body" ] && args+=(-H 'Content-Type: application/json' --data-binary "$body")
  curl "${args[@]}" "$@" "$BASE$path"
}
# json EXPR: evaluates a Python expression on the last body (as `j`).
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open('$OUT')); print($1)"; }
expect() {  # expect WHAT GOT WANTED
  [ "$2" = "$3" ] || fail "$1: got '$2', wanted '$3' (body: $(head -c 300 "$OUT"))"
}

wait_for 10 curl -s -o /dev/null --max-time 1 "$BASE/api/session" || fail "port 80 not open"

# (a) The page.
headers=$(curl -s -D - -o "$OUT" --compressed "$BASE/")
grep -q '^HTTP/1.1 200 OK' <<<"$headers" || fail "GET /: $headers"
grep -qi '^Content-Encoding: gzip' <<<"$headers" || fail "GET / not gzip: $headers"
grep -qi '^Content-Type: text/html' <<<"$headers" || fail "GET / type: $headers"
grep -qi '<title>' "$OUT" || fail "GET / is not the page"
etag=$(sed -n 's/^[Ee][Tt]ag: \(.*\)\r$/\1/p' <<<"$headers")
[ -n "$etag" ] || fail "no ETag"
expect "If-None-Match" "$(curl -s -o /dev/null -w '%{http_code}' -H "If-None-Match: $etag" "$BASE/")" 304
expect "HEAD /" "$(curl -s -o /dev/null -w '%{http_code}' -I "$BASE/")" 200
expect "GET /nope" "$(http GET /nope)" 404
expect "DELETE /" "$(http DELETE /)" 405
expect "identity only" "$(curl -s -o /dev/null -w '%{http_code}' -H 'Accept-Encoding: identity' "$BASE/")" 406
pass "page: gzip, text/html, ETag/304, HEAD, 404, 405, 406"

# (b) Access.
expect "monitor without session" "$(http GET /api/monitor)" 401
expect "session none" "$(http GET /api/session)" 200
expect "level" "$(json "j['level'], j['defaults']")" "none True"
expect "wrong password" "$(http POST /api/login '{"password":"nope"}')" 401
expect "wrong password text" "$(json "j['error']")" "wrong password"
expect "login" "$(http POST /api/login '{"password":"USER"}')" 200
expect "login level" "$(json "j['level'], len(j['csrf']), j['defaults']")" "read 32 True"
CSRF=$(json "j['csrf']")
grep -q 'ipe_session' "$JAR" || fail "no session cookie"
expect "session read" "$(http GET /api/session)" 200
expect "level read" "$(json "j['level']")" "read"
expect "write without CSRF" "$(http POST /api/registers '{"number":"0009","value":77}')" 403
expect "write at read level" "$(http POST /api/registers '{"number":"0009","value":77}' -H "X-CSRF-Token: $CSRF")" 403
expect "text" "$(json "j['error']")" "write password required"
expect "elevate wrong" "$(http POST /api/elevate '{"password":"bad"}' -H "X-CSRF-Token: $CSRF")" 401
expect "elevate" "$(http POST /api/elevate '{"password":"USER"}' -H "X-CSRF-Token: $CSRF")" 200
expect "level write" "$(json "j['level']")" "write"
pass "access: 401 without session, wrong password, cookie, CSRF 403, read level 403, elevate"

# (c) Data.
expect "monitor" "$(http GET /api/monitor)" 200
expect "monitor keys" "$(json "sorted(j['registers'])")" "['FC90', 'FC91', 'FD00', 'FD01', 'FE02', 'FE03', 'FE05', 'FE06', 'FE07', 'FE18']"
expect "monitor protocol" "$(json "j['protocol'], j['link']")" "modbus up"
wait_for 5 bash -c "curl -s -b $JAR $BASE/api/monitor | /usr/bin/python3 -c 'import json,sys; sys.exit(json.load(sys.stdin)[\"registers\"][\"FD01\"] is None)'" \
  || fail "monitor values never read"
expect "registers" "$(http GET '/api/registers?numbers=0009,0010,C500')" 200
acc_hex=$("$CTL" "$CARD_CONTROL" "get acc" | sed -n 's/.*(0x\([0-9A-Fa-f]*\)).*/\1/p')
expect "acc" "$(json "'%04X' % j['values'][0]['value'], j['values'][1]['number'], j['values'][2]['value']")" \
  "$(printf '%04X' "0x$acc_hex") 0010 0"
expect "write acc" "$(http POST /api/registers '{"number":"0009","value":77}' -H "X-CSRF-Token: $CSRF")" 200
expect "write answer" "$(json "j['number'], j['value']")" "0009 77"
"$CTL" "$CARD_CONTROL" "get acc" | grep -q '(0x004D)' || fail "acc in the inverter: $("$CTL" "$CARD_CONTROL" "get acc")"
expect "out of range" "$(http POST /api/registers '{"number":"0009","value":65000}' -H "X-CSRF-Token: $CSRF")" 422
expect "read only" "$(http POST /api/registers '{"number":"FD00","value":1}' -H "X-CSRF-Token: $CSRF")" 409
expect "no such" "$(http POST /api/registers '{"number":"000A","value":1}' -H "X-CSRF-Token: $CSRF")" 404
expect "bad numbers" "$(http GET '/api/registers?numbers=9')" 400
expect "bad JSON" "$(http POST /api/registers '{"number":"0009","value":1.5}' -H "X-CSRF-Token: $CSRF")" 400
for call in network modbus-scanner eip-scanner statistics; do
  expect "$call" "$(http GET /api/$call)" 200
done
expect "statistics" "$(json "j['ports'][0]['port'], j['ports'][0]['link'], 'tcp' in j['lwip']")" "L True True"
pass "data: monitor, registers (acc = 77 in the inverter), 409/422/404/400, network, scanners, statistics"

# (d) Passwords: the read password changes; the old one no longer opens a session.
expect "change" "$(http POST /api/passwords '{"which":"read","password":"Secret-1"}' -H "X-CSRF-Token: $CSRF")" 204
expect "too long" "$(http POST /api/passwords "{\"which\":\"read\",\"password\":\"$(printf 'x%.0s' {1..33})\"}" -H "X-CSRF-Token: $CSRF")" 400
expect "old password" "$(http POST /api/login '{"password":"USER"}')" 401
expect "new password" "$(http POST /api/login '{"password":"Secret-1"}')" 200
CSRF=$(json "j['csrf']")
! grep -rqa 'Secret-1' "$CARD_STATE_DIR" || fail "the password is stored in plain text"
pass "passwords: changed, the old one refused, stored only as a hash"

# (e) Back-off: the 3rd failure in a row starts a 1 s wait; an attempt within it is 429 unchecked.
expect "failure 1" "$(http POST /api/login '{"password":"w1"}')" 401  # (d)'s failure was reset by its success
expect "no wait yet" "$(json "j.get('retry_after_ms', 0)")" 0
expect "failure 2" "$(http POST /api/login '{"password":"w2"}')" 401
expect "failure 3" "$(http POST /api/login '{"password":"w3"}')" 401
expect "wait started" "$(json "j['retry_after_ms']")" 1000
code=$(curl -s -o "$OUT" -D "$OUT.h" -w '%{http_code}' -H 'Content-Type: application/json' \
  --data-binary '{"password":"Secret-1"}' "$BASE/api/login")
expect "during the wait" "$code" 429
grep -qi '^Retry-After: 1' "$OUT.h" || fail "no Retry-After: $(cat "$OUT.h")"
rm -f "$OUT.h"
sleep 1.1
expect "after the wait" "$(http POST /api/login '{"password":"Secret-1"}')" 200
CSRF=$(json "j['csrf']")
pass "back-off: 429 with Retry-After during the wait, login after it"

# (f) Slots (web::kMaxHttpClients = 3): 3 idle keep-alive connections, a 4th is served (an idle one is
# closed); 3 busy ones (a partial request each), a 4th gets 503.
/usr/bin/python3 - "$CARD_IP" <<'PY' || fail "slots"
import socket, sys, time
ip = sys.argv[1]
def conn():
    return socket.create_connection((ip, 80), 3)
def get(s):
    s.sendall(b"GET /api/session HTTP/1.1\r\nHost: card\r\n\r\n")
    data = b""
    while b"\r\n\r\n" not in data or not data.endswith(b"}"):
        chunk = s.recv(4096)
        if not chunk: break
        data += chunk
    return data
SLOTS = 3
idle = [conn() for _ in range(SLOTS)]
for s in idle: assert get(s).startswith(b"HTTP/1.1 200"), "idle client not served"
fourth = conn()
assert get(fourth).startswith(b"HTTP/1.1 200"), "4th client not served"
fourth.close()
for s in idle: s.close()
time.sleep(0.3)
busy = [conn() for _ in range(SLOTS)]
for s in busy: s.sendall(b"GET /api/session HTTP/1.1\r\n")  # incomplete: the slot is busy
time.sleep(0.3)
extra = conn()
answer = extra.recv(4096)
assert answer.startswith(b"HTTP/1.1 503 Service Unavailable"), answer
assert b"Retry-After: 1" in answer, answer
for s in busy: s.close()
PY
pass "slots: idle eviction for a 4th client, 503 when all 3 are busy"

# (g) c554 = 0 closes the port after a communication reset; Modbus opens it again.
expect "c554=0" "$(http POST /api/registers '{"number":"C554","value":0}' -H "X-CSRF-Token: $CSRF")" 403
expect "elevate" "$(http POST /api/elevate '{"password":"USER"}' -H "X-CSRF-Token: $CSRF")" 200
expect "c554=0" "$(http POST /api/registers '{"number":"C554","value":0}' -H "X-CSRF-Token: $CSRF")" 200
expect "reset unconfirmed" "$(http POST /api/network/reset '{}' -H "X-CSRF-Token: $CSRF")" 400
expect "reset" "$(http POST /api/network/reset '{"confirm":true}' -H "X-CSRF-Token: $CSRF")" 202
closed() { ! curl -s -o /dev/null --max-time 1 "$BASE/api/session"; }
wait_for 10 closed || fail "port 80 still open with c554 = 0"
timeout 10 mbpoll -m tcp -p 502 -a 1 -0 -r $((0xC554)) -t 4 -1 "$CARD_IP" 1 >/dev/null || fail "mbpoll c554=1"
timeout 10 mbpoll -m tcp -p 502 -a 1 -0 -r $((0x0899)) -t 4 -1 "$CARD_IP" 1 >/dev/null || true  # no reply to f899
wait_for 15 curl -s -o /dev/null --max-time 1 "$BASE/api/session" || fail "port 80 not reopened: $("$CTL" "$CARD_CONTROL" "get c554" config 2>&1 | head -20)"
pass "c554: 0 closes port 80 after the communication reset, 1 opens it again"

# (h) tshark over the capture: no malformed HTTP.
if [ -n "${CARD_PCAP:-}" ] && command -v tshark >/dev/null; then
  sleep 0.5
  bad=$(tshark -r "$CARD_PCAP" -Y '_ws.malformed && tcp.port == 80' 2>/dev/null | wc -l)
  [ "$bad" -eq 0 ] || fail "tshark: $bad malformed frames"
  n=$(tshark -r "$CARD_PCAP" -Y 'http.response' 2>/dev/null | wc -l)
  [ "$n" -gt 20 ] || fail "tshark sees only $n HTTP responses"
  pass "tshark: $n HTTP responses, none malformed"
fi
