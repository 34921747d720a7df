# Cross toolchain for the card's Cortex-M4F image: Debian's gcc-arm-none-eabi 12 with newlib-nano
# (libnewlib-arm-none-eabi) and libstdc++-arm-none-eabi-newlib. Used by the cortex-m4 preset
# (CMakePresets.json); docs/board.md explains the flags.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_OBJCOPY arm-none-eabi-objcopy CACHE FILEPATH "objcopy of the cross toolchain")
set(CMAKE_SIZE arm-none-eabi-size CACHE FILEPATH "size of the cross toolchain")
set(CMAKE_NM arm-none-eabi-nm CACHE FILEPATH "nm of the cross toolchain")
# A bare-metal compiler cannot link a test program without a startup file and linker script.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The core: Cortex-M4 with its single-precision FPU, hard-float calling convention.
set(IPE_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
# Every source of the image is device code: no exceptions, no RTTI, one section per function and object
# (so --gc-sections drops what nothing uses), and a stack-usage record per function (.su) plus the call
# graph (.ci) next to each object file, from which the worst-case stack depth is computed.
set(IPE_COMMON_FLAGS "${IPE_CPU_FLAGS} --specs=nano.specs -g -ffunction-sections -fdata-sections -fstack-usage -fcallgraph-info=su")
set(CMAKE_C_FLAGS_INIT "${IPE_COMMON_FLAGS}")
# -Wno-psabi: GCC's note that the parameter-passing ABI of some types changed in GCC 7 (std::pair,
# std::optional); the whole image is built by one compiler, so it cannot matter.
# -fno-threadsafe-statics: one thread, no RTOS; no __cxa_guard_* calls.
set(CMAKE_CXX_FLAGS_INIT "${IPE_COMMON_FLAGS} -fno-exceptions -fno-rtti -fno-threadsafe-statics -Wno-psabi")
set(CMAKE_ASM_FLAGS_INIT "${IPE_CPU_FLAGS}")
# No start files: the board brings its own vector table and reset handler (hal/mps2_an386/startup.cc).
# (--specs=nano.specs reaches the link through the compile flags, which CMake passes to it too.)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-nostartfiles -Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
