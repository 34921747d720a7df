#!/usr/bin/env bash
# The command/effect matrix of issue 21 (docs/drive-control.md). DRIVE_MATRIX=eip (default): every control
# path of the EtherNet/IP card (unconnected and class 3 Sets on 0x29/0x2A and 0x64/0x65 FA06/FA07, class 1
# 20, 21, 100, 102 and 105, the web API) in every loss state (the loss by Forward_Close or by timeout), the
# table docs/drive-control-matrix.md. DRIVE_MATRIX=modbus:
# the Modbus card (unit 0 FC06/FC16 of FA06/FA07, IO scanning FC23 on unit 255) in every state of IO
# scanning's loss, the table docs/drive-control-matrix-modbus.md. The generated table must equal the
# committed one (DRIVE_MATRIX_UPDATE=1 rewrites it).
source "$(dirname "$0")/lib.sh"

IT=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$IT${PYTHONPATH:+:$PYTHONPATH}" PYTHONDONTWRITEBYTECODE=1
export CARD_IP CARD_CONTROL
export MATRIX_OUT="${CARD_STATE_DIR:-/tmp}/../drive-control-matrix.$$.md"
case "${DRIVE_MATRIX:-eip}" in
  eip) SCRIPT=drive_control_matrix.py DOC="$ROOT/docs/drive-control-matrix.md" PORT=44818 ;;
  modbus) SCRIPT=drive_control_matrix_modbus.py DOC="$ROOT/docs/drive-control-matrix-modbus.md" PORT=502 ;;
  *) fail "DRIVE_MATRIX=$DRIVE_MATRIX: eip or modbus" ;;
esac

wait_for 10 /usr/bin/python3 -c "import socket; socket.create_connection(('$CARD_IP', $PORT), 1).close()" \
  || fail "port $PORT not open"
/usr/bin/python3 "$IT/$SCRIPT" || fail "matrix"
if [ -n "${DRIVE_MATRIX_UPDATE:-}" ]; then
  cp "$MATRIX_OUT" "$DOC"
  pass "$DOC rewritten"
fi
diff -u "$DOC" "$MATRIX_OUT" || fail "$DOC differs from the matrix run (DRIVE_MATRIX_UPDATE=1 rewrites it)"
pass "drive control matrix ($SCRIPT): every row answered and acted as ${DOC#$ROOT/} says"
