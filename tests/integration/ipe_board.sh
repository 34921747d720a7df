#!/usr/bin/env bash
# tools/ipe against the card's Cortex-M4 image on QEMU (docs/commissioning.md "Tests"; CTest
# board.ipe_tool, started by in_netns with c500=1): discover by broadcast on the namespace's subnet finds
# the board with its identity, get reads acc and dec in their unit as the simulated inverter holds them,
# and eds uploads the File object's EDS, equal byte for byte to the one the host build wrote.
source "$(dirname "$0")/lib.sh"

IPE=${IPE:?IPE names the ipe binary}
EDS_DIR=${EDS_DIR:?EDS_DIR names the built EDS directory}
KEEP=$(mktemp -d)
trap 'rm -rf "$KEEP"' EXIT

"$CTL" "$CARD_CONTROL" "set acc 123" >/dev/null || fail "cannot set acc in the simulated inverter"
"$CTL" "$CARD_CONTROL" "set dec 45" >/dev/null || fail "cannot set dec in the simulated inverter"

broadcast="${CARD_IP%.*}.255"
timeout 20 "$IPE" discover --broadcast "$broadcast" --timeout 2500 >"$KEEP/discover" 2>"$KEEP/err" \
  || fail "ipe discover --broadcast $broadcast: $(cat "$KEEP/err")"
grep -q "^$CARD_IP card_ip=$CARD_IP vendor=377 product_code=32000 product_name=\"VF-MB1\" serial=0x[0-9A-F]\{8\} revision=1\.8 status=0x[0-9A-F]\{4\}$" \
  "$KEEP/discover" || fail "discover did not find the board: $(cat "$KEEP/discover")"
pass "discover: ListIdentity to $broadcast finds the board ($(cat "$KEEP/discover"))"

wait_for 20 bash -c "timeout 10 '$IPE' get '$CARD_IP' acc dec >'$KEEP/get' 2>'$KEEP/err'" \
  || fail "ipe get: $(cat "$KEEP/err")"
[ "$(cat "$KEEP/get")" = "acc = 12.3 s
dec = 4.5 s" ] || fail "get acc dec: $(cat "$KEEP/get")"
pass "get acc dec over EtherNet/IP from the board: 12.3 s, 4.5 s as in the inverter"

built="$EDS_DIR/IPE002Z_VF-MB1.eds"
timeout 120 "$IPE" eds "$CARD_IP" "$KEEP/board.eds" 2>"$KEEP/err" || fail "ipe eds: $(cat "$KEEP/err")"
cmp "$built" "$KEEP/board.eds" || fail "the board's EDS differs from the built $built"
pass "eds: the board's File object serves the built VF-MB1 EDS ($(stat -c %s "$built") bytes)"
