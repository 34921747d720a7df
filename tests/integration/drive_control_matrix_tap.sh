#!/usr/bin/env bash
# The command/effect matrix of issue 21 (docs/drive-control.md, docs/drive-control-matrix.md): every
# control path of the EtherNet/IP card (unconnected and class 3 Sets on 0x29/0x2A and 0x65 FA06/FA07,
# class 1 21 and 100, the web API) in every loss state (none, c100 running, c101 = 0-5 after the owner's
# Forward_Close, owner idle, another owner running), answer and effect in the simulated inverter. The
# generated table must equal the committed docs/drive-control-matrix.md (DRIVE_MATRIX_UPDATE=1 rewrites it).
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CARD_IP CARD_CONTROL
export MATRIX_OUT="${CARD_STATE_DIR:-/tmp}/../drive-control-matrix.$$.md"
DOC="$ROOT/docs/drive-control-matrix.md"

wait_for 10 /usr/bin/python3 -c "import socket; socket.create_connection(('$CARD_IP', 44818), 1).close()" \
  || fail "EtherNet/IP port 44818 not open"
/usr/bin/python3 "$IT/drive_control_matrix.py" || fail "matrix"
if [ -n "${DRIVE_MATRIX_UPDATE:-}" ]; then
  cp "$MATRIX_OUT" "$DOC"
  pass "docs/drive-control-matrix.md rewritten"
fi
diff -u "$DOC" "$MATRIX_OUT" || fail "docs/drive-control-matrix.md differs from the matrix run (DRIVE_MATRIX_UPDATE=1 rewrites it)"
pass "drive control matrix: every row answered and acted as docs/drive-control-matrix.md says"
