#!/bin/sh
# Checks of the card image's symbols (tests/board/CMakeLists.txt):
#   heap   no malloc, free, realloc, calloc or _sbrk: the firmware allocates nothing after start-up
#          (DEVELOPERS.md); on the board newlib's malloc would need _sbrk, which the image deliberately
#          lacks (hal/mps2_an386/runtime.cc), so any of these means something in the image allocates.
#   stdio  none of newlib's stdio (printf family, FILE streams): it allocates its buffers and stream
#          table, and the board's text goes to its console UART without it.
#
# usage: check_image.sh heap|stdio NM IMAGE
#   NM: arm-none-eabi-nm; IMAGE: build/cortex-m4/bin/ipe002z-board.elf
# A missing image or nm fails the test: build the image first (cmake --preset cortex-m4 &&
# cmake --build --preset cortex-m4) or point IPE_BOARD_IMAGE at it.
what=$1
nm_tool=$2
image=$3

case "$what" in
  heap) pattern='^(malloc|_malloc_r|calloc|_calloc_r|realloc|_realloc_r|free|_free_r|_sbrk|_sbrk_r)$' ;;
  stdio) pattern='^(printf|_printf_r|sprintf|_sprintf_r|snprintf|_snprintf_r|vsnprintf|_vsnprintf_r|iprintf|siprintf|sniprintf|_svfprintf_r|_svfiprintf_r|_vfprintf_r|_vfiprintf_r|puts|fputs|fwrite|_fwrite_r|fopen|__sinit|__sfp|stdout|stderr)$' ;;
  *) echo "FAIL: unknown check '$what' (heap or stdio)"; exit 1 ;;
esac

if [ -z "$nm_tool" ] || ! command -v "$nm_tool" >/dev/null 2>&1; then
  echo "FAIL: arm-none-eabi-nm not found ('$nm_tool'); install gcc-arm-none-eabi (tools/setup)"
  exit 1
fi
if [ ! -f "$image" ]; then
  echo "FAIL: no board image at $image"
  echo "      build it: cmake --preset cortex-m4 && cmake --build --preset cortex-m4"
  echo "      (or configure the host build with -DIPE_BOARD_IMAGE=/path/to/ipe002z-board.elf)"
  exit 1
fi
symbols=$("$nm_tool" "$image") || { echo "FAIL: $nm_tool cannot read $image"; exit 1; }
if [ -z "$symbols" ]; then
  echo "FAIL: $image has no symbols (stripped?): cannot check it"
  exit 1
fi
found=$(printf '%s\n' "$symbols" | awk -v pattern="$pattern" '$NF ~ pattern { print $NF }' | sort -u)
if [ -n "$found" ]; then
  echo "FAIL: $image contains $what symbols:"
  printf '  %s\n' $found
  echo "      the link map (ipe002z-board.map, \"Archive member included\") says which object pulled them in"
  exit 1
fi
echo "ok: $image has no $what symbols"
