#!/bin/sh
# board.semihosting_flash: the flash of the board under QEMU (hal/mps2_an386/semihosting_flash.h) keeps
# hal/flash.h's rules and its bytes across a restart of the emulator. Runs the check image
# (ipe002z-board-flash-check.elf) twice on one new file: the first run checks every rule and programs a
# marker, the second finds it. Each run ends QEMU with status 0 only when all its checks passed.
#
# usage: semihosting_flash.sh QEMU IMAGE     (QEMU: qemu-system-arm)
qemu=$1
image=$2
if [ -z "$qemu" ] || ! command -v "$qemu" >/dev/null 2>&1; then
  echo "FAIL: qemu-system-arm not found ('$qemu'); install qemu-system-arm (tools/setup)"
  exit 1
fi
if [ ! -f "$image" ]; then
  echo "FAIL: no flash check image at $image"
  echo "      build it: cmake --preset cortex-m4 && cmake --build --preset cortex-m4"
  exit 1
fi
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
for run in first second; do
  echo "--- run=$run"
  timeout 60 "$qemu" -M mps2-an386 -display none -monitor none -no-reboot -nic none -serial stdio \
    -kernel "$image" \
    -semihosting-config "enable=on,target=native,arg=flash-check,arg=flash=$work/flash.bin,arg=run=$run" \
    2>"$work/qemu.err"
  status=$?
  if [ "$status" -ne 0 ]; then
    echo "FAIL: run=$run ended with status $status"
    cat "$work/qemu.err"
    exit 1
  fi
done
size=$(wc -c <"$work/flash.bin")
if [ "$size" -ne 32768 ]; then
  echo "FAIL: the flash file has $size bytes, expected 32768 (8 sectors of 4096)"
  exit 1
fi
echo "ok: the semihosting flash keeps the NOR rules and its bytes across a restart"
